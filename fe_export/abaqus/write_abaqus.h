// Abaqus / CalculiX input deck (.inp), flat (no parts), formats.md §2.
//
// *HEADING; *NODE (NSET=NALL); *ELEMENT TYPE=C3D4|C3D10 (C3D4H|C3D10H with hybrid, Abaqus only)
// one block per tissue with ELSET=<TISSUE>; *ELSET EALL; *NSET per node set; *SURFACE
// (TYPE=ELEMENT, faces S1..S4) per face set; *MATERIAL per tissue with *HYPERELASTIC (NEO HOOKE
// C10, D1 | MOONEY-RIVLIN C10, C01, D1 | OGDEN N=n mu_i, alpha_i, D1 [, D1*1e12 ...]) and *DENSITY;
// *SOLID SECTION per tissue; *BOUNDARY <set>, 1, 3 for fixed sets and *EQUATION n.u = 0 per node
// of sliding sets; *STEP, NLGEOM, INC=max_load_steps; *STATIC 1/load_steps, 1, min, 1/load_steps;
// *DLOAD EALL, GRAV, |g|, direction; *NODE PRINT NSET=NALL U; *NODE PRINT of each fixed set RF
// with TOTALS=YES; *NODE FILE U; *EL FILE S, E; *END STEP. At most 16 entries per data line,
// ids 1-based, names upper-case. CompressibleNeoHookean has no exact Abaqus equivalent and is
// refused (InputError naming the tissue), as are names that clash once upper-cased (or with
// EALL/NALL) and names over CalculiX's 80 characters; nothing is written before these checks.
// CalculiX specifics the deck respects (checked with ccx 2.20):
// - reals are printed shortest round-trip, but never longer than 20 characters: ccx reads each
//   field as f20.0 of its first 20 characters and silently cuts the rest (run: "0.2000...e+01"
//   of 25 characters was read as 0.2); long ones get 13-16 significant digits instead of 17;
// - Ogden N>=2: D2 (, D3) = D1 * 1e12 instead of 0, because ccx replaces any D_i < 1e-10 by
//   (0.1/mu)^i (hyperelastics.f; run: "D2 = 0.1235E+05"), a unit-dependent (J-1)^4 term; with
//   D1 * 1e12 the extra terms are below 1e-12 of the (J-1)^2 term for |J-1| <= 1;
// - sliding nodes that are also in a fixed set get no *EQUATION: they stay fixed (ccx refuses a
//   DOF both fixed and dependent; run: exit 201, "dependent side of a MPC and a SPC"); a node in
//   two sliding sets uses a different dependent DOF per equation (ccx refuses a DOF dependent
//   twice); parallel duplicates are dropped (with a note);
// - tissues without elements are left out (an empty ELSET would fail *SOLID SECTION).
// ccx's RF (printed with TOTALS=YES) is the internal force at the fixed nodes: it excludes the
// share of the body load lumped on those nodes, so RF total = weight - that share (run).
#pragma once

#include "core/model.h"
#include "fe_export/export_options.h"

#include <ostream>
#include <string>
#include <vector>

namespace tissuemesh {

std::vector<std::string> write_abaqus(const Model& model, std::ostream& out, const AbaqusOptions& options);

/// The upper-case Abaqus name of a tissue element set / node set ("FAT", "CHEST_WALL").
std::string abaqus_name(const std::string& name);

}  // namespace tissuemesh
