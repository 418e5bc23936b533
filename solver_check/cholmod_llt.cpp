#include "solver_check/cholmod_llt.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>

namespace tissuemesh {

bool CholmodLLT::analyse_grouped(const Eigen::SparseMatrix<double>& K, const std::vector<int>& group) {
  cholmod_common& c = this->cholmod();
  const int n = static_cast<int>(K.rows());
  if (static_cast<int>(group.size()) != n || n == 0) return false;
  const int groups = group.back() + 1;
  std::vector<int> first(groups + 1, n);  // first unknown of each group
  for (int j = n - 1; j >= 0; --j) first[group[j]] = j;
  // Lower triangle of the group graph: group g's column holds the groups of every row of its
  // unknowns' columns (all >= g, as groups do not decrease), sorted, without repeats.
  std::vector<int> column_start(groups + 1, 0), row_groups, seen(groups, -1);
  for (int g = 0; g < groups; ++g) {
    const std::size_t start = row_groups.size();
    for (int j = first[g]; j < first[g + 1]; ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(K, j); it; ++it)
        if (const int h = group[it.row()]; seen[h] != g) {
          seen[h] = g;
          row_groups.push_back(h);
        }
    std::sort(row_groups.begin() + static_cast<std::ptrdiff_t>(start), row_groups.end());
    column_start[g + 1] = static_cast<int>(row_groups.size());
  }
  cholmod_sparse graph{};
  graph.nrow = graph.ncol = static_cast<std::size_t>(groups);
  graph.nzmax = row_groups.size();
  graph.p = column_start.data();
  graph.i = row_groups.data();
  graph.stype = -1;  // symmetric, lower triangle stored
  graph.itype = CHOLMOD_INT;
  graph.xtype = CHOLMOD_PATTERN;
  graph.dtype = CHOLMOD_DOUBLE;
  graph.sorted = 1;
  graph.packed = 1;
  std::vector<int> group_order(groups), order;
  // No postorder here: cholmod_analyze_p postorders the unknowns' elimination tree anyway.
  if (!cholmod_metis(&graph, nullptr, 0, 0, group_order.data(), &c)) return false;
  order.reserve(n);
  for (int g : group_order)
    for (int j = first[g]; j < first[g + 1]; ++j) order.push_back(j);
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_GIVEN;
  cholmod_sparse A = Eigen::viewAsCholmod(K.selfadjointView<Eigen::Lower>());
  cholmod_factor* L = cholmod_analyze_p(&A, order.data(), nullptr, 0, &c);
  if (!L) return false;
  if (m_cholmodFactor) cholmod_free_factor(&m_cholmodFactor, &c);
  m_cholmodFactor = L;
  this->m_isInitialized = true;
  this->m_info = Eigen::Success;
  m_analysisIsOk = true;
  m_factorizationIsOk = false;
  return true;
}

namespace {

/// OpenBLAS (Debian's BLAS for CHOLMOD here) splits a supernode's dense work by its thread count,
/// so the factor's last bits, and the solution's, change with that count. Its default count is the
/// number of processors (or $OMP_NUM_THREADS): the same model would give other bits on another
/// machine. So CHOLMOD's BLAS runs on kBlasThreads unless $OPENBLAS_NUM_THREADS says otherwise
/// (tests/solver/test_linear_solver.cpp shows the bits changing with the count).
/// One thread: OpenBLAS's threads synchronise at every multithreaded BLAS call of a factorisation,
/// and when other processes keep the cores busy each synchronisation waits for a time slice: a
/// solve beside other busy processes then takes several times longer with two BLAS threads than
/// with one, while on an idle machine two gain only about a tenth. Parameter sweeps run solves side
/// by side, and a busy machine is the common case; large tet10 models on idle many-core machines
/// gain from more threads (set the variable; docs/solver.md, "Determinism and threads"). The
/// function is looked up at run time, so another BLAS is left alone.
constexpr int kBlasThreads = 1;

}  // namespace

int blas_threads() {
  using Get = int (*)();
  const auto get = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  return get ? get() : 1;
}
void fix_blas_threads() {
  if (const char* env = std::getenv("OPENBLAS_NUM_THREADS"); env && std::atoi(env) > 0) return;
  using Set = void (*)(int);
  if (const auto set = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) set(kBlasThreads);
}

}  // namespace tissuemesh
