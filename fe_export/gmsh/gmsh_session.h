// gmsh_sdk::initialize / finalize around one use of the Gmsh SDK, also when something throws.
// The SDK is global state: one session at a time, not thread-safe. The first session of a process
// loads the SDK (fe_export/gmsh/gmsh_sdk.h).
#pragma once

#include "fe_export/gmsh/gmsh_sdk.h"

namespace tissuemesh {

class GmshSession {
 public:
  GmshSession() {
    gmsh_sdk::initialize();  // no user config files: results must not depend on them
    gmsh_sdk::set_number("General.Terminal", 0);
  }
  ~GmshSession() {
    try {
      gmsh_sdk::finalize();
    } catch (...) {
    }
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

}  // namespace tissuemesh
