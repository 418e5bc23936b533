// Why: CHOLMOD's numeric factorisation works through the supernodes one after the other, and its
// BLAS runs on one thread (cholmod_llt.cpp: more BLAS threads change the last bits with their
// count and stall on a busy machine). A nested-dissection ordering's tree splits below its top
// separators into independent subtrees; here two threads factorise them at once, each calling
// BLAS on one thread, and the top follows: its wide supernodes (the root separator of a 3D mesh
// holds nearly a third of the flops) by panels on both threads, the others on one. With the
// panels the root's dense factorisation takes about half the time it takes on one thread.
//
// Algorithm (right-looking supernodal): a supernode whose block holds A's entries less the updates
// of all its descendants is factorised (dpotrf on its diagonal block, dtrsm below it) and sends its
// update L_below L_mine^T (dsyrk, dgemm) to every ancestor its rows reach, in the order of its
// rows. The updates go straight into the ancestor's block (only one thread touches a bin's
// supernodes), except bin 1's updates of top supernodes: they go into a buffer, added to the top's
// blocks once both bins are done (bin 0 writes there meanwhile). Every entry thus receives the same
// operations in the same order whatever the thread count (one thread does bin 0, bin 1, then the
// top; a wide supernode is cut into the same panels and panel parts for any thread count).
#include "solver_check/supernodal_cholesky.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include <omp.h>

// BLAS and LAPACK (Fortran interface; the trailing arguments are the hidden lengths of the
// character arguments). Debian links them to OpenBLAS. Two threads call them at once only when
// OpenBLAS runs each call on the caller's thread (one BLAS thread, cholmod_llt.cpp's default;
// the caller passes threads = 1 otherwise).
extern "C" {
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info, std::size_t);
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb, std::size_t,
            std::size_t, std::size_t, std::size_t);
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const double* a,
            const int* lda, const double* beta, double* c, const int* ldc, std::size_t, std::size_t);
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc, std::size_t, std::size_t);
}

