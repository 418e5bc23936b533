// The default phantom on coarse voxels, extracted once per test binary: a complex large enough for
// the remesher's partitioned sweeps (more than 10,000 vertices, surface/remesh_partition.cpp) and
// small enough to remesh in about a second. Shared by the remesher's tests.
#pragma once

#include "image/phantom.h"
#include "surface/surface_projection.h"
#include "support/surface_images.h"

namespace tissuemesh::test {

/// The default phantom on 1.4 x 1.4 x 3 mm voxels (no FGT islands: none fit in the fat at this
/// spacing; the thorax label 6 outside, as in configs/phantom.yaml): unlike the small test images
/// its polished surfaces keep triangles under the paper's Q_min.
struct CoarsePhantom {
  TriSurface surface;
  SurfaceProjection on_surface;
  double max_deviation_mm;
  explicit CoarsePhantom(const LabelImage& img)
      : surface(extract(img, 5).surface), on_surface(surface), max_deviation_mm(0.5 * img.spacing.norm()) {}
};

inline const CoarsePhantom& coarse_phantom() {
  static const CoarsePhantom phantom([] {
    PhantomParams coarse;
    coarse.spacing_mm = {1.4, 1.4, 3.0};
    coarse.fgt_islands = 0;
    LabelImage img = make_breast_phantom(coarse);
    for (auto& label : img.labels)
      if (label == 6) label = 0;
    return img;
  }());
  return phantom;
}

}  // namespace tissuemesh::test
