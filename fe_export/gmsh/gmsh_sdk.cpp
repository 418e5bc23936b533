// Why dlopen: libgmsh brings ~60 shared libraries (OpenCASCADE, FLTK, X11, image codecs) whose
// relocations the dynamic loader processes before main(), which costs several times the start-up
// of everything else tissuemesh links. Linked, every command would pay it, also `solve`, `mesh`
// and `--version`; loaded on demand, only a .msh export or `check --gmsh` does.
#include "fe_export/gmsh/gmsh_sdk.h"

#include <gmshc.h>

#include <dlfcn.h>

#ifndef TISSUEMESH_GMSH_SONAME
#error "TISSUEMESH_GMSH_SONAME (the Gmsh SDK's library, e.g. libgmsh.so.4.8) must be defined by the build"
#endif

namespace tissuemesh::gmsh_sdk {
namespace {

/// The C API functions used, resolved from libgmsh (types from gmshc.h).
struct Api {
  decltype(&::gmshFree) free;
  decltype(&::gmshLoggerGetLastError) last_error;
  decltype(&::gmshInitialize) initialize;
  decltype(&::gmshFinalize) finalize;
  decltype(&::gmshOptionSetNumber) set_number;
  decltype(&::gmshOptionGetString) get_string;
  decltype(&::gmshModelAdd) add_model;
  decltype(&::gmshModelAddDiscreteEntity) add_discrete_entity;
  decltype(&::gmshModelSetCoordinates) set_coordinates;
  decltype(&::gmshModelAddPhysicalGroup) add_physical_group;
  decltype(&::gmshModelSetPhysicalName) set_physical_name;
  decltype(&::gmshModelMeshAddNodes) add_nodes;
  decltype(&::gmshModelMeshAddElementsByType) add_elements_by_type;
  decltype(&::gmshWrite) write;
};

template <class F>
void resolve(void* library, const char* name, F& f) {
  f = reinterpret_cast<F>(dlsym(library, name));
  if (!f) throw GmshError(std::string(TISSUEMESH_GMSH_SONAME) + " has no " + name + " (not the Gmsh 4.8 SDK?)");
}

Api load() {
  // Never closed: the SDK keeps global state for the process's lifetime.
  void* library = dlopen(TISSUEMESH_GMSH_SONAME, RTLD_LAZY | RTLD_LOCAL);
  if (!library) {
    const char* reason = dlerror();
    throw GmshError(std::string("cannot load the Gmsh SDK (") + TISSUEMESH_GMSH_SONAME +
                    "; Debian package libgmsh4.8): " + (reason ? reason : "unknown reason"));
  }
  Api a{};
  resolve(library, "gmshFree", a.free);
  resolve(library, "gmshLoggerGetLastError", a.last_error);
  resolve(library, "gmshInitialize", a.initialize);
  resolve(library, "gmshFinalize", a.finalize);
  resolve(library, "gmshOptionSetNumber", a.set_number);
  resolve(library, "gmshOptionGetString", a.get_string);
  resolve(library, "gmshModelAdd", a.add_model);
  resolve(library, "gmshModelAddDiscreteEntity", a.add_discrete_entity);
  resolve(library, "gmshModelSetCoordinates", a.set_coordinates);
  resolve(library, "gmshModelAddPhysicalGroup", a.add_physical_group);
  resolve(library, "gmshModelSetPhysicalName", a.set_physical_name);
  resolve(library, "gmshModelMeshAddNodes", a.add_nodes);
  resolve(library, "gmshModelMeshAddElementsByType", a.add_elements_by_type);
  resolve(library, "gmshWrite", a.write);
  return a;
}

/// The loaded API (loaded by the first caller; a failed load is retried by the next call).
const Api& api() {
  static const Api a = load();
  return a;
}

/// A string the SDK allocated, released with gmshFree.
std::string take(char* s) {
  std::string out = s ? s : "";
  if (s) api().free(s);
  return out;
}

/// Throws GmshError naming the call, with the SDK's last logged error (which may be an older one
/// when the call failed without logging), when ierr says the call failed.
void check(int ierr, const char* call) {
  if (ierr == 0) return;
  char* message = nullptr;
  int ignored = 0;
  api().last_error(&message, &ignored);
  const std::string text = take(message);
  throw GmshError(std::string("Gmsh's ") + call + " failed" + (text.empty() ? "" : ": " + text));
}

}  // namespace

void initialize() {
  int ierr = 0;
  api().initialize(0, nullptr, 0, &ierr);
  check(ierr, "initialize");
}

void finalize() {
  int ierr = 0;
  api().finalize(&ierr);
  check(ierr, "finalize");
}

void set_number(const std::string& option, double value) {
  int ierr = 0;
  api().set_number(option.c_str(), value, &ierr);
  check(ierr, "option::setNumber");
}

std::string get_string(const std::string& option) {
  int ierr = 0;
  char* value = nullptr;
  api().get_string(option.c_str(), &value, &ierr);
  std::string out = take(value);
  check(ierr, "option::getString");
  return out;
}

void add_model(const std::string& name) {
  int ierr = 0;
  api().add_model(name.c_str(), &ierr);
  check(ierr, "model::add");
}

int add_discrete_entity(int dim, int tag) {
  int ierr = 0;
  const int out = api().add_discrete_entity(dim, tag, nullptr, 0, &ierr);
  check(ierr, "model::addDiscreteEntity");
  return out;
}

void set_coordinates(int tag, double x, double y, double z) {
  int ierr = 0;
  api().set_coordinates(tag, x, y, z, &ierr);
  check(ierr, "model::setCoordinates");
}

int add_physical_group(int dim, const std::vector<int>& tags, int tag) {
  int ierr = 0;
  // The C API takes non-const arrays but only reads them.
  const int out = api().add_physical_group(dim, const_cast<int*>(tags.data()), tags.size(), tag, &ierr);
  check(ierr, "model::addPhysicalGroup");
  return out;
}

void set_physical_name(int dim, int tag, const std::string& name) {
  int ierr = 0;
  api().set_physical_name(dim, tag, name.c_str(), &ierr);
  check(ierr, "model::setPhysicalName");
}

void add_nodes(int dim, int tag, const std::vector<std::size_t>& node_tags, const std::vector<double>& coords) {
  int ierr = 0;
  api().add_nodes(dim, tag, const_cast<std::size_t*>(node_tags.data()), node_tags.size(),
                  const_cast<double*>(coords.data()), coords.size(), nullptr, 0, &ierr);
  check(ierr, "model::mesh::addNodes");
}

void add_elements_by_type(int tag, int element_type, const std::vector<std::size_t>& element_tags,
                          const std::vector<std::size_t>& node_tags) {
  int ierr = 0;
  api().add_elements_by_type(tag, element_type, const_cast<std::size_t*>(element_tags.data()), element_tags.size(),
                             const_cast<std::size_t*>(node_tags.data()), node_tags.size(), &ierr);
  check(ierr, "model::mesh::addElementsByType");
}

void write(const std::string& path) {
  int ierr = 0;
  api().write(path.c_str(), &ierr);
  check(ierr, "write");
}

}  // namespace tissuemesh::gmsh_sdk
