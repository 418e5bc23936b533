// ReducedAssembly (solver_check/reduced_assembly.h) on the block with a tilted sliding top, refined
// to 12,000 tets (two of the assembly's element chunks): the same bits for any thread count (each
// thread scatters its own range of the matrix and the force, in element order), the force equal
// to an independent element-order sum, and a force-only assembly that leaves the last tangent as
// it was (the Newton loop relies on it when it skips the tangent of a step expected to end an
// increment).
#include "solver/block_assembly.h"
#include "solver_check/element_kernel.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCore>

#include <memory>
#include <vector>

namespace tissuemesh {
namespace {

/// Bitwise equality of two vectors of doubles (EXPECT_EQ per entry, reporting the first mismatch).
void expect_same_bits(const double* a, const double* b, Eigen::Index n, const char* what) {
  for (Eigen::Index i = 0; i < n; ++i)
    if (a[i] != b[i]) {
      ADD_FAILURE() << what << " differs at entry " << i << ": " << a[i] << " vs " << b[i];
      return;
    }
}

TEST(ReducedAssembly, SameBitsForAnyThreadCount) {
  test::BlockAssembly b(2);
  ASSERT_GT(b.model.elements.size(), 8192u);  // more than one chunk (kChunk in reduced_assembly.cpp)
  const Eigen::VectorXd u = b.dofs->expand(b.smooth_q(0.3), 0.0);
  for (const bool nodal : {false, true}) {
    const std::vector<const HyperelasticLaw*>& laws = nodal ? b.rest : b.full;
    ReducedAssembly one(ElementOrder::Linear, b.model.elements, b.geometry, laws, *b.dofs, 1,
                        nodal ? b.nodal.get() : nullptr);
    const ReducedAssembly::Result reference = one.assemble(u, true);
    ASSERT_TRUE(reference.ok) << reference.note;
    ASSERT_GT(one.tangent().nonZeros(), 0);
    for (const int threads : {2, 3, 4}) {
      SCOPED_TRACE(::testing::Message() << (nodal ? "nodal pressure, " : "standard, ") << threads << " threads");
      ReducedAssembly many(ElementOrder::Linear, b.model.elements, b.geometry, laws, *b.dofs, threads,
                           nodal ? b.nodal.get() : nullptr);
      const ReducedAssembly::Result r = many.assemble(u, true);
      ASSERT_TRUE(r.ok) << r.note;
      EXPECT_EQ(r.energy, reference.energy);
      ASSERT_EQ(r.f_int.size(), reference.f_int.size());
      expect_same_bits(r.f_int.data(), reference.f_int.data(), r.f_int.size(), "f_int");
      ASSERT_EQ(many.tangent().nonZeros(), one.tangent().nonZeros());
      expect_same_bits(many.tangent().valuePtr(), one.tangent().valuePtr(), one.tangent().nonZeros(), "tangent");
    }
  }
}

TEST(ReducedAssembly, ForceIsTheElementOrderSumOfElementForces) {
  // Independent of the assembly's buffers and ranges: each element's force from the kernel, added
  // into the global vector in element order, as a serial scatter does. Same order of additions,
  // so the same bits.
  test::BlockAssembly b(2);
  const Eigen::VectorXd u = b.dofs->expand(b.smooth_q(0.3), 0.0);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(u.size());
  double energy = 0.0;
  ElementNodes ue(4, 3);
  for (std::size_t e = 0; e < b.model.elements.size(); ++e) {
    for (int a = 0; a < 4; ++a) ue.row(a) = u.segment<3>(3 * b.model.elements[e][a]).transpose();
    const ElementResponse r = element_response(b.geometry[e], ue, *b.full[e], ElementOutput::EnergyAndForce);
    ASSERT_TRUE(r.ok()) << e;
    energy += r.energy;
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) f[3 * b.model.elements[e][a] + i] += r.force[3 * a + i];
  }
  for (const int threads : {1, 2, 3}) {
    ReducedAssembly assembly(ElementOrder::Linear, b.model.elements, b.geometry, b.full, *b.dofs, threads);
    const ReducedAssembly::Result r = assembly.assemble(u, threads != 2);  // with and without the tangent
    ASSERT_TRUE(r.ok) << r.note;
    EXPECT_EQ(r.energy, energy) << threads << " threads";
    expect_same_bits(r.f_int.data(), f.data(), f.size(), "f_int");
  }
}

TEST(ReducedAssembly, ForceOnlyAssemblyKeepsTheLastTangent) {
  test::BlockAssembly b;
  ReducedAssembly& assembly = *b.with_nodal;  // two threads, nodal pressure: every path of assemble()
  const Eigen::VectorXd u1 = b.dofs->expand(b.smooth_q(0.3), 0.0), u2 = b.dofs->expand(b.smooth_q(0.5), 0.0);
  ASSERT_TRUE(assembly.assemble(u1, true).ok);
  const Eigen::SparseMatrix<double> K1 = assembly.tangent();
  const ReducedAssembly::Result r2 = assembly.assemble(u2, false);
  ASSERT_TRUE(r2.ok) << r2.note;
  expect_same_bits(assembly.tangent().valuePtr(), K1.valuePtr(), K1.nonZeros(), "tangent after a force-only assembly");
  // ... and the tangent at u2 does differ (so the comparison above could fail).
  ASSERT_TRUE(assembly.assemble(u2, true).ok);
  EXPECT_GT((assembly.tangent() - K1).norm(), 0.0);
}

}  // namespace
}  // namespace tissuemesh
