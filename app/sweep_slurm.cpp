#include "app/sweep_slurm.h"

#include "app/cli_support.h"
#include "core/errors.h"

#include <array>
#include <cstdio>
#include <memory>

namespace fs = std::filesystem;

namespace tissuemesh::app {

namespace {

/// `s` in single quotes for a POSIX shell.
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string run_capture(const std::string& command, int& status) {
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((command + " 2>&1").c_str(), "r"), pclose);
  if (!pipe) {
    status = -1;
    return out;
  }
  std::array<char, 256> buf;
  while (fgets(buf.data(), buf.size(), pipe.get())) out += buf.data();
  status = pclose(pipe.release());
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

}  // namespace

SlurmScripts write_slurm_scripts(const fs::path& dir, const std::vector<std::string>& sweep_args, int shards) {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw OutputError("cannot find this program's path (/proc/self/exe): " + ec.message());
  const fs::path logs = fs::absolute(dir) / "slurm";
  fs::create_directories(logs, ec);
  if (ec) throw OutputError(logs.string() + ": cannot create: " + ec.message());
  std::string command = quoted(exe.string());
  for (const std::string& a : sweep_args) command += " " + quoted(a);
  SlurmScripts s{fs::absolute(dir) / "sweep.sbatch", fs::absolute(dir) / "merge.sbatch"};
  write_text_file(s.array, "#!/bin/bash\n"
                           "#SBATCH --job-name=tissuemesh-sweep\n"
                           "#SBATCH --array=1-" + std::to_string(shards) + "\n"
                           "#SBATCH --ntasks=1\n"
                           "#SBATCH --cpus-per-task=1\n"
                           "#SBATCH --output=" + (logs / "shard-%a.log").string() + "\n"
                           "# One shard of the sweep per array task; the merge job writes the results.\n"
                           "exec " + command + " --shard \"${SLURM_ARRAY_TASK_ID}/" + std::to_string(shards) +
                           "\" --threads \"${SLURM_CPUS_PER_TASK:-1}\"\n");
  write_text_file(s.merge, "#!/bin/bash\n"
                           "#SBATCH --job-name=tissuemesh-sweep-merge\n"
                           "#SBATCH --ntasks=1\n"
                           "#SBATCH --output=" + (logs / "merge.log").string() + "\n"
                           "# After every shard of sweep.sbatch: results.csv, summary, plots.\n"
                           "exec " + command + " --merge\n");
  return s;
}

std::string submit_slurm(const SlurmScripts& scripts) {
  int status = 0;
  const std::string array = run_capture("sbatch --parsable " + quoted(scripts.array.string()), status);
  if (status != 0) throw InputError("sbatch refused " + scripts.array.string() + ": " + array);
  const std::string array_id = array.substr(0, array.find(';'));
  const std::string merge =
      run_capture("sbatch --parsable --dependency=afterok:" + array_id + " " + quoted(scripts.merge.string()), status);
  if (status != 0) throw InputError("sbatch refused " + scripts.merge.string() + ": " + merge);
  return "array job " + array_id + ", merge job " + merge.substr(0, merge.find(';'));
}

}  // namespace tissuemesh::app
