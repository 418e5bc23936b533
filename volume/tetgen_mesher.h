// TetGen backend (issue #6, step 2): tetrahedra from a multi-material surface complex with
// TetGen 1.5, the cross-check mesher for the CGAL volume mesh of the same surface.
//
// Input: a valid TriSurface (every tissue's boundary closed, oriented and intersection free,
// every interface stored once; surface/surface_checks.h). It becomes one piecewise linear complex:
// every triangle a facet (its patch pair p|q as the facet marker 1000 p + q), one region per
// tissue with a seed point inside it, its tissue id as the region attribute and its maximum tet
// volume. Switches, built from the typed parameters only: p (PLC), q<ratio>/<dihedral> (quality),
// A (region attributes), a (per-region volume bounds), m (when a largest circumradius is given per
// surface point: a tet is split while its circumradius exceeds the value at any of its vertices,
// and points TetGen adds get the value interpolated from the tet they split), Y (keep every input
// facet as it is: the
// boundary and every interface are exactly the input triangles, so the tet mesh and the surface
// agree face for face and enclose the same volumes; without Y, TetGen flips and splits nearly
// coplanar boundary triangles and moves the surface by ~1e-6 of the volume), z (0-based),
// Q (quiet). With Y, a tet at the surface whose split point would land on the surface stays
// unsplit, so the volume bound holds inside a tissue but not for every tet touching the surface.
// Tets TetGen leaves in no region (cavities of "outside") are dropped.
//
// Seeds: every connected piece of a tissue's boundary (an island, a cavity's wall) gets one, so
// no part of a tissue is left without its region attribute (TetGen would drop it silently): from
// the piece's largest triangle, halfway to the first other triangle hit by a ray into the tissue,
// so it lies strictly inside the tissue whatever its thickness.
//
// Errors: TetGen's failures (self-intersecting or degenerate input, which a valid surface does
// not have) become MeshingError with TetGen's error code meaning. Deterministic.
#pragma once

#include "core/progress.h"
#include "core/tet_mesh.h"
#include "core/tri_surface.h"
#include "volume/tetgen_params.h"

#include <map>
#include <string>
#include <vector>

namespace tissuemesh {

struct TetgenResult {
  TetMesh mesh;
  std::string switches;  ///< the switches TetGen ran with, for the report
  std::size_t steiner_points = 0;  ///< nodes TetGen added (mesh nodes - surface vertices used)
};

/// Meshes `surface` (see the header comment). `point_radius_mm`, when not empty, is the largest
/// tet circumradius in mm at every surface point (switch m; 0 = no bound at that point); tissues
/// not named in params.max_volume_mm3 then get no volume bound, so these sizes alone set the
/// resolution. Throws InputError for bad parameters (naming the key) and MeshingError when TetGen
/// fails.
TetgenResult tetgen_mesh(const TriSurface& surface, const TetgenParams& params, Progress& progress,
                         const std::vector<double>& point_radius_mm = {});

}  // namespace tissuemesh
