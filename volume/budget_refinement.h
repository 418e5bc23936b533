// Meeting a tet budget by repeated refinement (direct pipeline, `direct.target_tets`;
// docs/direct-pipeline.md "Sizes from the image and a tet budget").
//
// Each round sizes the image for the budget (image_sizing.h) with the current tet volume factor,
// refines, and compares the count N with the target. Near the budget N follows the predicted raw
// sum R (voxel volume / edge^3 summed) as a power law N = c R^e: one round gives c (e = 1), two
// give e too, and the next factor is solved from them. Rounds stop within 5 % of the target, after
// four rounds, when the sizes stop changing (R equal in two rounds), or when e < 0.1 (the count
// hardly follows the sizes: small components and thin parts hold it up). A final count more
// than 10 % off is an InputError naming the counts reached and the way to move the budget.
#pragma once

#include "volume/image_sizing.h"

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace tissuemesh {

/// How the sizes met `direct.target_tets` (empty when it is 0).
struct DirectSizing {
  struct Attempt {
    double global_edge_mm = 0.0;  ///< the largest edge of the size field, mm
    double predicted_tets = 0.0;
    std::size_t refined_tets = 0;  ///< tets after Delaunay refinement
  };
  std::size_t target_tets = 0;
  double min_edge_mm = 0.0;
  double global_edge_mm = 0.0;    ///< of the refinement kept
  double tet_volume_factor = 0.0; ///< mean tet volume / edge^3 of the last prediction
  double thickness_scale = 1.0;   ///< > 1: thin parts got elements this much coarser than their thickness
  std::vector<CoarsenedTissue> coarsened;
  std::vector<Attempt> attempts;
};

/// `size(p)`: the size field for sizing parameters p (only p.tet_volume_factor changes between
/// rounds); `refine(s)`: refines to s, returns the tet count (the mesh of the last call is the one
/// kept). `components`: the tissue components meshed, for the message. Throws InputError as above.
DirectSizing refine_to_budget(const ImageSizingParams& params, std::size_t components,
                              const std::function<ImageSizing(const ImageSizingParams&)>& size,
                              const std::function<std::size_t(const ImageSizing&)>& refine);

}  // namespace tissuemesh
