// Why fork and not a thread: a fault inside a library cannot be caught in the process it happens
// in. Why the child's stdio streams are replaced rather than redirected: another thread of the
// parent may hold the lock of stdout at the moment of the fork, and that lock would never be
// released in the child; fresh streams on /dev/null have locks of their own. The child leaves by
// _exit, so neither atexit handlers nor destructors of the parent's copies run there.
#include "core/isolated_run.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace tissuemesh {
namespace {

constexpr char kResult = 'R', kException = 'E';

bool write_all(int fd, const char* data, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, data, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    data += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

/// Runs `work` here; the tag tells a result from an exception's message.
char run_here(const std::function<void(std::string&)>& work, std::string& bytes) {
  try {
    work(bytes);
    return kResult;
  } catch (const std::exception& e) {
    bytes = e.what();
  } catch (...) {
    bytes = "an exception that is not a std::exception";
  }
  return kException;
}

/// When no child can be started: `work` here, without protection.
IsolatedRun run_unprotected(const std::function<void(std::string&)>& work) {
  IsolatedRun run;
  run.ok = run_here(work, run.bytes) == kResult;
  if (!run.ok) run.failure.swap(run.bytes);
  return run;
}

}  // namespace

IsolatedRun run_isolated(const std::function<void(std::string& bytes)>& work) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) return run_unprotected(work);
  std::fflush(nullptr);  // nothing buffered here is written twice
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return run_unprotected(work);
  }
  if (pid == 0) {
    ::close(fds[0]);
    const int null_fd = ::open("/dev/null", O_WRONLY);
    if (null_fd >= 0) {
      ::dup2(null_fd, STDOUT_FILENO);
      ::dup2(null_fd, STDERR_FILENO);
    }
    if (FILE* out = ::fdopen(::dup(STDOUT_FILENO), "w")) stdout = out;
    if (FILE* err = ::fdopen(::dup(STDERR_FILENO), "w")) stderr = err;
    std::string bytes;
    const char tag = run_here(work, bytes);
    const bool sent = write_all(fds[1], &tag, 1) && write_all(fds[1], bytes.data(), bytes.size());
    ::_exit(sent ? 0 : 1);
  }
  ::close(fds[1]);
  IsolatedRun run;
  std::string received;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t got = ::read(fds[0], buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    received.append(buffer, static_cast<std::size_t>(got));
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  const bool exited_cleanly = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (exited_cleanly && !received.empty() && received[0] == kResult) {
    run.ok = true;
    run.bytes = received.substr(1);
  } else if (exited_cleanly && !received.empty() && received[0] == kException) {
    run.failure = received.substr(1);
  } else {
    run.crashed = true;
    if (WIFSIGNALED(status)) {
      const int sig = WTERMSIG(status);
      const char* name = ::strsignal(sig);
      run.failure = "killed by signal " + std::to_string(sig) + (name ? std::string(" (") + name + ")" : std::string());
    } else {
      run.failure = WIFEXITED(status) ? "ended with exit status " + std::to_string(WEXITSTATUS(status)) + " before its result was complete"
                                      : "ended without a result";
    }
  }
  return run;
}

}  // namespace tissuemesh
