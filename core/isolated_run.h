// Runs a computation in a child process (POSIX fork), so that a crash of third-party code inside
// it (a memory fault, an abort) ends the child only and comes back to the caller as a failure it
// can report, instead of ending the program. TetGen 1.5 is the case in point: when it stops on an
// input it cannot recover (nearly coplanar facets within its tolerance), it throws from deep
// inside its mesh, and the mesh's destructor may then fault while the exception unwinds.
//
// Contract: `work` runs in the child on a copy of the caller's memory (copy on write) and writes
// its whole result into the string it is given; nothing it changes reaches the caller but those
// bytes. It must not start threads or use OpenMP (only the forking thread exists in the child),
// and what it prints is discarded (the child's stdout and stderr are /dev/null). An exception it
// throws comes back as the failure's message. When the child cannot be started (fork fails:
// no processes or memory left), `work` runs in this process instead, unprotected. Never throws
// on the child's account; throws std::bad_alloc only if the result cannot be stored.
#pragma once

#include <functional>
#include <string>

namespace tissuemesh {

struct IsolatedRun {
  bool ok = false;      ///< `work` returned normally
  std::string bytes;    ///< what it wrote, when ok
  std::string failure;  ///< when not ok: the exception's message, or how the child ended ("killed by signal 11 (Segmentation fault)")
  bool crashed = false; ///< the child ended by a signal or without a result (not by an exception of `work`)
};

IsolatedRun run_isolated(const std::function<void(std::string& bytes)>& work);

}  // namespace tissuemesh
