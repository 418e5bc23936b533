#include "core/memory_budget.h"

#include "core/errors.h"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

namespace tissuemesh {
namespace {

constexpr std::uint64_t kUnlimited = std::numeric_limits<std::uint64_t>::max();

// "MemAvailable:   19876543 kB" -> bytes; kUnlimited when absent (old kernels, no /proc).
std::uint64_t meminfo_available() {
  std::ifstream in("/proc/meminfo");
  std::string key, unit;
  std::uint64_t kib = 0;
  while (in >> key >> kib >> unit) {
    if (key == "MemAvailable:") return kib * 1024;
  }
  return kUnlimited;
}

// A cgroup v2 file holding a byte count or "max".
std::uint64_t cgroup_value(const char* name) {
  std::ifstream in(std::string("/sys/fs/cgroup/") + name);
  std::string text;
  if (!(in >> text) || text == "max") return kUnlimited;
  try {
    return std::stoull(text);
  } catch (const std::exception&) {
    return kUnlimited;
  }
}

std::uint64_t cgroup_available() {
  const std::uint64_t max = cgroup_value("memory.max");
  if (max == kUnlimited) return kUnlimited;
  const std::uint64_t current = cgroup_value("memory.current");
  return current == kUnlimited ? max : max - std::min(max, current);
}

std::uint64_t address_space_limit() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return kUnlimited;
  return static_cast<std::uint64_t>(limit.rlim_cur);
}

std::uint64_t user_cap() {
  const char* text = std::getenv("TISSUEMESH_MEMORY_MB");
  if (text == nullptr || *text == '\0') return kUnlimited;
  char* end = nullptr;
  const unsigned long long mib = std::strtoull(text, &end, 10);
  if (*end != '\0' || mib == 0) {
    throw InputError(std::string("TISSUEMESH_MEMORY_MB='") + text +
                     "' is not a positive whole number of MiB");
  }
  return mib > kUnlimited / (1024 * 1024) ? kUnlimited : mib * 1024 * 1024;
}

}  // namespace

std::uint64_t available_memory_bytes() {
  return std::min({meminfo_available(), cgroup_available(), address_space_limit(), user_cap()});
}

std::uint64_t checked_multiply(std::uint64_t a, std::uint64_t b, const std::string& what) {
  std::uint64_t product = 0;
  if (__builtin_mul_overflow(a, b, &product)) {
    throw InputError(what + ": " + std::to_string(a) + " x " + std::to_string(b) +
                     " overflows 64 bits");
  }
  return product;
}

std::string format_bytes(std::uint64_t bytes) {
  static const char* const kUnits[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  double value = static_cast<double>(bytes);
  int unit = 0;
  while (value >= 1024.0 && unit < 6) value /= 1024.0, ++unit;
  char text[32];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.1f %s", value, kUnits[unit]);
  return text;
}

void require_memory(std::uint64_t needed_bytes, const std::string& what,
                    const std::string& estimate) {
  const std::uint64_t available = available_memory_bytes();
  if (needed_bytes <= available) return;
  throw InputError(what + " needs about " + format_bytes(needed_bytes) + " (" + estimate +
                   "), more than the " + format_bytes(available) +
                   " available to this run (free memory, ulimit -v, cgroup limit, "
                   "TISSUEMESH_MEMORY_MB)");
}

}  // namespace tissuemesh