namespace tissuemesh {

namespace {

/// Top supernodes with at least kPanelledColumns columns are factorised panel by panel, kPanel
/// columns at a time, on two threads (SupernodalCholesky::factorise_panelled); narrower ones by one
/// dpotrf and one dtrsm. The top of a 3D mesh's tree is typically one supernode of over a
/// thousand columns with nearly a third of the flops, which one dpotrf would do on one thread
/// while the other waits.
constexpr int kPanelledColumns = 256;
constexpr int kPanel = 128;

}  // namespace

void SupernodalCholesky::plan(const SupernodalFactorView& f, const Eigen::SparseMatrix<double>& K) {
  auto refuse = [](const std::string& what) { throw std::invalid_argument("supernodal Cholesky: " + what); };
  const std::vector<int> parent = supernode_parents(f);
  const int n = f.n, ns = f.nsuper;
  if (K.rows() != n || K.cols() != n) refuse("the matrix is not " + std::to_string(n) + " x " + std::to_string(n));
  if (!K.isCompressed()) refuse("the matrix is not compressed");
  std::vector<int> col_super(n);
  for (int s = 0; s < ns; ++s) {
    const int nscol = f.super[s + 1] - f.super[s];
    std::fill(col_super.begin() + f.super[s], col_super.begin() + f.super[s + 1], s);
    for (int i = f.pi[s] + nscol + 1; i < f.pi[s + 1]; ++i)
      if (f.rows[i] <= f.rows[i - 1]) refuse("the rows of supernode " + std::to_string(s) + " do not increase");
  }
  std::vector<int> inverse(n);
  for (int k = 0; k < n; ++k) inverse[f.perm ? f.perm[k] : k] = k;

  SupernodalCholesky next;
  // Where each of K's entries goes: row max(a, b), column min(a, b) of L for its permuted indices.
  next.destination_.resize(static_cast<std::size_t>(K.nonZeros()));
  for (int j = 0; j < n; ++j)
    for (int e = K.outerIndexPtr()[j]; e < K.outerIndexPtr()[j + 1]; ++e) {
      const int i = K.innerIndexPtr()[e];
      if (i < j) refuse("the matrix has an entry above its diagonal (" + std::to_string(i) + ", " + std::to_string(j) + ")");
      const int r = std::max(inverse[i], inverse[j]), c = std::min(inverse[i], inverse[j]);
      const int s = col_super[c], k1 = f.super[s], nscol = f.super[s + 1] - k1, nsrow = f.pi[s + 1] - f.pi[s];
      int position = r - k1;
      if (r >= f.super[s + 1]) {
        const int* below = f.rows + f.pi[s] + nscol;
        const int* end = f.rows + f.pi[s + 1];
        const int* at = std::lower_bound(below, end, r);
        if (at == end || *at != r)
          refuse("the matrix's entry (" + std::to_string(i) + ", " + std::to_string(j) + ") is outside the factor's pattern");
        position = nscol + static_cast<int>(at - below);
      }
      next.destination_[e] = f.px[s] + (c - k1) * nsrow + position;
    }
  next.diagonal_.resize(n);
  for (int k = 0; k < n; ++k) {
    const int s = col_super[k], nsrow = f.pi[s + 1] - f.pi[s];
    next.diagonal_[k] = f.px[s] + (k - f.super[s]) * (nsrow + 1);
  }

  // Each supernode's sends (its rows below its columns, grouped by the supernode they fall in)
  // and its flops: dpotrf, dtrsm, and the updates it sends (dsyrk + dgemm).
  std::vector<double> work(ns, 0.0);
  std::vector<std::size_t> largest_product(ns, 0);  // of each supernode's sends
  std::size_t widest = 0;
  next.send_start_.assign(1, 0);
  for (int d = 0; d < ns; ++d) {
    const double k = f.super[d + 1] - f.super[d];
    const int nsrow = f.pi[d + 1] - f.pi[d], nscol = f.super[d + 1] - f.super[d];
    work[d] = k * k * k / 3.0 + (nsrow - k) * k * k;
    widest = std::max(widest, static_cast<std::size_t>(nsrow));
    for (int i = nscol; i < nsrow;) {
      const int target = col_super[f.rows[f.pi[d] + i]];
      int last = i;
      while (last < nsrow && f.rows[f.pi[d] + last] < f.super[target + 1]) ++last;
      // The rows below must be rows of the target too (eliminate() finds their positions there).
      const int* trows = f.rows + f.pi[target];
      for (int r = last, at = f.super[target + 1] - f.super[target]; r < nsrow; ++r) {
        const int row = f.rows[f.pi[d] + r];
        while (at < f.pi[target + 1] - f.pi[target] && trows[at] < row) ++at;
        if (at == f.pi[target + 1] - f.pi[target] || trows[at] != row)
          refuse("row " + std::to_string(row) + " of supernode " + std::to_string(d) + " is not a row of supernode " +
                 std::to_string(target));
      }
      next.sends_.push_back({target, i, last});
      const double m = nsrow - i, w = last - i;
      work[d] += w * w * k + 2.0 * (m - w) * w * k;
      largest_product[d] = std::max(largest_product[d], static_cast<std::size_t>(nsrow - i) * (last - i));
      i = last;
    }
    next.send_start_.push_back(static_cast<int>(next.sends_.size()));
  }
  next.split_ = split_tree(parent, work);
  next.bin_.assign(ns, -1);
  for (int b = 0; b < 2; ++b)
    for (const SubtreeRange& t : next.split_.bins[b]) std::fill(next.bin_.begin() + t.first, next.bin_.begin() + t.last + 1, b);
  // A bin's supernodes update only their own bin or the top (what keeps the two threads apart).
  for (int d = 0; d < ns; ++d)
    for (int q = next.send_start_[d]; q < next.send_start_[d + 1]; ++q)
      if (const int t = next.sends_[q].target; next.bin_[t] != next.bin_[d] && next.bin_[t] != -1)
        refuse("supernode " + std::to_string(d) + " updates supernode " + std::to_string(t) + " of the other bin");
  double total = 0.0, top = 0.0;
  for (int s = 0; s < ns; ++s) total += work[s];
  next.top_offset_.assign(ns, -1);
  std::int64_t top_size = 0;
  for (int s : next.split_.top) {
    top += work[s];
    next.panelled_ = next.panelled_ || f.super[s + 1] - f.super[s] >= kPanelledColumns;
    next.top_offset_[s] = top_size;
    top_size += static_cast<std::int64_t>(f.pi[s + 1] - f.pi[s]) * (f.super[s + 1] - f.super[s]);
  }
  next.top_share_ = total > 0.0 ? top / total : 1.0;
  // Work space: thread 0 does bin 0 and the top, thread 1 bin 1.
  for (int s = 0; s < ns; ++s) {
    std::vector<double>& product = next.product_[next.bin_[s] == 1 ? 1 : 0];
    if (product.size() < largest_product[s]) product.resize(largest_product[s]);
  }
  for (int b = 0; b < 2; ++b) next.position_[b].resize(widest);
  if (next.split_.split()) next.buffer_.resize(static_cast<std::size_t>(top_size));
  next.outer_.assign(K.outerIndexPtr(), K.outerIndexPtr() + n + 1);
  next.inner_.assign(K.innerIndexPtr(), K.innerIndexPtr() + K.nonZeros());
  next.n_ = n;
  next.nsuper_ = ns;
  next.super_ = f.super;
  next.pi_ = f.pi;
  next.px_ = f.px;
  next.rows_ = f.rows;
  next.values_ = f.values;
  *this = std::move(next);
}

bool SupernodalCholesky::factorise_panelled(int s, int threads) {
  static const double one = 1.0, minus_one = -1.0;
  const int nscol = super_[s + 1] - super_[s], nsrow = pi_[s + 1] - pi_[s];
  double* L = values_ + px_[s];
  // Element (i, j) of the block (rows: the supernode's own columns, then its rows below).
  const auto at = [&](int i, int j) { return L + static_cast<std::ptrdiff_t>(j) * nsrow + i; };
  std::atomic<bool> failed{false};
  // Right-looking by panels: factorise the panel's diagonal block (one thread), solve the rows
  // below it in the block (two fixed halves of the rows), update the columns right of it (two
  // fixed parts of about equal work). The parts do not depend on the thread count: with one
  // thread it runs both, in order, with the same calls, so the bits are the same.
#pragma omp parallel num_threads(std::clamp(threads, 1, 2))
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    for (int kb = 0; kb < nscol; kb += kPanel) {
      const int b = std::min(kPanel, nscol - kb), rest = nsrow - kb - b;
#pragma omp single
      {
        int info = 0;
        dpotrf_("L", &b, at(kb, kb), &nsrow, &info, 1);
        for (int j = kb; j < kb + b && info == 0; ++j)
          if (!std::isfinite(*at(j, j))) info = 1;
        if (info != 0) failed = true;
      }  // (implicit barrier: every thread sees the same `failed`)
      if (failed) break;
      if (rest == 0) break;
      for (int part = t; part < 2; part += nt) {
        const int first = kb + b + rest * part / 2, rows = kb + b + rest * (part + 1) / 2 - first;
        if (rows > 0) dtrsm_("R", "L", "T", "N", &rows, &b, &one, at(kb, kb), &nsrow, at(first, kb), &nsrow, 1, 1, 1, 1);
      }
#pragma omp barrier
      // Columns kb + b .. nscol - 1 minus the panel's contribution: column c has nsrow - c rows.
      const int c0 = kb + b;
      if (c0 < nscol) {
        double total = 0.0;
        for (int c = c0; c < nscol; ++c) total += nsrow - c;
        int middle = c0;
        for (double sum = 0.0; middle < nscol && sum < 0.5 * total; ++middle) sum += nsrow - middle;
        for (int part = t; part < 2; part += nt) {
          const int first = part == 0 ? c0 : middle, last = part == 0 ? middle : nscol, w = last - first;
          if (w == 0) continue;
          dsyrk_("L", "N", &w, &b, &minus_one, at(first, kb), &nsrow, &one, at(first, first), &nsrow, 1, 1);
          const int below = nsrow - last;
          if (below > 0)
            dgemm_("N", "T", &below, &w, &b, &minus_one, at(last, kb), &nsrow, at(first, kb), &nsrow, &one,
                   at(last, first), &nsrow, 1, 1);
        }
      }
#pragma omp barrier
    }
  }
  return !failed;
}

