// Multi-material surface extraction from a tissue-id image (the surface stage, §2.2, of Alqaoud et
// al., "Multi-material, approach-guided, controlled-resolution breast meshing";
// docs/surface-pipeline.md, "1. Multi-material surface extraction").
//
// Method: multi-label SurfaceNets with constrained relaxation (Frisken, "SurfaceNets for
// multi-label segmentations with preservation of sharp boundaries", JCGT 2022):
//   0. tissue components below `min_island_voxels` join the region around them
//      (image/small_islands.h): nothing that small is resolved by the mesh;
//   1. every region is made well-composed (image/label_repair.h), so each tissue's boundary is a
//      closed 2-manifold;
//   2. one vertex per voxel corner touched by a boundary, one quad per voxel face between two
//      regions (p|q) -- each interface is stored once and shared by both tissues, and per tissue the
//      quads are exactly its voxel boundary, hence closed and consistently oriented;
//   3. junction edges (voxel edges around which >= 3 regions meet) form the junction polylines;
//      their vertices are classified as curve vertices (2 junction edges) or corners (other);
//   4. Taubin lambda|mu relaxation (Taubin 1995; no shrinkage): surface vertices move towards the
//      mean of their neighbours, curve vertices towards the mean of their two curve neighbours
//      (they stay on the junction curve), corners stay; every vertex is clamped to the box
//      spanned by its 8 voxel centres, so the surface never leaves the half-voxel band around the
//      voxel boundary;
//   5. each quad is split along its shorter diagonal into two triangles;
//   6. where relaxation folded a tissue's boundary onto itself (check_surface with
//      PairSearch::Grid: CGAL's self-intersection rule, surface/intersecting_pairs.h), the
//      vertices of the intersecting triangles move back towards their voxel corners.
// Averaging commutes with the affine index -> LPS map, so relaxing in voxel-index space is the same
// as relaxing in millimetres, anisotropic spacing included. Deterministic (fixed scan orders).
#pragma once

#include "core/label_image.h"
#include "core/progress.h"
#include "core/tri_surface.h"
#include "image/label_repair.h"
#include "image/small_islands.h"
#include "surface/surface_checks.h"
#include "surface/surface_params.h"

#include <string>
#include <vector>

namespace tissuemesh {

struct SurfaceExtraction {
  TriSurface surface;
  IslandAbsorption islands;      ///< sub-resolution components given to their surroundings
  LabelRepairResult repair;      ///< voxels relabelled to remove non-manifold configurations
  std::size_t curve_vertices = 0;   ///< vertices inside junction polylines
  std::size_t corner_vertices = 0;  ///< fixed vertices: polyline ends, where curves meet
  std::size_t unfolded_vertices = 0;  ///< vertex moves back towards the voxel corner (step 6)
  SurfaceCheckReport checks;          ///< surface/surface_checks.h of the returned surface
};

/// `ids`: tissue ids (0 = outside, 1..names.size()), e.g. TissueTable::to_tissue_ids. Throws
/// InputError when an id is out of range, MeshingError when there is no boundary at all.
SurfaceExtraction extract_surface(const LabelImage& ids, const std::vector<std::string>& tissue_names,
                                  const SurfaceParams& params, Progress& progress);

}  // namespace tissuemesh
