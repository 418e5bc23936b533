// Machine resources and build facts recorded in every run's JSON record.
#pragma once

#include <map>
#include <string>

namespace tissuemesh {

/// Peak resident memory of this process so far, in MiB (getrusage).
double peak_memory_mib();

/// Versions of tissuemesh and of the libraries core is built with: {"tissuemesh": "0.1.0",
/// "Eigen": ..., "VTK": ..., "yaml-cpp": ...}. The mesher adds CGAL's (mesher_versions()).
std::map<std::string, std::string> library_versions();

}  // namespace tissuemesh
