// Reports of label images, of any mesh and of a direct-pipeline run, as JSON (machine-readable)
// and text (the same figures, for people); a surface-pipeline run's: pipeline/surface_report.h.
// Units are in every JSON key and every column header.
#pragma once

#include "core/label_image.h"
#include "core/tet_mesh.h"
#include "pipeline/mesh_job.h"

#include <nlohmann/json.hpp>

#include <string>

namespace tissuemesh {

/// dims, spacing_mm, origin_mm (LPS), direction (rows), orientation code, voxel volume, label
/// counts with volumes.
nlohmann::json image_summary_json(const LabelImage& image);
std::string image_summary_text(const LabelImage& image);

/// Quality and conformity of any mesh (no reference volumes): what `tissuemesh info MESH` shows.
nlohmann::json mesh_summary_json(const TetMesh& mesh);
std::string mesh_summary_text(const TetMesh& mesh);

/// The result part of a mesh run: counts, per-tissue quality with volume fidelity, conformity,
/// image components and the ones the mesh misses (by tissue, size and position).
nlohmann::json mesh_job_json(const MeshJobResult& result);
std::string mesh_job_text(const MeshJobResult& result);

}  // namespace tissuemesh
