// SOFA scene (.scn) for SOFA v24.06 and later, with its companion mesh (docs/formats.md, "SOFA";
// SOFA documentation, "Components").
//
// Root: gravity in model units, DefaultAnimationLoop, a RequiredPlugin for every component used.
// Node "breast": the static solver (v25.06+: NewtonRaphsonSolver + StaticSolver; v24.06:
// StaticSolver newton_iterations=...), SparseLDLSolver, MeshVTKLoader of the companion legacy VTK
// file, TetrahedronSetTopologyContainer, TetrahedronSetGeometryAlgorithms, MechanicalObject,
// MeshMatrixMass with one massDensity per tet, FixedProjectiveConstraint (0-based corner indices)
// per fixed set, PlaneProjectiveConstraint per sliding set whose normals are parallel and whose
// nodes are coplanar; one child node per tissue with its tets (global 0-based ids) and a
// TetrahedronHyperelasticityFEMForceField, parameters in SOFA's order: NeoHookean "mu lambda"
// (exact for CompressibleNeoHookean), MooneyRivlin "C10 C01 K" for NeoHookean and MooneyRivlin
// (SOFA's volumetric term is K/2 (ln J)^2, not K/2 (J-1)^2: a note says so). Solver thresholds
// are AnalysisSettings' relative ones (absolute ones written as 0 = off). A tet10 model is written
// as its corners (SOFA's hyperelastic tets are linear; a note says so).
#pragma once

#include "core/model.h"
#include "fe_export/export_options.h"

#include <ostream>
#include <string>
#include <vector>

namespace tissuemesh {

/// Writes the scene to `scene`; the scene's loader reads `options.mesh_file` (a path relative to
/// the scene), which the caller writes with write_legacy_vtk. Returns notes for the user. Calls
/// validate_model first; throws InputError, before anything is written, for Ogden (SOFA changed
/// its parameter order in v25.12), a curved or non-planar sliding set, or an unknown version.
std::vector<std::string> write_sofa(const Model& model, std::ostream& scene, const SofaOptions& options);

/// Legacy VTK 4.2 ASCII unstructured grid of the model's corner nodes and linear tets (cell type
/// 10), coordinates in the model's length unit, cell data tissue_id: what SOFA's MeshVTKLoader
/// reads without warnings (it warns for version >= 5).
void write_legacy_vtk(const Model& model, std::ostream& out);

}  // namespace tissuemesh
