// Ctrl-C (SIGINT), SIGTERM (kill, a batch system's time limit) and SIGHUP (a closed terminal)
// must not leave partial output behind or end the program by a signal.
//
// install_interrupt_cleanup() installs a handler for these signals that only writes the signal's
// number into a pipe (all a handler may safely do, in whichever thread it runs: libraries such as
// OpenBLAS start threads before main), and starts one thread that waits on that pipe. On a signal
// that thread removes every uncommitted output staging folder (core/output_dir.h,
// OutputDir::abandon_all), prints "tissuemesh: interrupted by SIGINT; no output written" and ends
// the process with exit code 1 (a run that did not complete; exit 2 is kept for bad input).
// Call it first thing in main().
#pragma once

namespace tissuemesh::app {

void install_interrupt_cleanup();

}  // namespace tissuemesh::app
