// ReducedAssembly: internal force and tangent of the whole mesh in the solver's reduced unknowns
// (solver_check/dof_map.h), assembled in parallel and deterministically.
//
// The tangent is the lower triangle of the symmetric reduced matrix B^T K B (B: every node's basis
// of allowed directions), stored column-major (Eigen::SparseMatrix) with a pattern built once from
// the node graph: entry (r, c), r >= c, exists when the nodes of dofs r and c share an element.
// Elements are evaluated in parallel (OpenMP) and scattered in element order, so every matrix
// entry and force component receives its element contributions in element order for any thread
// count: bit-identical results (the .cpp says how and why).
// With a NodalPressure (solver_check/nodal_pressure.h) the elements carry the laws' shear parts,
// each element response gets its nodal-pressure terms, and the patch terms U''/V_p d_p d_p^T are
// scattered serially in patch order after the elements; the pattern then also holds every pair
// of nodes of a patch.
#pragma once

#include "materials/hyperelastic_law.h"
#include "solver_check/dof_map.h"
#include "solver_check/element_kernel.h"
#include "solver_check/nodal_pressure.h"

#include <Eigen/SparseCore>

#include <array>
#include <string>
#include <vector>

namespace tissuemesh {

class ReducedAssembly {
 public:
  /// `geometry` and `law` per element (same length as `elements`); everything is referenced, not
  /// copied, and must outlive this object. threads <= 0: $OMP_NUM_THREADS, else all processors.
  /// `nodal` (tet4 only, may be null): the volumetric energy integrated per node; `law` must then
  /// be the laws' shear parts (materials/volumetric_split.h).
  ReducedAssembly(ElementOrder order, const std::vector<std::array<int, 10>>& elements,
                  const std::vector<ElementGeometry>& geometry, const std::vector<const HyperelasticLaw*>& law,
                  const DofMap& dofs, int threads, const NodalPressure* nodal = nullptr);

  struct Result {
    bool ok = true;
    std::string note;        ///< failure reason ("inverted element 12 (min J -0.1)")
    Eigen::VectorXd f_int;   ///< 3 per node, global
    double energy = 0.0;     ///< stored energy of the whole mesh (summed in element order)
  };

  /// f_int at the global displacement u (3 per node) and, when `with_tangent`, the tangent into
  /// tangent() (its values are overwritten; the pattern never changes). On an inverted or
  /// non-finite element, ok = false and the note names the lowest-numbered such element.
  Result assemble(const Eigen::VectorXd& u, bool with_tangent);

  /// The reduced tangent of the last assemble(..., true): lower triangle, num_free x num_free.
  const Eigen::SparseMatrix<double>& tangent() const { return K_; }
  int threads() const { return threads_; }

 private:
  int n_;  ///< nodes per element
  const std::vector<std::array<int, 10>>& elements_;
  const std::vector<ElementGeometry>& geometry_;
  const std::vector<const HyperelasticLaw*>& law_;
  const DofMap& dofs_;
  int threads_ = 1;
  Eigen::SparseMatrix<double> K_;
  std::vector<int> slot_start_;  ///< per element: offset into slots_ (size elements + 1)
  std::vector<int> slots_;       ///< lower-triangle pairs (i >= j) of each element's reduced dofs
  /// Per element: the first and last of owner_threads_ threads whose scatter ranges hold its slots
  /// (with the mesh's RCM numbering most elements belong to one thread, which skips the others).
  std::vector<int> first_owner_, last_owner_;
  int owner_threads_ = 1;
  std::vector<double> buffer_;   ///< a chunk's reduced element matrices (slot layout)
  std::vector<double> forces_;   ///< a chunk's element forces (3 n per element)
  std::vector<double> energies_; ///< a chunk's element energies
  const NodalPressure* nodal_ = nullptr;
  /// Per patch, per node pair (i >= j in patch order), per reduced dof k of the column node: the
  /// value slot of the pair's first row in that column (the rows of one node are contiguous).
  std::vector<int> patch_slots_;
  void add_patch_terms(const NodalPressure::State& state);
};

}  // namespace tissuemesh
