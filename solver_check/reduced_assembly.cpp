// Why this scheme: every element knows, for each pair of its reduced dofs, the slot of that entry
// in the matrix's value array, so assembly writes straight into the matrix (no triplets, no sort).
// Elements are taken in chunks of a few thousand; a chunk's elements are evaluated in parallel
// into a buffer, then scattered into the matrix and the force vector in element order by the same
// threads, each owning one contiguous range of the matrix's values and of the force vector. So
// the results do not depend on the thread count, the buffer stays small, and there are two
// synchronisations per chunk. Element colouring would need one per colour (~30), and each costs a
// scheduler time slice on a loaded machine: far slower than serial while other processes run. A
// serial scatter would take about a third of the assembly time. A thread skips the elements
// whose slots all lie in other threads' ranges (with the RCM numbering most do) and adds those
// wholly in its own without a range test, which saves another tenth, with the same bits.
#include "solver_check/reduced_assembly.h"

#include <omp.h>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <utility>

namespace tissuemesh {

namespace {

/// Reduced dofs of an element's nodes, node-major: (global reduced index, node slot a, column k).
struct LocalDofs {
  int count = 0;
  int global[30];
  int node[30];
  int column[30];
};

LocalDofs local_dofs(const std::array<int, 10>& element, int n, const DofMap& dofs) {
  LocalDofs d;
  for (int a = 0; a < n; ++a) {
    const int v = element[a];
    for (int k = 0; k < dofs.count(v); ++k) {
      d.global[d.count] = dofs.first(v) + k;
      d.node[d.count] = a;
      d.column[d.count] = k;
      ++d.count;
    }
  }
  return d;
}

/// Elements per parallel chunk: large enough that one synchronisation per chunk is negligible,
/// small enough that the chunk's buffer (up to 465 doubles per tet10) stays a few tens of MB.
constexpr int kChunk = 8192;

/// The contiguous range [first, second) of `size` entries (matrix values or force components)
/// that thread t of nt adds in the scatter.
std::pair<Eigen::Index, Eigen::Index> thread_range(Eigen::Index size, int t, int nt) {
  return {size * t / nt, size * (t + 1) / nt};
}

/// $OMP_NUM_THREADS when set, else every processor. Not omp_get_max_threads(): other libraries
/// in the process change it (initialising the Gmsh SDK, which the .msh writer does, sets it to 1).
int default_threads() {
  if (const char* env = std::getenv("OMP_NUM_THREADS"))
    if (const int n = std::atoi(env); n > 0) return n;
  return omp_get_num_procs();
}

}  // namespace

ReducedAssembly::ReducedAssembly(ElementOrder order, const std::vector<std::array<int, 10>>& elements,
                                 const std::vector<ElementGeometry>& geometry,
                                 const std::vector<const HyperelasticLaw*>& law, const DofMap& dofs, int threads,
                                 const NodalPressure* nodal)
    : n_(order == ElementOrder::Linear ? 4 : 10),
      elements_(elements),
      geometry_(geometry),
      law_(law),
      dofs_(dofs),
      threads_(threads > 0 ? threads : default_threads()),
      nodal_(nodal) {
  const int num_nodes = dofs.num_nodes();
  const int ne = static_cast<int>(elements.size());

  // Upper node graph in CSR: each node v, then the nodes w > v it shares an element (or a
  // nodal-pressure patch) with, increasing. Gathered with duplicates, then sorted per node.
  std::vector<int> start(num_nodes + 1, 0);
  const auto for_each_group = [&](const auto& visit) {  // visit(first, last): nodes sharing an element or patch
    for (int e = 0; e < ne; ++e) visit(elements[e].data(), elements[e].data() + n_);
    if (nodal_)
      for (int p = 0; p < nodal_->num_patches(); ++p) visit(nodal_->patch_nodes_begin(p), nodal_->patch_nodes_end(p));
  };
  for_each_group([&](const int* first, const int* last) {
    for (const int* v = first; v != last; ++v) start[*v + 1] += static_cast<int>(last - first);
  });
  for (int v = 0; v < num_nodes; ++v) start[v + 1] += start[v];
  std::vector<int> upper(start[num_nodes]);
  {
    std::vector<int> at(start.begin(), start.end() - 1);
    for_each_group([&](const int* first, const int* last) {
      for (const int* v = first; v != last; ++v)
        for (const int* w = first; w != last; ++w)
          if (*w >= *v) upper[at[*v]++] = *w;
    });
    int kept = 0;
    for (int v = 0; v < num_nodes; ++v) {
      const auto begin = upper.begin() + start[v], end = upper.begin() + at[v];
      std::sort(begin, end);
      const auto unique_end = std::unique(begin, end);
      start[v] = kept;
      const auto destination = upper.begin() + kept;  // at or before `begin`
      if (destination != begin) std::copy(begin, unique_end, destination);
      kept += static_cast<int>(unique_end - begin);
    }
    start[num_nodes] = kept;
    upper.resize(kept);
  }
  // Where node w's rows start in node v's first column, after v's own (the reduced dofs of the
  // entries of v's list before w's); the column of v's dof k has k fewer rows of v's own.
  std::vector<int> rows_before(upper.size(), 0);
  for (int v = 0; v < num_nodes; ++v)
    for (int i = start[v] + 1, sum = 0; i < start[v + 1]; ++i) {
      rows_before[i] = sum;
      sum += dofs.count(upper[i]);
    }

  // Column-major lower pattern: column of dof (v, k) holds the dofs of adjacent nodes w >= v
  // (components >= k for w = v). Reduced dofs are numbered node by node, so rows come sorted.
  const int nf = dofs.num_free();
  std::vector<int> outer(nf + 1, 0);
  std::vector<int> inner;
  for (int v = 0; v < num_nodes; ++v)
    for (int k = 0; k < dofs.count(v); ++k) {
      const int column = dofs.first(v) + k;
      for (int l = k; l < dofs.count(v); ++l) inner.push_back(dofs.first(v) + l);
      for (int i = start[v] + 1; i < start[v + 1]; ++i)
        for (int l = 0; l < dofs.count(upper[i]); ++l) inner.push_back(dofs.first(upper[i]) + l);
      outer[column + 1] = static_cast<int>(inner.size());
    }
  K_.resize(nf, nf);
  K_.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), K_.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), K_.innerIndexPtr());
  std::fill(K_.valuePtr(), K_.valuePtr() + inner.size(), 0.0);
  // Value slot of row dof (w, l) in the column of dof (v, k), w >= v.
  const auto slot_of = [&](int v, int k, int w, int l) {
    const int column_start = outer[dofs.first(v) + k];
    if (w == v) return column_start + l - k;
    const int i = static_cast<int>(std::lower_bound(upper.begin() + start[v] + 1, upper.begin() + start[v + 1], w) -
                                   upper.begin());
    return column_start + (dofs.count(v) - k) + rows_before[i] + l;
  };

  // Value slot of every lower pair (i >= j, local order) of each element's reduced dofs, and the
  // threads whose value ranges (assemble()'s scatter) hold each element's first and last slot.
  // Elements are independent: in parallel, each writing its own part of slots_.
  slot_start_.assign(ne + 1, 0);
  for (int e = 0; e < ne; ++e) {
    int count = 0;
    for (int a = 0; a < n_; ++a) count += dofs.count(elements[e][a]);
    slot_start_[e + 1] = slot_start_[e] + count * (count + 1) / 2;
  }
  slots_.resize(slot_start_[ne]);
  owner_threads_ = threads_;
  first_owner_.resize(ne);
  last_owner_.resize(ne);
  const auto owner = [&](int slot) {
    int t = 0;
    while (t + 1 < owner_threads_ && slot >= thread_range(K_.nonZeros(), t, owner_threads_).second) ++t;
    return t;
  };
