// The few Gmsh SDK calls tissuemesh makes (the .msh writer and the Gmsh quality check), through
// the SDK's C API in libgmsh, which is loaded at the first call (dlopen) instead of at start-up
// (the .cpp says why).
//
// Contract: every function throws GmshError with Gmsh's own message when the call fails, and when
// libgmsh cannot be loaded (the message then names the library and the loader's reason). Sizes and
// tags as in the C++ API (gmsh.h); node and element tags 1-based. Not thread-safe (the SDK is
// global state): one GmshSession (gmsh_session.h) at a time.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace tissuemesh::gmsh_sdk {

struct GmshError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// gmsh::initialize without command-line arguments or user configuration files.
void initialize();
void finalize();
void set_number(const std::string& option, double value);
std::string get_string(const std::string& option);
/// gmsh::model::add
void add_model(const std::string& name);
/// gmsh::model::addDiscreteEntity without boundary; returns the tag.
int add_discrete_entity(int dim, int tag);
/// gmsh::model::setCoordinates (of a point entity)
void set_coordinates(int tag, double x, double y, double z);
/// gmsh::model::addPhysicalGroup; returns the tag.
int add_physical_group(int dim, const std::vector<int>& tags, int tag);
/// gmsh::model::setPhysicalName
void set_physical_name(int dim, int tag, const std::string& name);
/// gmsh::model::mesh::addNodes (3 coordinates per node, no parametric coordinates)
void add_nodes(int dim, int tag, const std::vector<std::size_t>& node_tags, const std::vector<double>& coords);
/// gmsh::model::mesh::addElementsByType
void add_elements_by_type(int tag, int element_type, const std::vector<std::size_t>& element_tags,
                          const std::vector<std::size_t>& node_tags);
/// gmsh::write
void write(const std::string& path);

}  // namespace tissuemesh::gmsh_sdk
