// gmsh::initialize / gmsh::finalize around one use of the Gmsh SDK, also when something throws.
// The SDK is global state: one session at a time, not thread-safe.
#pragma once

#include <gmsh.h>

namespace tissuemesh {

class GmshSession {
 public:
  GmshSession() {
    gmsh::initialize(0, nullptr, false);  // no user config files: results must not depend on them
    gmsh::option::setNumber("General.Terminal", 0);
  }
  ~GmshSession() {
    try {
      gmsh::finalize();
    } catch (...) {
    }
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

}  // namespace tissuemesh
