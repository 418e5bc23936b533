// Bounds checks of generator parameters (phantom, fragmented breast, folded layers): each failure
// is an InputError "<where(key)>: <rule>", where `where` names the file and key.
#pragma once

#include "core/errors.h"

#include <functional>
#include <sstream>
#include <string>

namespace tissuemesh {

class ParamBounds {
 public:
  explicit ParamBounds(const std::function<std::string(const char*)>& where) : where_(where) {}
  /// Throws InputError naming `key` with `rule`.
  [[noreturn]] void fail(const char* key, const std::string& rule) const { throw InputError(where_(key) + ": " + rule); }
  /// Throws unless lo <= v <= hi (NaN fails).
  void range(const char* key, double v, double lo, double hi) const {
    if (v >= lo && v <= hi) return;
    std::ostringstream msg;
    msg << "must be in [" << lo << ", " << hi << "], got " << v;
    fail(key, msg.str());
  }

 private:
  const std::function<std::string(const char*)>& where_;
};

}  // namespace tissuemesh
