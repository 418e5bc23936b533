// The report of a surface-pipeline run, as JSON (machine-readable) and text (the same figures, for
// people). Units are in every JSON key and every column header.
#pragma once

#include "pipeline/surface_job.h"

#include <nlohmann/json.hpp>

#include <string>

namespace tissuemesh {

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
