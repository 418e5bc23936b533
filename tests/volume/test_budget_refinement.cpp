// The budget rounds against manufactured count laws N(R) of the raw sum R: a power law with an
// offset is met within 5 % in at most four rounds; a count that hardly follows the sizes (a
// floor above the budget) and sizes stuck at their limits are input errors that say which way
// to move the budget, after as few rounds as it takes to see it.
#include "core/errors.h"
#include "volume/budget_refinement.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace tissuemesh;

namespace {

ImageSizingParams budget(std::size_t target) {
  ImageSizingParams p;
  p.target_tets = target;
  p.tet_volume_factor = 0.015;
  return p;
}

// What size_from_image would give for an image whose raw sum at the solved sizes is `raw(f)`:
// the prediction raw / f meets the target unless the sizes are clamped.
ImageSizing sized(double predicted) {
  ImageSizing s;
  s.predicted_tets = predicted;
  s.global_edge_mm = 5.0;
  s.min_edge_mm = 0.5;
  return s;
}

}  // namespace

TEST(BudgetRefinement, PowerLawWithAnOffsetIsMetInFourRounds) {
  for (double exponent : {0.6, 1.0, 1.4}) {
    const auto p = budget(300000);
    double factor = 0.015;
    int rounds = 0;
    const DirectSizing met = refine_to_budget(
        p, 100,
        [&](const ImageSizingParams& q) {
          factor = q.tet_volume_factor;
          return sized(static_cast<double>(q.target_tets));
        },
        [&](const ImageSizing& s) {
          ++rounds;
          const double raw = s.predicted_tets * factor;  // = target * factor
          return static_cast<std::size_t>(40000 + 2.0e6 * std::pow(raw / 4500.0, exponent));
        });
    const double n = static_cast<double>(met.attempts.back().refined_tets);
    EXPECT_NEAR(n / 300000.0, 1.0, 0.05) << "exponent " << exponent;
    EXPECT_LE(rounds, 4);
  }
}

TEST(BudgetRefinement, AFloorAboveTheBudgetIsAnInputErrorNamingALargerBudget) {
  double factor = 0.015;
  int rounds = 0;
  try {
    refine_to_budget(
        budget(300000), 1128,
        [&](const ImageSizingParams& q) {
          factor = q.tet_volume_factor;
          return sized(static_cast<double>(q.target_tets));
        },
        [&](const ImageSizing& s) {
          ++rounds;
          return static_cast<std::size_t>(450000 + 10.0 * s.predicted_tets * factor);  // ~flat in the sizes
        });
    FAIL() << "a floor of 450,000 tets cannot meet a budget of 300,000";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("1128 tissue components"), std::string::npos) << m;
    EXPECT_NE(m.find("raise direct.target_tets to at least"), std::string::npos) << m;
  }
  EXPECT_EQ(rounds, 2) << "two rounds show the count does not follow the sizes";
}

TEST(BudgetRefinement, SizesAtTheirLimitsStopAndNameASmallerBudget) {
  int rounds = 0;
  try {
    refine_to_budget(
        budget(5000000), 10,
        // Clamped sizes: the raw sum (prediction x factor) stays 1000 whatever the factor.
        [&](const ImageSizingParams& q) { return sized(1000.0 / q.tet_volume_factor); },
        [&](const ImageSizing&) {
          ++rounds;
          return std::size_t{80000};
        });
    FAIL() << "80,000 tets at the finest sizes cannot meet 5,000,000";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lower direct.target_tets to at most 80000"), std::string::npos) << e.what();
  }
  EXPECT_EQ(rounds, 2);
}
