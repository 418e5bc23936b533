#include "solver_check/calculix_run.h"

#include "core/errors.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace tissuemesh {

namespace fs = std::filesystem;

namespace {

bool is_executable_file(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

/// `name` itself when it holds a '/', else the first executable `name` in $PATH; "" if none.
std::string resolve(const std::string& name) {
  if (name.find('/') != std::string::npos) return is_executable_file(name) ? name : "";
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const std::string candidate = (dir.empty() ? std::string(".") : dir) + "/" + name;
    if (is_executable_file(candidate)) return candidate;
  }
  return "";
}

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

std::string find_calculix() {
  // An explicit $TISSUEMESH_CCX wins: when it does not name an executable, report "not found"
  // rather than silently running another ccx.
  if (const char* env = std::getenv("TISSUEMESH_CCX"); env && *env) return resolve(env);
  return resolve("ccx");
}

CalculixRun run_calculix(const std::string& inp_path, int threads) {
  const fs::path inp = fs::absolute(inp_path);
  if (inp.extension() != ".inp") throw InputError("'" + inp_path + "': a CalculiX input deck must end in .inp");
  if (!fs::is_regular_file(inp)) throw InputError("'" + inp_path + "': no such input deck");
  const std::string ccx = find_calculix();
  if (ccx.empty())
    throw SolverError("cannot run CalculiX: no ccx executable found (set TISSUEMESH_CCX or put ccx on PATH)");
  const fs::path dir = inp.parent_path();
  const std::string job = inp.stem().string();
  const std::string log_path = (dir / (job + ".log")).string();
  const std::string threads_text = std::to_string(threads < 1 ? 1 : threads);

  // The child's environment and arguments are built before fork (only async-signal-safe calls
  // between fork and exec).
  std::vector<std::string> env_text;
  for (char** e = environ; e && *e; ++e)
    if (std::strncmp(*e, "OMP_NUM_THREADS=", 16) != 0) env_text.emplace_back(*e);
  env_text.push_back("OMP_NUM_THREADS=" + threads_text);
  std::vector<char*> envp;
  for (std::string& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);
  std::string arg0 = ccx, arg1 = "-i", arg2 = job;
  char* argv[] = {arg0.data(), arg1.data(), arg2.data(), nullptr};

  // The child reports a failed chdir/open/exec (stage, errno) through a close-on-exec pipe:
  // nothing arrives when exec succeeds.
  int report[2];
  if (::pipe2(report, O_CLOEXEC) != 0) throw SolverError(std::string("cannot run CalculiX: pipe: ") + std::strerror(errno));
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(report[0]);
    ::close(report[1]);
    throw SolverError(std::string("cannot run CalculiX: fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    auto fail = [&](int stage) {
      const int info[2] = {stage, errno};
      [[maybe_unused]] ssize_t w = ::write(report[1], info, sizeof info);
      ::_exit(127);
    };
    ::close(report[0]);
    if (::chdir(dir.c_str()) != 0) fail(1);
    const int log = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (log < 0) fail(2);
    if (::dup2(log, STDOUT_FILENO) < 0 || ::dup2(log, STDERR_FILENO) < 0) fail(2);
    const int null_in = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    if (null_in >= 0) ::dup2(null_in, STDIN_FILENO);
    ::execve(argv[0], argv, envp.data());
    fail(3);
  }
  ::close(report[1]);
  int info[2] = {0, 0};
  ssize_t got;
  do got = ::read(report[0], info, sizeof info);
  while (got < 0 && errno == EINTR);
  ::close(report[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  const auto stop = std::chrono::steady_clock::now();
  if (got == static_cast<ssize_t>(sizeof info)) {
    const std::string what = info[0] == 1   ? "cannot enter folder '" + dir.string() + "'"
                             : info[0] == 2 ? "cannot write log '" + log_path + "'"
                                            : "cannot execute '" + ccx + "'";
    throw SolverError("cannot run CalculiX: " + what + ": " + std::strerror(info[1]));
  }

  CalculixRun run;
  run.seconds = std::chrono::duration<double>(stop - start).count();
  if (WIFEXITED(status))
    run.exit_code = WEXITSTATUS(status);
  else if (WIFSIGNALED(status))
    run.exit_code = 128 + WTERMSIG(status);  // the shell's convention
  run.log = read_all(log_path);
  run.dat_path = (dir / (job + ".dat")).string();
  return run;
}

}  // namespace tissuemesh
