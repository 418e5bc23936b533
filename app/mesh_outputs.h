// Meshing a label image into an output folder: shared by `mesh` and `demo`.
#pragma once

#include "app/html_outputs.h"
#include "core/label_image.h"
#include "core/output_dir.h"
#include "core/progress.h"
#include "core/tet_mesh.h"
#include "pipeline/mesh_config.h"

#include <nlohmann/json.hpp>

#include <string>

namespace tissuemesh::app {

/// Meshes `labels` with `config`, stages DIR/mesh.vtu, DIR/report.json (the run record: inputs,
/// effective config, versions, timings, counts, quality) and DIR/report.txt, and prints the
/// report table. `inputs` is merged into the record's "inputs". Does not commit `out`. Returns the
/// mesh (for the demo's exports). A conforming mesh goes into `report` (report.html) when given.
TetMesh mesh_into(const LabelImage& labels, const std::string& image_name, const MeshConfig& config,
               const nlohmann::json& inputs, const std::string& command_line, Progress& progress,
               OutputDir& out, RunReport* report = nullptr);

/// The surface pipeline (docs/surface-pipeline.md): stages DIR/surface.vtp (triangles with
/// label_p, label_q), DIR/junctions.vtp (junction polylines), DIR/mesh.vtu (the tet mesh of that
/// surface, same cell data as the direct pipeline's), DIR/report.json and DIR/report.txt, and
/// prints the report. Does not commit `out`. Throws MeshingError when the surface fails its checks
/// (closed, oriented, intersection free, stored once): such a surface must not reach a volume
/// mesher. The tet mesh, with the junction curves, goes into `report` when given.
void surface_into(const LabelImage& labels, const std::string& image_name, const MeshConfig& config,
                  const nlohmann::json& inputs, const std::string& command_line, Progress& progress, OutputDir& out,
                  RunReport* report = nullptr);

}  // namespace tissuemesh::app
