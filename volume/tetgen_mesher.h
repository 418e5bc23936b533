// TetGen backend: tetrahedra from a multi-material surface complex with TetGen 1.5 (Si, "TetGen,
// a Delaunay-based quality tetrahedral mesh generator", ACM TOMS 41, 2015), the cross-check
// mesher for the CGAL volume mesh of the same surface (docs/verification.md).
//
// Input: a valid TriSurface (every tissue's boundary closed, oriented and intersection free,
// every interface stored once; surface/surface_checks.h), as one piecewise linear complex: every
// triangle a facet with marker 1000 p + q (its patch pair p|q); one region per connected piece of
// a tissue's boundary, seeded strictly inside, with the tissue id as region attribute and the
// tissue's maximum tet volume. Switches (TetGen 1.5 user manual, "Command line switches"), built
// from the typed parameters only: p (PLC), q<ratio>/<dihedral> (quality), A (region attributes),
// a (per-region volume bounds), m (a largest circumradius per surface point, interpolated at the
// points TetGen adds), Y (keep every input facet), z (0-based), Q (quiet).
//
// Output: the boundary and every interface are exactly the input triangles, so the tet mesh and
// the surface enclose the same volumes; the volume bound holds inside a tissue but not for every
// tet touching the surface. Tets in no region take the region on their side of the surface
// triangles around them (volume/unseeded_cells.h): a cavity of "outside" is dropped, a cell
// enclosed by a fold of one tissue's boundary is kept as that tissue. TetGen runs
// in a child process (core/isolated_run.h): its failures (self-intersecting or degenerate input,
// which a valid surface does not have, or facets nearly coplanar within its tolerance) become
// MeshingError with the meaning of TetGen's error code, and so does a crash of TetGen, which
// TetGen 1.5 can have while it stops on such input. Deterministic.
#pragma once

#include "core/progress.h"
#include "core/tet_mesh.h"
#include "core/tri_surface.h"
#include "volume/tetgen_params.h"
#include "volume/unseeded_cells.h"

#include <map>
#include <string>
#include <vector>

namespace tissuemesh {

struct TetgenResult {
  TetMesh mesh;
  std::string switches;  ///< the switches TetGen ran with, for the report
  std::size_t steiner_points = 0;  ///< nodes TetGen added (mesh nodes - surface vertices used)
  UnseededCells unseeded;          ///< tets in no region given the tissue around them
};

/// Meshes `surface` (see the header comment). `point_radius_mm`, when not empty, is the largest
/// tet circumradius in mm at every surface point (switch m; 0 = no bound at that point); tissues
/// not named in params.max_volume_mm3 then get no volume bound, so these sizes alone set the
/// resolution. Throws InputError for bad parameters (naming the key) and MeshingError when TetGen
/// fails.
TetgenResult tetgen_mesh(const TriSurface& surface, const TetgenParams& params, Progress& progress,
                         const std::vector<double>& point_radius_mm = {});

}  // namespace tissuemesh
