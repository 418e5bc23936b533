#include "core/number_format.h"

#include <cstdio>

namespace tissuemesh {

std::string format_double(const char* printf_format, double value) {
  char buf[128];
  std::snprintf(buf, sizeof buf, printf_format, value);
  return buf;
}

}  // namespace tissuemesh
