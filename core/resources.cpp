#include "core/resources.h"

#include <sys/resource.h>

#include <Eigen/Core>
#include <vtkVersion.h>


#ifndef TISSUEMESH_VERSION
#error "TISSUEMESH_VERSION must be defined by the build"
#endif

namespace tissuemesh {

double peak_memory_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: ru_maxrss in KiB
}

std::map<std::string, std::string> library_versions() {
  std::map<std::string, std::string> v;
  v["tissuemesh"] = TISSUEMESH_VERSION;
  v["Eigen"] = std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) +
               "." + std::to_string(EIGEN_MINOR_VERSION);
  v["VTK"] = vtkVersion::GetVTKVersion();
  return v;
}

}  // namespace tissuemesh
