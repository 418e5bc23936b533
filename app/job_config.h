// JobConfig: one config file for the whole pipeline — meshing (pipeline/mesh_config.h), materials
// (materials/material_config.h), the model (core/model_settings.h) and export options
// (fe_export/export_options.h) and the prone-to-supine workflow (workflows/prone2supine_settings.h). Each command reads the parts it needs; unknown keys anywhere are
// errors. A file without meshing keys (no `tissues`) is a valid export/solve/check config; of the
// meshing part it may then hold `tetgen:` (for check --tetgen).
#pragma once

#include "core/model_settings.h"
#include "fe_export/export_options.h"
#include "materials/material_config.h"
#include "pipeline/mesh_config.h"
#include "workflows/prone2supine_settings.h"

#include <string>

namespace tissuemesh::app {

struct JobConfig {
  std::string source = "<built-in defaults>";
  bool has_mesh = false;  ///< the file has meshing keys (`tissues`, ...)
  MeshConfig mesh;
  MaterialTable materials;
  bool has_materials = false;
  ModelSettings model;
  ExportOptions exports;
  Prone2SupineSettings prone2supine;  ///< `prone2supine:` (defaults when absent)

  static JobConfig load(const std::string& path);
  /// `tissuemesh demo` without -c: identical to configs/phantom.yaml (a CLI test compares the two
  /// --print-config outputs).
  static JobConfig phantom_default();
  /// Effective config with every key (materials expanded from presets).
  std::string to_yaml() const;
  /// The meshing part, refusing a file that has none (for `mesh`).
  const MeshConfig& require_mesh() const;
  /// Fails early (before meshing) when a tissue of the meshing part has no material.
  void check_materials_cover_tissues() const;
};

}  // namespace tissuemesh::app
