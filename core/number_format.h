// One number printed with a printf format, for messages, progress notes and reports.
#pragma once

#include <string>

namespace tissuemesh {

/// `value` printed with a printf format for one double, e.g. format_double("%.2f", 1.234) = "1.23".
std::string format_double(const char* printf_format, double value);

}  // namespace tissuemesh
