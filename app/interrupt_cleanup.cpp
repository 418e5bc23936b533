#include "app/interrupt_cleanup.h"

#include "core/output_dir.h"

#include <fcntl.h>
#include <signal.h>
#include <string.h>
#include <unistd.h>

#include <string>
#include <thread>

namespace tissuemesh::app {
namespace {

int signal_pipe[2] = {-1, -1};

extern "C" void on_termination_signal(int signal) {
  const unsigned char number = static_cast<unsigned char>(signal);
  [[maybe_unused]] const ssize_t written = ::write(signal_pipe[1], &number, 1);
}

// The waiting thread runs ordinary code, not a handler: it may take the output registry's lock
// and remove folders.
void wait_for_termination() {
  unsigned char number = 0;
  while (::read(signal_pipe[0], &number, 1) != 1) {
  }
  OutputDir::abandon_all();
  const char* name = sigabbrev_np(number);
  const std::string text = std::string("tissuemesh: interrupted by SIG") + (name ? name : "?") +
                           "; no output written\n";
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, text.data(), text.size());
  ::_exit(1);
}

}  // namespace

void install_interrupt_cleanup() {
  if (::pipe2(signal_pipe, O_CLOEXEC) != 0) return;  // without a pipe the default actions remain
  std::thread(wait_for_termination).detach();
  struct sigaction action {};
  action.sa_handler = on_termination_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(signal, &action, nullptr);
}

}  // namespace tissuemesh::app
