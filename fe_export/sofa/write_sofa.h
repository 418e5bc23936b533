// SOFA scene (.scn) for SOFA v24.06 and later, formats.md §3, with its companion mesh.
//
// Root: gravity in model units, DefaultAnimationLoop, RequiredPlugin pluginName=... for every
// component used. Node "breast": the static solver (v25.06+: NewtonRaphsonSolver + StaticSolver;
// v24.06: StaticSolver newton_iterations=...), SparseLDLSolver (CompressedRowSparseMatrixMat3x3d),
// MeshVTKLoader of the companion legacy ASCII VTK 4.2 file, TetrahedronSetTopologyContainer,
// TetrahedronSetGeometryAlgorithms, MechanicalObject, MeshMatrixMass with one massDensity per
// tet, FixedProjectiveConstraint (0-based corner indices) per fixed set, PlaneProjectiveConstraint
// (indices, origin, normal) per sliding set whose normals are all parallel and whose nodes are
// coplanar (it also projects positions onto its plane); the old name ProjectToPlaneConstraint is
// deprecated in v24.06 and removed in v25.06 like FixedConstraint (SOFA ComponentChange.cpp,
// PlaneProjectiveConstraint.cpp); one child node per tissue with its tets (global
// 0-based ids) and a TetrahedronHyperelasticityFEMForceField with the ParameterSet in SOFA's
// order: NeoHookean "mu lambda" (exact for CompressibleNeoHookean), MooneyRivlin "C10 C01 K"
// (for NeoHookean / MooneyRivlin: SOFA's volumetric term is K/2 (ln J)^2, not K/2 (J-1)^2 — a
// note says so). Ogden (SOFA changed its parameter order in v25.12), curved and non-planar
// sliding sets and an unknown version are refused (InputError) before anything is written.
// Solver thresholds come from AnalysisSettings (relative ones only: absolute thresholds are
// written as 0 = off, since an absolute norm depends on the unit system). SOFA's hyperelastic
// tets are linear: a tet10 model is written as its corners (a note says so).
#pragma once

#include "core/model.h"
#include "fe_export/export_options.h"

#include <ostream>
#include <string>
#include <vector>

namespace tissuemesh {

/// Writes the scene to `scene`; the scene's loader reads `options.mesh_file` (a path relative to
/// the scene), which the caller writes with write_legacy_vtk.
std::vector<std::string> write_sofa(const Model& model, std::ostream& scene, const SofaOptions& options);

/// Legacy VTK 4.2 ASCII unstructured grid of the model's corner nodes and linear tets (cell type
/// 10), coordinates in the model's length unit, cell data tissue_id: what SOFA's MeshVTKLoader
/// reads without warnings (it warns for version >= 5).
void write_legacy_vtk(const Model& model, std::ostream& out);

}  // namespace tissuemesh
