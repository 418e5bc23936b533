#include "core/progress_bar.h"

#include "core/number_format.h"

#include <algorithm>
#include <cmath>

namespace tissuemesh {

std::string progress_bar_line(double fraction, double seconds, const std::string& text, int width) {
  constexpr int kBar = 24;
  const double f = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0);
  const int filled = static_cast<int>(std::lround(f * kBar));
  std::string line = "  [" + std::string(static_cast<std::size_t>(filled), '#') +
                     std::string(static_cast<std::size_t>(kBar - filled), '.') + "] " +
                     format_double("%3.0f", 100.0 * f) + "%  " + format_double("%.1f", seconds) + " s";
  if (f >= 0.01 && f < 1.0) line += ", ~" + format_double("%.0f", seconds * (1.0 - f) / f) + " s left";
  line += "  " + text;
  if (width > 4 && line.size() > static_cast<std::size_t>(width - 1))
    line = line.substr(0, static_cast<std::size_t>(width - 4)) + "...";
  return line;
}

}  // namespace tissuemesh
