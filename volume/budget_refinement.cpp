#include "volume/budget_refinement.h"

#include "core/errors.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace tissuemesh {

namespace {

// Rounds stop this close to the target (the optimisers and repairs after refinement change the
// count by well under 1 %); further off than kTolerance at the end is an input error.
constexpr double kSlack = 0.05;
constexpr double kTolerance = 0.10;
constexpr int kRounds = 4;

}  // namespace

DirectSizing refine_to_budget(const ImageSizingParams& params, std::size_t components,
                              const std::function<ImageSizing(const ImageSizingParams&)>& size,
                              const std::function<std::size_t(const ImageSizing&)>& refine) {
  DirectSizing result;
  result.target_tets = params.target_tets;
  ImageSizingParams sp = params;
  const double target = static_cast<double>(params.target_tets);
  std::vector<double> raws;
  ImageSizing sizing;
  for (int round = 0;; ++round) {
    sizing = size(sp);
    const double tets = static_cast<double>(refine(sizing));
    const double raw = sizing.predicted_tets * sp.tet_volume_factor;
    result.attempts.push_back({sizing.global_edge_mm, sizing.predicted_tets, static_cast<std::size_t>(tets)});
    raws.push_back(raw);
    const double off = tets / target;
    if (std::abs(off - 1.0) <= kSlack || round + 1 >= kRounds || tets == 0) break;
    if (off < 1.0 && sizing.global_edge_mm <= sizing.min_edge_mm * 1.0001) break;  // finest edges everywhere
    if (raws.size() >= 2 && std::abs(raw / raws[raws.size() - 2] - 1.0) < 1e-9) break;  // sizes at their limits
    double next_raw = raw / off;
    if (raws.size() >= 2) {
      const double r0 = raws[raws.size() - 2];
      const double n0 = static_cast<double>(result.attempts[result.attempts.size() - 2].refined_tets);
      if (std::abs(std::log(raw / r0)) > 1e-6 && n0 > 0) {
        const double exponent = std::log(tets / n0) / std::log(raw / r0);
        if (exponent < 0.1 && off > 1.0) break;
        if (exponent >= 0.1) next_raw = raw * std::pow(target / tets, 1.0 / exponent);
      }
    }
    sp.tet_volume_factor = next_raw / target;
  }

  const auto& last = result.attempts.back();
  const double off = static_cast<double>(last.refined_tets) / target - 1.0;
  if (std::abs(off) > kTolerance) {
    std::ostringstream e;
    e << "direct.target_tets: a budget of " << params.target_tets << " tets cannot be met on this image; the "
      << "refinements gave";
    for (const auto& a : result.attempts) e << " " << a.refined_tets;
    e << " tets";
    if (off > 0) {
      std::size_t closest = last.refined_tets;
      for (const auto& a : result.attempts) closest = std::min(closest, a.refined_tets);
      e << ". Its " << components << " tissue components and thin parts hold the count up (the closest was "
        << closest << "): raise direct.target_tets to at least " << (closest + closest / 10)
        << ", or let more small components join their surroundings (direct.min_component_mm3)";
    } else {
      std::size_t most = 0;
      for (const auto& a : result.attempts) most = std::max(most, a.refined_tets);
      e << " (smallest edge " << sizing.min_edge_mm << " mm): lower direct.target_tets to at most " << most
        << " or direct.min_edge_mm";
    }
    throw InputError(e.str());
  }
  result.min_edge_mm = sizing.min_edge_mm;
  result.global_edge_mm = sizing.global_edge_mm;
  result.thickness_scale = sizing.thickness_scale;
  result.coarsened = sizing.coarsened;
  result.tet_volume_factor = sp.tet_volume_factor;
  return result;
}

}  // namespace tissuemesh
