#include "core/progress.h"

#include <algorithm>
#include <limits>

namespace tissuemesh {

Progress::Stage::Stage(Progress& owner, std::string name)
    : owner_(owner), name_(std::move(name)), start_(std::chrono::steady_clock::now()) {
  if (owner_.sink_) owner_.sink_(Event::Begin, name_, "", 0.0, std::numeric_limits<double>::quiet_NaN());
}

Progress::Stage::~Stage() {
  const double s = elapsed();
  owner_.timings_.push_back({name_, s});
  if (owner_.sink_) owner_.sink_(Event::End, name_, "", s, std::numeric_limits<double>::quiet_NaN());
}

void Progress::Stage::note(const std::string& text) {
  if (owner_.sink_) owner_.sink_(Event::Note, name_, text, elapsed(), std::numeric_limits<double>::quiet_NaN());
}

void Progress::Stage::note(const std::string& text, double fraction) {
  if (owner_.sink_) owner_.sink_(Event::Note, name_, text, elapsed(), std::clamp(fraction, 0.0, 1.0));
}

double Progress::Stage::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

}  // namespace tissuemesh
