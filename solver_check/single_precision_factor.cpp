#include "solver_check/single_precision_factor.h"

#include <Eigen/Core>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <stdexcept>
#include <string>

namespace tissuemesh {
namespace {

using BlockMap = Eigen::Map<const Eigen::MatrixXf, 0, Eigen::OuterStride<>>;
using VectorMap = Eigen::Map<Eigen::VectorXf>;

/// Opening stops when the larger bin holds at most this much more than half the bins' entries
/// (closer balance than the two threads' noise buys nothing), or after this many steps.
constexpr double kBalance = 1.05;
constexpr int kMaxOpened = 256;

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
  auto refuse = [](const std::string& what) { throw std::invalid_argument("supernodal factor: " + what); };
  const int ns = f.nsuper;
  if (f.n <= 0 || ns <= 0 || f.super[0] != 0 || f.super[ns] != f.n || f.pi[0] != 0 || f.px[0] != 0)
    refuse("the supernodes do not cover the columns 0.." + std::to_string(f.n - 1));
  n_ = f.n;
  super_.assign(f.super, f.super + ns + 1);
  pi_.assign(f.pi, f.pi + ns + 1);
  px_.assign(f.px, f.px + ns + 1);
  rows_ = f.rows;
  perm_.resize(n_);
  std::vector<char> seen(n_, 0);
  for (int k = 0; k < n_; ++k) {
    perm_[k] = f.perm ? f.perm[k] : k;
    if (perm_[k] < 0 || perm_[k] >= n_ || seen[perm_[k]]++) refuse("the permutation is not one of 0.." + std::to_string(n_ - 1));
  }
  std::vector<int> col_super(n_, -1);  // the supernode of each column
  std::size_t widest = 0;
  for (int s = 0; s < ns; ++s) {
    const int nscol = super_[s + 1] - super_[s], nsrow = pi_[s + 1] - pi_[s];
    if (nscol <= 0 || nsrow < nscol || px_[s + 1] - px_[s] < static_cast<std::int64_t>(nsrow) * nscol)
      refuse("supernode " + std::to_string(s) + " has an inconsistent block");
    for (int i = 0; i < nsrow; ++i) {
      const int r = rows_[pi_[s] + i];
      if (i < nscol ? r != super_[s] + i : r < super_[s + 1] || r >= n_)
        refuse("supernode " + std::to_string(s) + " has row " + std::to_string(r) + " at position " + std::to_string(i));
    }
    for (int j = 0; j < nscol; ++j) col_super[super_[s] + j] = s;
    widest = std::max(widest, static_cast<std::size_t>(nsrow));
  }

  // The elimination tree of the supernodes: a supernode's parent holds its first off-diagonal row.
  std::vector<int> parent(ns, -1), first(ns), count(ns, 1);
  std::vector<double> work(ns);
  std::vector<std::vector<int>> children(ns);
  std::iota(first.begin(), first.end(), 0);
  double total = 0.0;
  for (int s = 0; s < ns; ++s) {
    const int nscol = super_[s + 1] - super_[s], nsrow = pi_[s + 1] - pi_[s];
    work[s] += static_cast<double>(nsrow) * nscol;
    total += static_cast<double>(nsrow) * nscol;
    if (nsrow > nscol) parent[s] = col_super[rows_[pi_[s] + nscol]];
    if (parent[s] >= 0) {
      if (parent[s] <= s) refuse("the elimination tree is not ordered");
      children[parent[s]].push_back(s);
      work[parent[s]] += work[s];  // work[s] is complete: all of s's descendants come before s
      first[parent[s]] = std::min(first[parent[s]], first[s]);
      count[parent[s]] += count[s];
    }
  }
  // Subtrees are contiguous ranges only in a postordered tree (CHOLMOD's default); otherwise no split.
  bool postordered = true;
  for (int s = 0; s < ns; ++s) postordered = postordered && count[s] == s - first[s] + 1;