bool SupernodalCholesky::eliminate(int s, int bin, std::vector<double>& product, std::vector<int>& position,
                                   int threads) {
  static const double one = 1.0, zero = 0.0;
  const int k1 = super_[s], nscol = super_[s + 1] - k1, nsrow = pi_[s + 1] - pi_[s], below = nsrow - nscol;
  double* L = values_ + px_[s];
  const int* rows = rows_ + pi_[s];
  if (bin < 0 && nscol >= kPanelledColumns) {
    if (!factorise_panelled(s, threads)) return false;
  } else {
    int info = 0;
    dpotrf_("L", &nscol, L, &nsrow, &info, 1);
    if (info != 0) return false;
    for (int j = 0; j < nscol; ++j)
      if (!std::isfinite(L[j * (nsrow + 1)])) return false;
    if (below > 0) dtrsm_("R", "L", "T", "N", &below, &nscol, &one, L, &nsrow, L + nscol, &nsrow, 1, 1, 1, 1);
  }
  for (int q = send_start_[s]; q < send_start_[s + 1]; ++q) {
    const Send& send = sends_[q];
    const int t = send.target, m = nsrow - send.first, w = send.last - send.first, rest = m - w;
    // C (m x w, column-major) = L(first:, :) L(first:last, :)^T: its top w x w square (lower part) by
    // dsyrk, the rows below by dgemm.
    double* C = product.data();
    dsyrk_("L", "N", &w, &nscol, &one, L + send.first, &nsrow, &zero, C, &m, 1, 1);
    if (rest > 0)
      dgemm_("N", "T", &rest, &w, &nscol, &one, L + send.last, &nsrow, L + send.first, &nsrow, &zero, C + w, &m, 1, 1);
    // The rows' positions in the target's block: its own columns first, then its rows below them
    // (both increasing, like these rows).
    const int tk1 = super_[t], tnscol = super_[t + 1] - tk1, tnsrow = pi_[t + 1] - pi_[t];
    const int* trows = rows_ + pi_[t];
    for (int i = 0; i < w; ++i) position[i] = rows[send.first + i] - tk1;
    for (int i = w, at = tnscol; i < m; ++i) {
      const int r = rows[send.first + i];
      while (trows[at] < r) ++at;
      position[i] = at;
    }
    double* T = bin == 1 && bin_[t] < 0 ? buffer_.data() + top_offset_[t] : values_ + px_[t];
    for (int j = 0; j < w; ++j) {
      double* column = T + static_cast<std::ptrdiff_t>(position[j]) * tnsrow;
      const double* c = C + static_cast<std::ptrdiff_t>(j) * m;
      for (int i = j; i < m; ++i) column[position[i]] -= c[i];
    }
  }
  return true;
}

