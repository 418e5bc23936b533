// The export registry: every format tissuemesh writes, by name and file extension, and one entry
// point that validates the model and dispatches to the format's writer.
//
//   name    extensions   writer                                  notes
//   febio   .feb         febio/write_febio.h   (FEBio spec 4.0)
//   abaqus  .inp         abaqus/write_abaqus.h (Abaqus, CalculiX)
//   sofa    .scn         sofa/write_sofa.h     (SOFA v24.06+)    + companion legacy VTK mesh
//   vtu     .vtu         vtu/write_model_vtu.h (ParaView)        tissue and parameters as cell data
//   msh     .msh         gmsh/write_gmsh.h     (Gmsh 4.1 via SDK) physical groups per tissue/set
#pragma once

#include "core/model.h"
#include "fe_export/export_options.h"

#include <string>
#include <vector>

namespace tissuemesh {

struct ExportFormat {
  std::string name;                     ///< "febio"
  std::vector<std::string> extensions;  ///< {".feb"}
  std::string description;              ///< "FEBio 4 model (spec 4.0)"
  std::string default_file;             ///< "model.feb"
};

/// Every registered format, in a fixed order.
const std::vector<ExportFormat>& export_formats();
/// Lookup by name or by a file's extension; InputError listing the supported ones otherwise.
const ExportFormat& export_format_named(const std::string& name);
const ExportFormat& export_format_for_path(const std::string& path);

/// What a writer produced: files (the main one first) and notes a user must know (e.g. an
/// approximated volumetric term).
struct ExportResult {
  std::vector<std::string> files;
  std::vector<std::string> notes;
};

/// validate_model, then writes `model` in `format` to `path` (companion files next to it).
/// Throws InputError for a model the format cannot represent exactly (naming tissue and law),
/// OutputError naming the path when a file cannot be written.
ExportResult export_model(const Model& model, const ExportFormat& format, const std::string& path,
                          const ExportOptions& options);

}  // namespace tissuemesh
