// Refusing up front work that cannot fit in memory, instead of being killed by the OOM killer
// half-way through (the user then gets no message and no output).
//
// The memory a run may use is the least of: the kernel's MemAvailable (/proc/meminfo), the
// process's address-space limit (RLIMIT_AS, `ulimit -v`), the cgroup's memory.max less its
// memory.current (a container or a Slurm job), and TISSUEMESH_MEMORY_MB when set (a user's own
// cap, e.g. for jobs that share a node). Unknown sources are ignored.
#pragma once

#include <cstdint>
#include <string>

namespace tissuemesh {

/// Bytes this process may still allocate (see above); UINT64_MAX when nothing limits it.
std::uint64_t available_memory_bytes();

/// a * b, or throws InputError "<what>: <a> x <b> overflows 64 bits" (header sizes whose product
/// does not fit, before anything is allocated from it).
std::uint64_t checked_multiply(std::uint64_t a, std::uint64_t b, const std::string& what);

/// Throws InputError when `needed_bytes` exceeds available_memory_bytes(): "<what> needs about
/// <needed> (<estimate>), more than the <available> this machine has available". `estimate` says
/// what the number is made of (voxels, expected tets) so that the user can see what to change.
void require_memory(std::uint64_t needed_bytes, const std::string& what, const std::string& estimate);

/// "1.5 GiB", "300 MiB", "12 KiB": a byte count for messages.
std::string format_bytes(std::uint64_t bytes);

}  // namespace tissuemesh