#pragma omp parallel for num_threads(threads_) schedule(static)
  for (int e = 0; e < ne; ++e) {
    const LocalDofs d = local_dofs(elements[e], n_, dofs);
    int* slot = slots_.data() + slot_start_[e];
    for (int i = 0; i < d.count; ++i)
      for (int j = 0; j <= i; ++j) {
        const bool i_lower = d.global[i] < d.global[j];  // the column is the lower dof's
        const int c = i_lower ? i : j, r = i_lower ? j : i;
        *slot++ = slot_of(elements[e][d.node[c]], d.column[c], elements[e][d.node[r]], d.column[r]);
      }
    if (slot_start_[e] == slot_start_[e + 1]) {  // no free dof: nothing to scatter
      first_owner_[e] = owner_threads_;
      last_owner_[e] = -1;
      continue;
    }
    const auto [lo, hi] = std::minmax_element(slots_.begin() + slot_start_[e], slots_.begin() + slot_start_[e + 1]);
    first_owner_[e] = owner(*lo);
    last_owner_[e] = owner(*hi);
  }

  if (nodal_)
    for (int p = 0; p < nodal_->num_patches(); ++p) {
      const int* nodes = nodal_->patch_nodes_begin(p);
      const int m = static_cast<int>(nodal_->patch_nodes_end(p) - nodes);
      for (int i = 0; i < m; ++i)
        for (int j = 0; j <= i; ++j) {
          const int w = nodes[i], v = nodes[j];
          for (int k = 0; k < dofs.count(v); ++k) {
            if (dofs.count(w) == 0) break;
            patch_slots_.push_back(slot_of(v, k, w, w == v ? k : 0));  // patch nodes are sorted: w >= v
          }
        }
    }
}

