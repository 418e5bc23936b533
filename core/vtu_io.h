// VTU (VTK XML unstructured grid) read/write of a TetMesh, the toolkit's native mesh file.
//
// Layout written: points in LPS mm; VTK_TETRA cells with the TetMesh node order (VTK's tetra order
// is the same: positive volume for (p1-p0).((p2-p0)x(p3-p0)) > 0); cell data `tissue_id` (Int32,
// 1-based); the field data of every toolkit VTU (write_grid_vtu, core/vtk_grid_file.h: tissue
// names, coordinate system LPS, length unit mm, one tag per tissue; docs/formats.md, "VTU").
// ParaView shows tissue_id directly.
#pragma once

#include "core/tet_mesh.h"

#include <map>
#include <string>
#include <vector>

namespace tissuemesh {

/// Extra per-cell scalar arrays to write alongside tissue_id (name -> one value per tet).
using CellScalars = std::map<std::string, std::vector<double>>;

/// Writes `mesh` to `path`. Throws OutputError naming the path on failure.
void write_vtu(const TetMesh& mesh, const std::string& path, const CellScalars& extra = {});

/// Reads a mesh written by write_vtu (or any VTU with only tetra cells and a `tissue_id` cell
/// array; tissue names default to "tissue_<id>"). Throws InputError naming the path and the
/// problem (missing file, not a VTU, non-tetra cells, missing tissue_id).
TetMesh read_vtu(const std::string& path);

}  // namespace tissuemesh
