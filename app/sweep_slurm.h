// A sweep on a Slurm cluster (docs/sweeps.md, "Beyond one machine"): a job array of N shards, each
// `tissuemesh sweep ... --shard $SLURM_ARRAY_TASK_ID/N`, and a merge job that runs after the whole
// array succeeded (`--dependency=afterok`), `tissuemesh sweep ... --merge`. DIR must be on a file
// system every node sees. Logs go to DIR/slurm/.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace tissuemesh::app {

struct SlurmScripts {
  std::filesystem::path array, merge;
};

/// Writes DIR/sweep.sbatch and DIR/merge.sbatch running this executable (/proc/self/exe) with
/// `sweep_args` (the sweep command's arguments, absolute paths) plus --shard / --merge.
/// OutputError naming the file when it cannot be written.
SlurmScripts write_slurm_scripts(const std::filesystem::path& dir, const std::vector<std::string>& sweep_args, int shards);

/// Submits the array, then the merge with a dependency on it, with `sbatch --parsable`; returns
/// "array job <id>, merge job <id>". InputError when sbatch is missing or refuses a script (its
/// message included).
std::string submit_slurm(const SlurmScripts& scripts);

}  // namespace tissuemesh::app
