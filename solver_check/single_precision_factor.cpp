// Why: each CG iteration applies the kept factorisation once (a forward and a backward triangular
// solve through all its entries), which costs many times the multiplication by K; the solves
// stream the factor from memory. Single precision halves the bytes, and the elimination tree of a
// nested-dissection ordering splits into independent subtrees that two threads solve at the same
// time. A preconditioner only has to be close to K^-1: the float factor's relative error (~1e-7)
// leaves CG's convergence unchanged, and CG itself still works on K in double precision, so the
// solution's accuracy does not change. The conversion is in place because a separate float copy
// would raise the solve's peak memory by half the factor's size.
#include "solver_check/single_precision_factor.h"

#include <Eigen/Core>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <stdexcept>
#include <string>

namespace tissuemesh {
namespace {

using VectorMap = Eigen::Map<Eigen::VectorXf>;

}  // namespace

void SinglePrecisionFactor::assign(const SupernodalFactorView& f) {
  SinglePrecisionFactor next;
  next.plan(f);  // every check and allocation; f is not touched
  // To single precision in place, in increasing order: float i (bytes 4i..4i+3) only overwrites
  // doubles before i, which were read already.
  float* converted = reinterpret_cast<float*>(f.values);
  for (std::int64_t i = 0; i < next.px_.back(); ++i) {
    double v;
    std::memcpy(&v, f.values + i, sizeof v);
    const float w = static_cast<float>(v);
    std::memcpy(converted + i, &w, sizeof w);
  }
  next.values_ = converted;
  *this = std::move(next);
}

void SinglePrecisionFactor::plan(const SupernodalFactorView& f) {
  const std::vector<int> parent = supernode_parents(f);  // every check
  const int ns = f.nsuper;
  n_ = f.n;
  super_.assign(f.super, f.super + ns + 1);
  pi_.assign(f.pi, f.pi + ns + 1);
  px_.assign(f.px, f.px + ns + 1);
  rows_ = f.rows;
  perm_.resize(n_);
  for (int k = 0; k < n_; ++k) perm_[k] = f.perm ? f.perm[k] : k;
  // A solve's work: the entries it streams.
  std::vector<double> entries(ns);
  std::size_t widest = 0;
  double total = 0.0;
  for (int s = 0; s < ns; ++s) {
    const int nsrow = pi_[s + 1] - pi_[s];
    entries[s] = static_cast<double>(nsrow) * (super_[s + 1] - super_[s]);
    total += entries[s];
    widest = std::max(widest, static_cast<std::size_t>(nsrow));
  }
  const TreeSplit split = split_tree(parent, entries);
  bins_ = split.bins;
  top_ = split.top;
  double top_entries = 0.0;
  for (int s : top_) top_entries += entries[s];
  top_share_ = total > 0.0 ? top_entries / total : 1.0;

  y_.assign(n_, 0.0f);
  for (int b = 0; b < 2; ++b) {
    outside_[b].assign(n_, 0.0f);
    scratch_[b].assign(widest, 0.0f);
  }
}

void SinglePrecisionFactor::forward(int s, float* y, float* outside, int first, int last,
                                    std::vector<float>& scratch) const {
  const int k1 = super_[s], nscol = super_[s + 1] - k1, nsrow = pi_[s + 1] - pi_[s], below = nsrow - nscol;
  const float* block = values_ + px_[s];
  // One pass over the block's columns: w = (the supernode's own unknowns, its updates of the rows
  // below); column j divides w[j] by the pivot and subtracts the column times w[j] from w[j + 1:].
  float* w = scratch.data();
  std::copy(y + k1, y + k1 + nscol, w);
  std::fill(w + nscol, w + nsrow, 0.0f);
  for (int j = 0; j < nscol; ++j) {
    const float* column = block + static_cast<std::ptrdiff_t>(j) * nsrow;
    const float wj = w[j] / column[j];
    w[j] = wj;
    const int n = nsrow - j - 1;
    VectorMap(w + j + 1, n).noalias() -= wj * Eigen::Map<const Eigen::VectorXf>(column + j + 1, n);
  }
  std::copy(w, w + nscol, y + k1);
  if (below == 0) return;
  const int* row = rows_ + pi_[s] + nscol;
  // Rows of this subtree's columns are updated in place, the others (top rows) in the bin's buffer.
  const int lo = first >= 0 ? super_[first] : 0, hi = first >= 0 ? super_[last + 1] : n_;
  for (int i = 0; i < below; ++i) {
    const int r = row[i];
    (r >= lo && r < hi ? y : outside)[r] += w[nscol + i];
  }
}

void SinglePrecisionFactor::backward(int s, float* y, std::vector<float>& scratch) const {
  const int k1 = super_[s], nscol = super_[s + 1] - k1, nsrow = pi_[s + 1] - pi_[s], below = nsrow - nscol;
  const float* block = values_ + px_[s];
  // w = (own unknowns, the known values of the rows below); column j, last to first:
  // w[j] = (w[j] - column[j + 1:] . w[j + 1:]) / pivot.
  float* w = scratch.data();
  std::copy(y + k1, y + k1 + nscol, w);
  const int* row = rows_ + pi_[s] + nscol;
  for (int i = 0; i < below; ++i) w[nscol + i] = y[row[i]];
  for (int j = nscol - 1; j >= 0; --j) {
    const float* column = block + static_cast<std::ptrdiff_t>(j) * nsrow;
    const int n = nsrow - j - 1;
    const float dot = Eigen::Map<const Eigen::VectorXf>(column + j + 1, n).dot(Eigen::Map<const Eigen::VectorXf>(w + j + 1, n));
    w[j] = (w[j] - dot) / column[j];
  }
  std::copy(w, w + nscol, y + k1);
}

void SinglePrecisionFactor::solve(const Eigen::VectorXd& r, Eigen::VectorXd& z, int threads) {
  float* y = y_.data();
  for (int k = 0; k < n_; ++k) y[k] = static_cast<float>(r[perm_[k]]);
  const bool split = !bins_[0].empty() && !bins_[1].empty();
  threads = split ? std::clamp(threads, 1, 2) : 1;
  // L y = P r: the bins' subtrees (two threads), their updates of top rows added in bin order, then the top.
  if (split) {
#pragma omp parallel for num_threads(threads) schedule(static, 1)
    for (int b = 0; b < 2; ++b)
      for (const SubtreeRange& t : bins_[b])
        for (int s = t.first; s <= t.last; ++s) forward(s, y, outside_[b].data(), t.first, t.last, scratch_[b]);
    for (int s : top_)
      for (int k = super_[s]; k < super_[s + 1]; ++k) {
        y[k] += outside_[0][k];
        y[k] += outside_[1][k];
        outside_[0][k] = outside_[1][k] = 0.0f;
      }
  }
  for (int s : top_) forward(s, y, y, -1, -1, scratch_[0]);
  // L^T w = y: the top first, then the bins' subtrees (two threads; each reads only its own rows and the top's).
  for (auto it = top_.rbegin(); it != top_.rend(); ++it) backward(*it, y, scratch_[0]);
  if (split) {
#pragma omp parallel for num_threads(threads) schedule(static, 1)
    for (int b = 0; b < 2; ++b)
      for (auto t = bins_[b].rbegin(); t != bins_[b].rend(); ++t)
        for (int s = t->last; s >= t->first; --s) backward(s, y, scratch_[b]);
  }
  z.resize(n_);
  for (int k = 0; k < n_; ++k) z[perm_[k]] = y[k];
}

}  // namespace tissuemesh
