// VTP (VTK XML polydata) output of a multi-material TriSurface (docs/formats.md, "VTP (surface
// pipeline)").
//
// surface file: points in LPS mm; triangle cells with the TriSurface winding (normal from label_p
// into label_q); cell data `label_p`, `label_q` (Int32 region ids, 0 = outside) and `patch` (Int32,
// the same for all triangles of one p|q pair, numbered in ascending (p, q) order); field data as every
// toolkit VTK file (tissue_names, coordinate_system LPS, length_unit mm). ParaView: colour by patch,
// or threshold label_p/label_q to see one tissue's boundary.
// junctions file: the same points, one polyline cell per junction curve; cell data `closed` (1 for
// loops) and `junction` (index).
#pragma once

#include "core/tri_surface.h"

#include <string>

namespace tissuemesh {

/// Throws OutputError naming the path when it cannot be written.
void write_surface_vtp(const TriSurface& surface, const std::string& path);
void write_junctions_vtp(const TriSurface& surface, const std::string& path);

}  // namespace tissuemesh
