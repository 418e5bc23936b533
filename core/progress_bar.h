// The live progress bar of an interactive terminal: one line redrawn in place, e.g.
//   "  [##########..........]  50%  12.3 s, ~12 s left  round 3/6: 41,200 vertices ..."
// The program draws it when stdout is a terminal and prints plain note lines otherwise.
#pragma once

#include <string>

namespace tissuemesh {

/// The bar line for `fraction` (in [0, 1]) of a stage done after `seconds`, with `text` after it,
/// cut to `width` characters. The time left is the linear estimate seconds * (1 - f) / f, shown
/// from 1 % on.
std::string progress_bar_line(double fraction, double seconds, const std::string& text, int width);

}  // namespace tissuemesh
