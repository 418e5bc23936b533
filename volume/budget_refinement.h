// Meeting a tet budget by repeated refinement: the rounds of a count budget in one size measure
// (meet_count_budget), and their use by the direct pipeline (`direct.target_tets`;
// docs/direct-pipeline.md "Sizes from the image and a tet budget") and by the surface pipeline's
// TetGen volume stage (`volume.target_tets`; volume/surface_tetgen.h).
//
// Each round meshes with sizes for a measure R (the direct pipeline: voxel volume / edge^3 summed
// over the image; TetGen: the cube of the inverse size factor) and compares the count N with the
// target. Near the budget N follows R as a power law N = c R^e: one round gives c (e = 1), two
// give e too, and the next measure is solved from them. Rounds stop within 5 % of the target,
// after four rounds, when the sizes stop changing (R equal in two rounds), when the sizes are at
// their finest and the count is still below, or when e < 0.1 with the count above (the count
// hardly follows the sizes: small components, thin parts or the kept surface hold it up). A final
// count more than 10 % off is an InputError naming the counts reached and the way to move the
// budget.
#pragma once

#include "volume/image_sizing.h"

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace tissuemesh {

/// One round of meet_count_budget.
struct BudgetRound {
  double measure = 0.0;   ///< R the round's sizes realised (> 0; may differ from the one asked for)
  std::size_t count = 0;  ///< tets it gave
  bool finest = false;    ///< the sizes are at their finest: a larger R would change nothing
};

/// The rounds towards `target` tets (see the header comment). `round(R)` meshes for measure R and
/// reports what it got; the first call gets R = 0, meaning the caller's initial sizes. Returns every
/// round, the last one being the mesh kept. Does not throw for a budget missed: budget_missed tells,
/// and the caller words the error for its own keys.
std::vector<BudgetRound> meet_count_budget(std::size_t target, const std::function<BudgetRound(double)>& round);

/// True when the last round is more than 10 % off `target` (> 0).
bool budget_missed(std::size_t target, const std::vector<BudgetRound>& rounds);

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