void ReducedAssembly::add_patch_terms(const NodalPressure::State& state) {
  double* values = K_.valuePtr();
  std::vector<Eigen::Vector3d> d;
  std::vector<Eigen::Vector3d> reduced;
  std::size_t t = 0;
  for (int p = 0; p < nodal_->num_patches(); ++p) {
    nodal_->patch_gradient(state, p, d);
    const int* nodes = nodal_->patch_nodes_begin(p);
    const int m = static_cast<int>(d.size());
    reduced.resize(m);
    for (int i = 0; i < m; ++i)
      reduced[i] = dofs_.unconstrained(nodes[i]) ? d[i] : Eigen::Vector3d(dofs_.basis(nodes[i]).transpose() * d[i]);
    const double k = state.stiffness[p];
    for (int i = 0; i < m; ++i)
      for (int j = 0; j <= i; ++j) {
        const int w = nodes[i], v = nodes[j];
        for (int kk = 0; kk < dofs_.count(v); ++kk) {
          if (dofs_.count(w) == 0) break;
          const int first_row = (w == v ? kk : 0);
          double* column = values + patch_slots_[t++] - first_row;
          const double scale = k * reduced[j][kk];
          for (int l = first_row; l < dofs_.count(w); ++l) column[l] += scale * reduced[i][l];
        }
      }
  }
}

