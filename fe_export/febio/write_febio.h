// FEBio model file, spec version 4.0 (formats.md §1; FEBio 4.x reads it).
//
// Layout: Module solid; Control (STATIC, time_steps = load_steps, step_size 1/load_steps, default
// time stepper with cut-backs down to dtmin = min_step_fraction, full Newton (BFGS max_ups 0,
// max_refs = max_newton_iterations) with dtol/etol/rtol from AnalysisSettings; max_load_steps has
// no FEBio equivalent); Material (one per tissue, named after it, with density); Mesh (Nodes "all"
// ids 1..N = model node index + 1, one Elements block per tissue named after it, tet4 or tet10,
// NodeSets, Surfaces tri3/tri6 for face sets); MeshDomains (SolidDomain name = block, mat =
// material name); Boundary (`zero displacement` per fixed set; sliding sets, below); Loads
// (`body_load` type `const` with the NEGATIVE of the gravity acceleration: FEBio's sign
// convention, §1.9); LoadData (linear ramp 0 -> 1); Output (plotfile displacement + stress,
// logfile node_data ux;uy;uz into "<title>_disp.txt", title reduced to [A-Za-z0-9_.-] and 99
// characters, "model" when empty). FEBio's own XMLReader copies attribute values into 128-char
// buffers and does not expand entities (FEBioXML/XMLReader.h/.cpp): names (identifiers, see
// validate_model) must have at most 127 characters; comments are ASCII without "--".
// Laws (§0): NeoHookean -> Mooney-Rivlin c1 = C10, c2 = 0, k = K, pressure_model Abaqus;
// MooneyRivlin -> same with c2 = C01; Ogden -> Ogden c_i = 2 mu_i, m_i = alpha_i, k = K,
// pressure_model Abaqus; CompressibleNeoHookean -> neo-Hookean E, v. All exact.
//
// Element ids: the file numbers elements 1..E contiguously in block order — all elements of
// tissue 1 in model order, then tissue 2, ... (febio_element_ids gives the map). They equal
// model index + 1 only when the model is already grouped by tissue. Reason: the 4.0 reader keeps
// the file ids (FEBioMeshDomainsSection4.cpp, el.SetID(domElement.id)), but FEBModel::BuildPart
// with buildDomains (used by other FEBio import paths) renumbers elements 1, 2, ... in file
// order, ignoring the ids; ids that increase within and across blocks without gaps are the same
// under both, so plot/log element ids never depend on the reader path.
//
// Sliding sets (n.u = 0 per node): a set whose normals are all parallel to one axis
// (|n_i| > 1 - 1e-9) becomes `zero displacement` on that one dof. Every other sliding node gets
// FEBio `<bc type="linear constraint">` (parent dof = sum value_j * child dof_j, offset 0;
// FEBioXML/FEBioBoundarySection3.cpp ParseLinearConstraint, FECore/FELinearConstraintManager.cpp
// Update): the node's normals from all its oblique sets, with dofs already fixed by axis sets
// removed, are reduced by complete pivoting; each independent row gives one constraint whose
// parent is its pivot dof (largest coefficient). A parent dof is never a child or a fixed dof
// (FELinearConstraintManager::Activate refuses that). Nodes of fixed sets get no constraint.
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
