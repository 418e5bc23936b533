// Abaqus / CalculiX input deck (.inp), flat (no parts): docs/formats.md, "Abaqus / CalculiX";
// Abaqus Keywords Reference Guide; CalculiX CrunchiX User's Manual 2.20.
//
// One *ELEMENT block per tissue (C3D4 | C3D10; C3D4H | C3D10H with `hybrid`, Abaqus only) with
// ELSET=<TISSUE>, sets EALL and NALL, *NSET per node set, *SURFACE (faces S1..S4) per face set,
// *MATERIAL per tissue (*HYPERELASTIC NEO HOOKE | MOONEY-RIVLIN | OGDEN N=n, *DENSITY),
// *BOUNDARY per fixed set, *EQUATION n . u = 0 per sliding node, one NLGEOM *STATIC step under
// *DLOAD GRAV, output U and the fixed sets' RF totals. Ids 1-based, names upper-case, numbers in
// the model's unit system (reals shortest round-trip, but at most 20 characters: 13-16 significant
// digits for the few that need more), tissues without elements left out. Readable by CalculiX as
// well as Abaqus (the .cpp says which CalculiX limits the deck respects).
#pragma once

#include "core/model.h"
#include "fe_export/export_options.h"

#include <ostream>
#include <string>
#include <vector>

namespace tissuemesh {

/// Writes the deck; returns notes for the user (e.g. sliding nodes that stay fixed). Calls
/// validate_model first. Throws InputError naming the tissue or set, before anything is written,
/// for CompressibleNeoHookean (no exact Abaqus equivalent), names that clash once upper-cased (or
/// with EALL/NALL) and names over CalculiX's 80 characters.
std::vector<std::string> write_abaqus(const Model& model, std::ostream& out, const AbaqusOptions& options);

/// The upper-case Abaqus name of a tissue element set / node set ("FAT", "CHEST_WALL").
std::string abaqus_name(const std::string& name);

}  // namespace tissuemesh