ReducedAssembly::Result ReducedAssembly::assemble(const Eigen::VectorXd& u, bool with_tangent) {
  Result out;
  out.f_int = Eigen::VectorXd::Zero(u.size());
  if (with_tangent) std::fill(K_.valuePtr(), K_.valuePtr() + K_.nonZeros(), 0.0);
  double* values = K_.valuePtr();
  const ElementOutput what = with_tangent ? ElementOutput::EnergyForceAndTangent : ElementOutput::EnergyAndForce;
  const int ne = static_cast<int>(elements_.size());
  const int nf = 3 * n_;
  NodalPressure::State state;
  if (nodal_) {
    state = nodal_->evaluate(u, threads_);
    if (!state.ok) {
      out.ok = false;
      std::ostringstream note;
      if (state.failed_element >= 0)
        note << "inverted element " << state.failed_element << " (min J " << state.failed_J << ")";
      else
        note << "non-finite volumetric energy of a node patch";
      out.note = note.str();
      return out;
    }
  }

  for (int start = 0; start < ne; start += kChunk) {
    const int end = std::min(ne, start + kChunk);
    const int base = slot_start_[start];
    if (with_tangent) buffer_.resize(slot_start_[end] - base);
    forces_.resize(static_cast<std::size_t>(end - start) * nf);
    energies_.resize(static_cast<std::size_t>(end - start));
    int failed_element = std::numeric_limits<int>::max();
    ElementResponse failure;
#pragma omp parallel num_threads(threads_)
    {
      ElementNodes ue(n_, 3);
#pragma omp for schedule(dynamic, 64)
      for (int e = start; e < end; ++e) {
        const std::array<int, 10>& element = elements_[e];
        for (int a = 0; a < n_; ++a) ue.row(a) = u.segment<3>(3 * element[a]).transpose();
        ElementResponse r = element_response(geometry_[e], ue, *law_[e], what);
        if (r.ok() && nodal_) nodal_->add_element_terms(state, e, r.force, with_tangent ? &r.tangent : nullptr);
        if (!r.ok()) {
#pragma omp critical(tissuemesh_assembly_failure)
          if (e < failed_element) {
            failed_element = e;
            failure = std::move(r);
          }
          continue;
        }
        std::copy(r.force.data(), r.force.data() + nf, forces_.data() + static_cast<std::size_t>(e - start) * nf);
        energies_[e - start] = r.energy;
        if (!with_tangent) continue;
        // Lower triangle of the reduced element matrix T^T K T (T: block-diagonal node bases,
        // identity for free nodes), in the slot order.
        const LocalDofs d = local_dofs(element, n_, dofs_);
        double* m = buffer_.data() + (slot_start_[e] - base);
        for (int i = 0, p = 0; i < d.count; ++i) {
          const int a = d.node[i];
          const bool plain_a = dofs_.unconstrained(element[a]);
          for (int j = 0; j <= i; ++j, ++p) {
            const int b = d.node[j];
            if (plain_a && dofs_.unconstrained(element[b])) {
              m[p] = r.tangent(3 * a + d.column[i], 3 * b + d.column[j]);
            } else {
              const Eigen::Vector3d ta = dofs_.basis(element[a]).col(d.column[i]);
              const Eigen::Vector3d tb = dofs_.basis(element[b]).col(d.column[j]);
              m[p] = ta.dot(r.tangent.block<3, 3>(3 * a, 3 * b) * tb);
            }
          }
        }
      }
      // (the implicit barrier of the loop above: every element of the chunk is evaluated)
      // Scatter in element order, in parallel: each thread owns one contiguous range of the
      // matrix's values and of f_int and adds, walking the chunk's elements in order, only the
      // contributions that fall into its ranges. Every entry thus receives its contributions in
      // element order, as a serial scatter would: bit-identical for any thread count.
      if (failed_element == std::numeric_limits<int>::max()) {
        const int t = omp_get_thread_num(), nt = omp_get_num_threads();
        const auto [f_lo, f_hi] = thread_range(out.f_int.size(), t, nt);
        for (int e = start; e < end; ++e) {
          const double* f = forces_.data() + static_cast<std::size_t>(e - start) * nf;
          for (int a = 0; a < n_; ++a)
            for (int i = 0; i < 3; ++i) {
              const Eigen::Index g = 3 * static_cast<Eigen::Index>(elements_[e][a]) + i;
              if (g >= f_lo && g < f_hi) out.f_int[g] += f[3 * a + i];
            }
        }
        if (t == 0)
          for (int e = start; e < end; ++e) out.energy += energies_[e - start];
        if (with_tangent) {
          const auto [v_lo, v_hi] = thread_range(K_.nonZeros(), t, nt);
          const int* slots = slots_.data() + base;  // slots[i]: where buffer_[i] goes
          // Elements whose slots all lie in other threads' ranges are skipped, and those whose
          // slots all lie in this thread's range need no test (the owners planned for
          // owner_threads_ threads; for another count every element is tested).
          const bool by_owner = nt == owner_threads_;
          for (int e = start; e < end; ++e) {
            if (by_owner && (t < first_owner_[e] || t > last_owner_[e])) continue;
            const int from = slot_start_[e] - base, to = slot_start_[e + 1] - base;
            if (by_owner && first_owner_[e] == t && last_owner_[e] == t) {
              for (int i = from; i < to; ++i) values[slots[i]] += buffer_[i];
            } else {
              for (int i = from; i < to; ++i)
                if (slots[i] >= v_lo && slots[i] < v_hi) values[slots[i]] += buffer_[i];
            }
          }
        }
      }
    }
    if (failed_element != std::numeric_limits<int>::max()) {
      out.ok = false;
      std::ostringstream note;
      note << (failure.status == ElementStatus::Inverted ? "inverted element " : "non-finite response in element ")
           << failed_element << " (min J " << failure.min_J << ")";
      out.note = note.str();
      return out;
    }
  }
  if (nodal_) {
    out.energy += state.energy;
    if (with_tangent) add_patch_terms(state);
  }
  return out;
}

}  // namespace tissuemesh