bool SupernodalCholesky::factorise(const Eigen::SparseMatrix<double>& K, double shift, int threads) {
  if (empty() || K.rows() != n_ || K.cols() != n_ || !K.isCompressed() ||
      static_cast<std::size_t>(K.nonZeros()) != inner_.size() ||
      !std::equal(outer_.begin(), outer_.end(), K.outerIndexPtr()) ||
      !std::equal(inner_.begin(), inner_.end(), K.innerIndexPtr()))
    throw std::invalid_argument("supernodal Cholesky: the matrix does not have the planned pattern");
  const bool split = split_.split();
  const int nt = split ? std::clamp(threads, 1, 2) : 1;
  const std::int64_t size = px_[nsuper_];
  const double* k = K.valuePtr();
  const std::int64_t entries = static_cast<std::int64_t>(destination_.size());
#pragma omp parallel num_threads(nt)
  {
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < size; ++i) values_[i] = 0.0;
#pragma omp for schedule(static)
    for (std::int64_t e = 0; e < entries; ++e) values_[destination_[e]] = k[e];  // distinct destinations
  }
  for (int i = 0; i < n_; ++i) values_[diagonal_[i]] += shift;

  std::atomic<bool> failed{false};
  if (split) {
#pragma omp parallel for num_threads(nt) schedule(static, 1)
    for (int b = 0; b < 2; ++b) {
      if (b == 1) std::fill(buffer_.begin(), buffer_.end(), 0.0);
      for (const SubtreeRange& t : split_.bins[b])
        for (int s = t.first; s <= t.last && !failed.load(std::memory_order_relaxed); ++s)
          if (!eliminate(s, b, product_[b], position_[b])) failed = true;
    }
    if (failed) return false;
    // Bin 1's updates of the top (bin 0's are in the top's blocks already).
    for (int s : split_.top) {
      const std::int64_t count = static_cast<std::int64_t>(pi_[s + 1] - pi_[s]) * (super_[s + 1] - super_[s]);
      double* block = values_ + px_[s];
      const double* update = buffer_.data() + top_offset_[s];
      for (std::int64_t i = 0; i < count; ++i) block[i] += update[i];
    }
  }
  // The top on this thread, its wide supernodes by panels on two (also when the tree does not split).
  for (int s : split_.top)
    if (!eliminate(s, -1, product_[0], position_[0], std::clamp(threads, 1, 2))) return false;
  return true;
}

}  // namespace tissuemesh
