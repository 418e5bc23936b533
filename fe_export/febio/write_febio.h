// FEBio model file, specification 4.0, read by FEBio 4.x (FEBio User's Manual, version 4, "The
// FEBio Input File"; docs/formats.md, "FEBio").
//
// Sections: Module solid; Control (STATIC, time_steps = load_steps, step_size 1/load_steps,
// cut-backs down to dtmin = min_step_fraction, full Newton with max_refs = max_newton_iterations,
// dtol/etol/rtol from AnalysisSettings; max_load_steps has no FEBio equivalent); one Material per
// tissue, named after it, with its density; Mesh (Nodes "all" with ids = model node index + 1, one
// Elements block per tissue, tet4 or tet10, NodeSets, Surfaces tri3/tri6 for face sets);
// MeshDomains; Boundary; Loads (`body_load` type `const` holding the NEGATIVE of the gravity
// acceleration, FEBio's sign convention); LoadData (linear ramp 0 -> 1); Output (plot file with
// displacement and stress, log file ux;uy;uz in "<title>_disp.txt", the title reduced to
// [A-Za-z0-9_.-] and 99 characters, "model" when empty). Numbers in the model's unit system.
// Laws, all exact: NeoHookean -> Mooney-Rivlin c1 = C10, c2 = 0, k = K, pressure_model Abaqus;
// MooneyRivlin -> the same with c2 = C01; Ogden -> Ogden c_i = 2 mu_i, m_i = alpha_i, k = K,
// pressure_model Abaqus; CompressibleNeoHookean -> neo-Hookean E, v.
//
// Element ids: 1..E contiguously in block order (all elements of tissue 1 in model order, then
// tissue 2, ...; febio_element_ids gives the map), i.e. model index + 1 when the model is grouped
// by tissue, as build_model makes it.
//
// Sliding sets (n . u = 0 per node): a set whose normals are all parallel to one axis
// (|n_i| > 1 - 1e-9) becomes `zero displacement` on that dof; every other sliding node gets one
// `linear constraint` boundary condition per independent normal. Nodes of fixed sets get none.
#pragma once

#include "core/model.h"
#include "fe_export/export_options.h"

#include <ostream>
#include <string>
#include <vector>

namespace tissuemesh {

/// Writes the .feb; returns notes for the user. Calls validate_model first. Throws InputError if
/// a node set is named "all" (the name of FEBio's Nodes block) or a tissue or set name is longer
/// than 127 characters.
std::vector<std::string> write_febio(const Model& model, std::ostream& out, const FebioOptions& options);

/// The .feb element id of every model element (index e -> id), see "Element ids" above.
std::vector<int> febio_element_ids(const Model& model);

}  // namespace tissuemesh
