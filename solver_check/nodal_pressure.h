// NodalPressure: the volumetric energy of a tet4 mesh integrated per node, the built-in solver's
// cure for the volumetric locking of tet4 at nu -> 0.5 (`model.analysis.tet4_pressure: nodal`):
// the average nodal pressure tetrahedron (Bonet & Burton, Commun. Numer. Meth. Engng 14:437-449,
// 1998), here in its energy form, so the tangent is symmetric and the line search keeps a
// potential.
//
// Each law is W = W_rest(C) + U(J) (HyperelasticLaw::volumetric). Elements integrate W_rest
// (materials/volumetric_split.h); U is integrated over node patches. A patch p is a node a with
// the elements of one tissue t around it; with V_e, v_e the reference and current element volumes,
//   V_p = sum_{e in p} V_e / 4,   J_p = (sum_{e in p} v_e / 4) / V_p,   Pi_vol = sum_p V_p U_t(J_p).
// A node on an interface has a patch per tissue: the pressure jumps where the material does.
// One volume constraint per node instead of per element: about 1 per 3 unknowns instead of 2, so
// the mesh no longer locks. Under a homogeneous deformation every J_p equals J and Pi_vol is the
// element integral of U.
// Derivatives, with dv_e/dx_b = v_e g_b and g_b = F^-T grad_X N_b (the spatial gradient):
//   force      f_b = sum_e pbar_e dv_e/dx_b,   pbar_e = mean of U'(J_p) over e's four corner patches
//   tangent    K_bc = sum_e pbar_e (dv_b dv_c^T - dv_c dv_b^T) / v_e                (element-local)
//                   + sum_p U''(J_p) / V_p  d_p d_p^T,   d_p = sum_{e in p} dv_e / 4  (patch-wide)
// The patch term couples every two nodes of a patch, so the tangent's pattern reaches a node's
// neighbours' neighbours in the same tissue. The element's Cauchy stress is that of W_rest plus
// pbar_e I (pbar_e is a pressure in the laws' stress unit).
// Units: any consistent system (volumes cancel in J_p; forces come out in the laws' stress unit x
// the geometry's length^2).
#pragma once

#include "materials/hyperelastic_law.h"
#include "solver_check/element_kernel.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace tissuemesh {

/// True when the built-in solver integrates this model's volumetric energy per node: tet4 with
/// analysis.tet4_pressure = nodal (tet10 ignores the setting).
bool uses_nodal_pressure(const Model& model);

class NodalPressure {
 public:
  /// tet4 `elements` (first 4 entries), their reference `geometry` (element_geometry, 1 point),
  /// tissue and full law per element; all referenced, must outlive this object. A patch is made
  /// for every (node, tissue) pair that occurs, in order of first appearance (element order).
  /// Throws std::invalid_argument when the sizes differ or an element is not a 1-point tet4.
  NodalPressure(const std::vector<std::array<int, 10>>& elements, const std::vector<ElementGeometry>& geometry,
                const std::vector<int>& tissue, const std::vector<const HyperelasticLaw*>& law);

  int num_patches() const { return static_cast<int>(patch_volume_.size()); }
  /// The nodes of patch p (the node itself and its neighbours in the patch's elements), sorted.
  const int* patch_nodes_begin(int p) const { return patch_nodes_.data() + node_start_[p]; }
  const int* patch_nodes_end(int p) const { return patch_nodes_.data() + node_start_[p + 1]; }

  /// Everything the assembly needs at a displacement.
  struct State {
    bool ok = true;
    /// Lowest element with det F <= 0 or a non-finite F; -1 with ok = false: U(J_p) not finite.
    int failed_element = -1;
    double failed_J = 0.0;                ///< its det F
    std::vector<Eigen::Matrix<double, 4, 3>> dv;  ///< per element: row b = dv_e/dx_b
    std::vector<double> volume;           ///< per element: v_e
    std::vector<double> pressure;         ///< per element: pbar_e
    std::vector<double> J;                ///< per patch: J_p
    std::vector<double> stiffness;        ///< per patch: U''(J_p) / V_p
    double energy = 0.0;                  ///< Pi_vol, summed in patch order
  };

  /// The state at global displacement u (3 per node), elements evaluated on `threads` threads;
  /// deterministic for any thread count.
  State evaluate(const Eigen::VectorXd& u, int threads) const;

  /// Adds e's force and (when tangent != nullptr) element-local tangent terms (header formulas),
  /// node-major 12-vector / 12 x 12, to an element response.
  void add_element_terms(const State& s, int e, ElementVector& force, ElementMatrix* tangent) const;

  /// d_p (3 per patch node, in patch_nodes order) of patch p at state s.
  void patch_gradient(const State& s, int p, std::vector<Eigen::Vector3d>& d) const;

 private:
  const std::vector<std::array<int, 10>>& elements_;
  const std::vector<ElementGeometry>& geometry_;
  std::vector<double> patch_volume_;     ///< V_p
  std::vector<const HyperelasticLaw*> patch_law_;
  std::vector<int> element_start_, patch_elements_;  ///< CSR: the elements of each patch, ascending
  /// Parallel to patch_elements_: each corner's index in its patch's node list.
  std::vector<std::array<int, 4>> corner_in_patch_;
  std::vector<int> node_start_, patch_nodes_;        ///< CSR: the nodes of each patch, sorted
  std::vector<std::array<int, 4>> corner_patch_;     ///< per element: the patch of each corner
};

}  // namespace tissuemesh
