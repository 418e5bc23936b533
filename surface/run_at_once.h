// run_at_once: two independent, coarse pieces of work on two OpenMP threads (SurfaceProjection's
// trees, the remesher's partitioned sweeps). `first` and `second` must not write anything the
// other reads or writes; then the outcome is the one of calling them one after the other (which
// is what `threads` 1 does). An exception never leaves the OpenMP region
// (that would call std::terminate): each is caught on its thread and rethrown on the caller's after
// both finished, `first`'s when both threw, so callers see the errors serial code would raise.
// Include it only from translation units compiled with OpenMP (without, the two run one after the
// other).
//
// Not for fine-grained work (pieces of a few microseconds, such as one collapse's checks): while
// other processes keep the cores busy, each split waits for the scheduler, and the split code runs
// several times slower than serial code.
#pragma once

#include <exception>

namespace tissuemesh {

template <class First, class Second>
void run_at_once(First&& first, Second&& second, int threads = 2) {
  std::exception_ptr first_error, second_error;
#pragma omp parallel sections num_threads(threads)
  {
#pragma omp section
    {
      try {
        first();
      } catch (...) {
        first_error = std::current_exception();
      }
    }
#pragma omp section
    {
      try {
        second();
      } catch (...) {
        second_error = std::current_exception();
      }
    }
  }
  if (first_error) std::rethrow_exception(first_error);
  if (second_error) std::rethrow_exception(second_error);
}

}  // namespace tissuemesh