  // Open up the largest subtree (its root joins the top) step by step; after each step the open
  // subtrees go largest-first into the lighter of two bins. The split kept is the step with the
  // least estimated time, top + larger bin (a nested-dissection tree often starts with a chain of
  // separator supernodes that must all be opened before it branches).
  std::vector<int> open;
  for (int s = 0; s < ns; ++s)
    if (parent[s] < 0) open.push_back(s);
  double top_work = 0.0, best_time = total;
  auto by_work = [&](int a, int b) { return work[a] > work[b] || (work[a] == work[b] && a < b); };
  std::array<std::vector<int>, 2> assigned;
  for (int opened = 0; postordered && !open.empty() && opened <= kMaxOpened; ++opened) {
    std::sort(open.begin(), open.end(), by_work);
    std::array<double, 2> load{0.0, 0.0};
    std::array<std::vector<int>, 2> bins;
    for (int s : open) {
      const int b = load[1] < load[0] ? 1 : 0;
      load[b] += work[s];
      bins[b].push_back(s);
    }
    const double time = top_work + std::max(load[0], load[1]);
    if (!bins[1].empty() && time < best_time) {
      best_time = time;
      assigned = bins;
    }
    const int largest = open.front();
    if (children[largest].empty() || std::max(load[0], load[1]) <= kBalance * 0.5 * (load[0] + load[1])) break;
    top_work += work[largest] - std::accumulate(children[largest].begin(), children[largest].end(), 0.0,
                                                [&](double sum, int c) { return sum + work[c]; });
    if (top_work >= best_time) break;  // no later step can beat the best
    open.erase(open.begin());
    open.insert(open.end(), children[largest].begin(), children[largest].end());
  }
  // Supernodes in no bin are the top part, solved in increasing order.
  std::vector<char> in_bin(ns, 0);
  for (int b = 0; b < 2; ++b) {
    bins_[b].clear();
    for (int root : assigned[b]) {
      bins_[b].push_back({first[root], root});
      std::fill(in_bin.begin() + first[root], in_bin.begin() + root + 1, 1);
    }
    std::sort(bins_[b].begin(), bins_[b].end(), [](const Subtree& a, const Subtree& c) { return a.first < c.first; });
  }
  top_.clear();
  double top_entries = 0.0;
  for (int s = 0; s < ns; ++s)
    if (!in_bin[s]) {
      top_.push_back(s);
      top_entries += static_cast<double>(pi_[s + 1] - pi_[s]) * (super_[s + 1] - super_[s]);
    }
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
  const BlockMap block(values_ + px_[s], nsrow, nscol, Eigen::OuterStride<>(nsrow));
  VectorMap own(y + k1, nscol);
  block.topRows(nscol).triangularView<Eigen::Lower>().solveInPlace(own);
  if (below == 0) return;
  VectorMap update(scratch.data(), below);
  update.noalias() = block.bottomRows(below) * own;
  const int* row = rows_ + pi_[s] + nscol;
  // Rows of this subtree's columns are updated in place, the others (top rows) in the bin's buffer.
  const int lo = first >= 0 ? super_[first] : 0, hi = first >= 0 ? super_[last + 1] : n_;
  for (int i = 0; i < below; ++i) {
    const int r = row[i];
    (r >= lo && r < hi ? y : outside)[r] -= update[i];
  }
}

void SinglePrecisionFactor::backward(int s, float* y, std::vector<float>& scratch) const {
  const int k1 = super_[s], nscol = super_[s + 1] - k1, nsrow = pi_[s + 1] - pi_[s], below = nsrow - nscol;
  const BlockMap block(values_ + px_[s], nsrow, nscol, Eigen::OuterStride<>(nsrow));
  VectorMap own(y + k1, nscol);
  if (below > 0) {
    VectorMap known(scratch.data(), below);
    const int* row = rows_ + pi_[s] + nscol;
    for (int i = 0; i < below; ++i) known[i] = y[row[i]];
    own.noalias() -= block.bottomRows(below).transpose() * known;
  }
  block.topRows(nscol).triangularView<Eigen::Lower>().transpose().solveInPlace(own);
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
      for (const Subtree& t : bins_[b])
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
