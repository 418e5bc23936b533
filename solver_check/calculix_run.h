// Running CalculiX (ccx) on an input deck: the third-party solver the tests and `check` use.
#pragma once

#include <string>

namespace tissuemesh {

struct CalculixRun {
  int exit_code = -1;
  double seconds = 0.0;
  std::string log;          ///< ccx's stdout + stderr
  std::string dat_path;     ///< <dir>/<job>.dat
};

/// Path of the ccx executable: $TISSUEMESH_CCX, else `ccx` on PATH; empty when not found.
std::string find_calculix();

/// Runs `ccx -i <job>` in the folder of `inp_path` (job = file name without .inp) with
/// OMP_NUM_THREADS = `threads`. Throws SolverError when ccx cannot be started.
CalculixRun run_calculix(const std::string& inp_path, int threads = 2);

}  // namespace tissuemesh
