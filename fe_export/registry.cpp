#include "fe_export/registry.h"

#include "core/errors.h"
#include "fe_export/abaqus/write_abaqus.h"
#include "fe_export/febio/write_febio.h"
#include "fe_export/gmsh/write_gmsh.h"
#include "fe_export/sofa/write_sofa.h"
#include "fe_export/vtu/write_model_vtu.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace tissuemesh {

namespace fs = std::filesystem;

const std::vector<ExportFormat>& export_formats() {
  static const std::vector<ExportFormat> kFormats{
      {"febio", {".feb"}, "FEBio 4 model (spec 4.0)", "model.feb"},
      {"abaqus", {".inp"}, "Abaqus / CalculiX input deck", "model.inp"},
      {"sofa", {".scn"}, "SOFA scene (v24.06+) with its legacy VTK mesh", "model.scn"},
      {"vtu", {".vtu"}, "VTK unstructured grid with tissue and material cell data (ParaView)", "model.vtu"},
      {"msh", {".msh"}, "Gmsh 4.1 mesh with physical groups per tissue and set", "model.msh"},
  };
  return kFormats;
}

namespace {
std::string supported_list() {
  std::string out;
  for (const ExportFormat& f : export_formats()) out += (out.empty() ? "" : ", ") + f.name + " (" + f.extensions[0] + ")";
  return out;
}

// Renders a writer's whole text first and only then creates `path`: a writer that refuses the
// model leaves no empty or half-written file behind.
template <typename Write>
void write_text_file(const std::string& path, Write&& write) {
  std::ostringstream text;
  write(text);
  std::ofstream out(path, std::ios::binary);
  if (!out) throw OutputError("cannot open '" + path + "' for writing");
  out << text.str();
  out.flush();
  if (!out) throw OutputError("writing '" + path + "' failed (disk full?)");
}
}  // namespace

const ExportFormat& export_format_named(const std::string& name) {
  for (const ExportFormat& f : export_formats())
    if (f.name == name) return f;
  throw InputError("unknown export format '" + name + "' (supported: " + supported_list() + ")");
}

const ExportFormat& export_format_for_path(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  for (const ExportFormat& f : export_formats())
    for (const std::string& e : f.extensions)
      if (e == ext) return f;
  throw InputError("'" + path + "': no export format for extension '" + ext + "' (supported: " + supported_list() + ")");
}

ExportResult export_model(const Model& model, const ExportFormat& format, const std::string& path,
                          const ExportOptions& options) {
  validate_model(model);
  ExportResult result;
  result.files.push_back(path);
  if (format.name == "febio") {
    write_text_file(path, [&](std::ostream& out) { result.notes = write_febio(model, out, options.febio); });
  } else if (format.name == "abaqus") {
    write_text_file(path, [&](std::ostream& out) { result.notes = write_abaqus(model, out, options.abaqus); });
  } else if (format.name == "sofa") {
    // The scene names its mesh relative to itself: keep the companion next to the scene.
    SofaOptions sofa = options.sofa;
    sofa.mesh_file = fs::path(path).stem().string() + ".vtk";
    std::ostringstream scene;  // the scene is checked (Ogden, curved sliding) before any file is written
    result.notes = write_sofa(model, scene, sofa);
    const std::string mesh_path = (fs::path(path).parent_path() / sofa.mesh_file).string();
    write_text_file(mesh_path, [&](std::ostream& out) { write_legacy_vtk(model, out); });
    write_text_file(path, [&](std::ostream& out) { out << scene.str(); });
    result.files.push_back(mesh_path);
  } else if (format.name == "vtu") {
    write_model_vtu(model, path);
  } else if (format.name == "msh") {
    write_gmsh(model, path);
  } else {
    throw InputError("export format '" + format.name + "' has no writer");
  }
  return result;
}

}  // namespace tissuemesh
