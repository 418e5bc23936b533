// compare_solutions (solver_check/solution_comparison.h): the figures of the CalculiX cross-check
// on fields whose answer is known by hand.
#include "solver_check/solution_comparison.h"

#include "core/errors.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace tissuemesh {
namespace {

using Field = std::vector<Eigen::Vector3d>;

TEST(SolutionComparison, FiguresOfAHandMadeField) {
  // Reference: |u| = 0, 5, 10 (largest at node 2). Other differs by 0, (0, 0.3, 0.4) = 0.5 and 0.1.
  const Field ref{{0, 0, 0}, {3, 4, 0}, {0, 0, -10}};
  const Field other{{0, 0, 0}, {3, 4.3, 0.4}, {0, 0, -10.1}};
  const SolutionComparison c = compare_solutions(ref, other);
  EXPECT_NEAR(c.max_diff, 0.5, test::kRelativeRoundoff);
  EXPECT_EQ(c.max_diff_node, 1);
  EXPECT_NEAR(c.mean_diff, 0.6 / 3.0, test::kRelativeRoundoff);
  EXPECT_EQ(c.max_u_reference, 10.0);
  EXPECT_NEAR(c.max_u_other, 10.1, test::kRelativeRoundoff);
  EXPECT_NEAR(c.max_diff_rel, 0.05, test::kRelativeRoundoff);
  EXPECT_NEAR(c.mean_diff_rel, 0.02, test::kRelativeRoundoff);
}

TEST(SolutionComparison, RelativeToTheReferenceNotTheOther) {
  // Swapping the roles changes the denominator only.
  const Field a{{0, 2, 0}, {0, 0, 0}};
  const Field b{{0, 4, 0}, {0, 0, 0}};
  EXPECT_EQ(compare_solutions(a, b).max_diff_rel, 1.0);
  EXPECT_EQ(compare_solutions(b, a).max_diff_rel, 0.5);
  EXPECT_EQ(compare_solutions(b, a).mean_diff_rel, 0.25);
}

TEST(SolutionComparison, IdenticalFieldsDifferByZero) {
  const Field u{{1, 2, 3}, {-1, 0, 0.5}};
  const SolutionComparison c = compare_solutions(u, u);
  EXPECT_EQ(c.max_diff, 0.0);
  EXPECT_EQ(c.mean_diff, 0.0);
  EXPECT_EQ(c.max_diff_rel, 0.0);
  EXPECT_EQ(c.max_diff_node, 0);
  EXPECT_EQ(c.max_u_reference, c.max_u_other);
}

TEST(SolutionComparison, ReferenceAtRest) {
  const Field zero(3, Eigen::Vector3d::Zero());
  EXPECT_EQ(compare_solutions(zero, zero).max_diff_rel, 0.0);
  Field moved = zero;
  moved[2] = {0, 0, 1e-3};
  const SolutionComparison c = compare_solutions(zero, moved);
  EXPECT_EQ(c.max_diff_rel, std::numeric_limits<double>::infinity());
  EXPECT_EQ(c.mean_diff_rel, std::numeric_limits<double>::infinity());
  EXPECT_EQ(c.max_diff_node, 2);
}

TEST(SolutionComparison, RefusesMismatchedEmptyOrNonFiniteFields) {
  const Field two{{0, 0, 0}, {1, 0, 0}};
  EXPECT_THROW(compare_solutions(two, Field{{0, 0, 0}}), InputError);
  EXPECT_THROW(compare_solutions(Field{}, Field{}), InputError);
  Field bad = two;
  bad[1].y() = std::nan("");
  try {
    compare_solutions(two, bad);
    FAIL() << "not refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("node 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tissuemesh
