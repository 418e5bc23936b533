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

std::vector<BudgetRound> meet_count_budget(std::size_t target_tets, const std::function<BudgetRound(double)>& round) {
  const double target = static_cast<double>(target_tets);
  std::vector<BudgetRound> rounds;
  double next = 0.0;  // the first round: the caller's initial sizes
  for (;;) {
    const BudgetRound r = round(next);
    rounds.push_back(r);
    const double tets = static_cast<double>(r.count), raw = r.measure;
    const double off = tets / target;
    if (std::abs(off - 1.0) <= kSlack || static_cast<int>(rounds.size()) >= kRounds || r.count == 0) break;
    if (off < 1.0 && r.finest) break;
    if (rounds.size() >= 2 && std::abs(raw / rounds[rounds.size() - 2].measure - 1.0) < 1e-9) break;  // sizes at their limits
    next = raw / off;
    if (rounds.size() >= 2) {
      const double r0 = rounds[rounds.size() - 2].measure;
      const double n0 = static_cast<double>(rounds[rounds.size() - 2].count);
      if (std::abs(std::log(raw / r0)) > 1e-6 && n0 > 0) {
        const double exponent = std::log(tets / n0) / std::log(raw / r0);
        if (exponent < 0.1 && off > 1.0) break;
        if (exponent >= 0.1) next = raw * std::pow(target / tets, 1.0 / exponent);
      }
    }
  }
  return rounds;
}

bool budget_missed(std::size_t target, const std::vector<BudgetRound>& rounds) {
  return rounds.empty() ||
         std::abs(static_cast<double>(rounds.back().count) / static_cast<double>(target) - 1.0) > kTolerance;
}

DirectSizing refine_to_budget(const ImageSizingParams& params, std::size_t components,
                              const std::function<ImageSizing(const ImageSizingParams&)>& size,
                              const std::function<std::size_t(const ImageSizing&)>& refine) {
  DirectSizing result;
  result.target_tets = params.target_tets;
  ImageSizingParams sp = params;
  const double target = static_cast<double>(params.target_tets);
  ImageSizing sizing;
  // The measure is the raw sum (prediction x tet volume factor); the sizes solved for the budget
  // predict `target` tets, so the factor that aims at raw sum R is R / target.
  const std::vector<BudgetRound> rounds = meet_count_budget(params.target_tets, [&](double raw) {
    if (raw > 0.0) sp.tet_volume_factor = raw / target;
    sizing = size(sp);
    const std::size_t tets = refine(sizing);
    result.attempts.push_back({sizing.global_edge_mm, sizing.predicted_tets, tets});
    return BudgetRound{sizing.predicted_tets * sp.tet_volume_factor, tets,
                       sizing.global_edge_mm <= sizing.min_edge_mm * 1.0001};
  });

  const auto& last = result.attempts.back();
  const double off = static_cast<double>(last.refined_tets) / target - 1.0;
  if (budget_missed(params.target_tets, rounds)) {
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
