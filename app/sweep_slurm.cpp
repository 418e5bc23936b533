#include "app/sweep_slurm.h"

#include "app/cli_support.h"
#include "core/errors.h"

#include <array>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>

#include <unistd.h>

namespace fs = std::filesystem;

namespace tissuemesh::app {

namespace {

/// `s` in single quotes for a POSIX shell.
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// Runs `command`; returns its standard output (its standard error is appended when it fails).
std::string run_capture(const std::string& command, int& status) {
  std::string out;
  const fs::path err = fs::temp_directory_path() / ("tissuemesh-sbatch-" + std::to_string(::getpid()) + ".err");
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((command + " 2>" + quoted(err.string())).c_str(), "r"), pclose);
  if (!pipe) {
    status = -1;
    return out;
  }
  std::array<char, 256> buf;
  while (fgets(buf.data(), buf.size(), pipe.get())) out += buf.data();
  status = pclose(pipe.release());
  if (status != 0) {
    std::ifstream e(err);
    out += std::string(std::istreambuf_iterator<char>(e), std::istreambuf_iterator<char>());
  }
  std::error_code ec;
  fs::remove(err, ec);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

/// The job id of `sbatch --parsable`: the last line's digits before any ';cluster'.
std::string job_id(const std::string& out, const fs::path& script) {
  const std::string last = out.substr(out.find_last_of('\n') == std::string::npos ? 0 : out.find_last_of('\n') + 1);
  const std::string id = last.substr(0, last.find(';'));
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    throw InputError("sbatch gave no job id for " + script.string() + ": " + out);
  return id;
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
  const std::string array_id = job_id(array, scripts.array);
  const std::string merge =
      run_capture("sbatch --parsable --dependency=afterok:" + array_id + " " + quoted(scripts.merge.string()), status);
  if (status != 0) throw InputError("sbatch refused " + scripts.merge.string() + ": " + merge);
  return "array job " + array_id + ", merge job " + job_id(merge, scripts.merge);
}

}  // namespace tissuemesh::app
