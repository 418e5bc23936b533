// Reports of label images and meshes, as JSON (machine-readable) and text (the same figures, for
// people). Units are in every JSON key and every column header.
#pragma once

#include "core/label_image.h"
#include "core/tet_mesh.h"
#include "pipeline/mesh_job.h"
#include "pipeline/surface_job.h"

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

/// The result part of a surface-pipeline run: counts, voxel repair, Table 1 (triangle quality) of
/// Alqaoud et al., "Multi-material, approach-guided, controlled-resolution breast meshing",
/// per-tissue closedness/orientation/intersections and enclosed volume against voxel volume of the
/// final surface ("table2_tissues"), stored-twice and junction checks, the tet mesh's quality and
/// conformity, and the paper's Table 2 ("table2_steps": vertices and cells per tissue and in all
/// after extraction, remeshing and tet meshing; null for a step not run) and Table 3
/// ("table3_total_cells": the tet mesh's total tets).
nlohmann::json surface_job_json(const SurfaceJobResult& result);
std::string surface_job_text(const SurfaceJobResult& result);

}  // namespace tissuemesh
