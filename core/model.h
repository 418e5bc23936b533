// Model: everything a finite-element solver needs, independent of any file format.
//
//   Model = nodes + tet4/tet10 elements with a tissue per element + a MaterialSpec per tissue
//         + node sets (fixed or sliding) + face sets + gravity + units + analysis settings.
//
// Conventions every writer and the solver rely on:
// - nodes in LPS millimetres; the first `num_corner_nodes` are the mesh's own nodes, in reverse
//   Cuthill-McKee order unless `model.node_order: mesh` (then in the mesh's order); midside nodes
//   (tet10) follow. `mesh_node_of` maps each corner node back to the mesh. Writers convert
//   lengths with `units`.
// - elements[e][0..3] are the corners, positively oriented ((n1-n0).((n2-n0)x(n3-n0)) > 0);
//   for tet10, [4..9] are the midside nodes of edges (0,1) (1,2) (2,0) (0,3) (1,3) (2,3): the
//   order of VTK, Abaqus/CalculiX C3D10 and FEBio tet10 (docs/formats.md, "Conventions shared by
//   every file"). Unused slots are -1.
// - tissue_ids[e] in 1..tissue_names.size(); materials[i] belongs to tissue_names[i]. build_model
//   groups elements by tissue (within a tissue: by lowest corner with `node_order: rcm`, the
//   mesh's order with `mesh`), so file ids = model order + 1 in every format.
// - a node set lists sorted, unique 0-based node indices; a sliding set also carries one unit
//   normal per node (the constraint is n . u = 0).
// - a face set lists (element, local face) pairs with the Abaqus face numbering of C3D4/C3D10:
//   face 0 = corners (0,1,2), 1 = (0,3,1), 2 = (1,3,2), 3 = (2,3,0) (S1..S4); `face_corners`
//   returns them ordered so that the right-hand normal points out of the element.
// - gravity is an acceleration in m/s^2 in the LPS frame (prone: towards anterior, -y).
#pragma once

#include "core/material_spec.h"
#include "core/unit_system.h"

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace tissuemesh {

enum class ElementOrder { Linear, Quadratic };  ///< tet4, tet10 (straight edges)

enum class Constraint { Fixed, Sliding };

struct NodeSet {
  std::string name;                       ///< a valid identifier in every format ([A-Za-z_][A-Za-z0-9_]*)
  Constraint constraint = Constraint::Fixed;
  std::vector<int> nodes;                 ///< sorted, unique, 0-based
  std::vector<Eigen::Vector3d> normals;   ///< Sliding only: unit normal per node (same order)
  std::string selection;                  ///< how it was chosen, for reports ("interface muscle|outside")
};

struct FaceSet {
  std::string name;
  std::vector<std::array<int, 2>> faces;  ///< (element index, local face 0..3)
  std::string selection;
};

struct Gravity {
  Eigen::Vector3d acceleration_m_s2 = Eigen::Vector3d::Zero();  ///< LPS frame
  std::string name;  ///< "prone", "supine", "vector" or "none"
};

/// How tet4 integrates the volumetric part U(J) of the laws in the built-in solver: per element
/// (the standard tet4 every export writes; locks as nu -> 0.5) or per node (average nodal
/// pressure, solver_check/nodal_pressure.h).
enum class Tet4Pressure { Element, Nodal };

/// Nonlinear static analysis settings shared by the writers and the built-in solver.
struct AnalysisSettings {
  int load_steps = 10;                 ///< initial number of equal load increments
  int max_load_steps = 100;            ///< increments allowed including cut-backs
  double min_step_fraction = 1e-4;     ///< smallest load increment as a fraction of the load
  int max_newton_iterations = 25;      ///< per increment
  double displacement_tolerance = 1e-3;  ///< relative norm of the displacement correction
  double energy_tolerance = 1e-2;        ///< relative energy norm (FEBio etol)
  double residual_tolerance = 1e-6;      ///< relative residual norm (0 = off in FEBio)
  /// Built-in solver only (writers ignore it; tet10 elements too).
  Tet4Pressure tet4_pressure = Tet4Pressure::Element;
};

struct Model {
  std::string title;
  std::vector<Eigen::Vector3d> nodes;      ///< LPS mm
  int num_corner_nodes = 0;
  /// Per corner node (0..num_corner_nodes-1): its index in the input mesh (mesh.vtu), to map results
  /// back. Identity with `node_order: mesh`. Set by build_model; empty in a model made otherwise.
  std::vector<int> mesh_node_of;
  ElementOrder order = ElementOrder::Linear;
  std::vector<std::array<int, 10>> elements;
  std::vector<int> tissue_ids;             ///< per element, 1-based
  std::vector<std::string> tissue_names;
  std::vector<MaterialSpec> materials;     ///< per tissue, same order as tissue_names
  std::vector<NodeSet> node_sets;
  std::vector<FaceSet> face_sets;
  Gravity gravity;
  UnitSystem units = UnitSystem::MillimetreTonneSecond;
  AnalysisSettings analysis;

  int nodes_per_element() const { return order == ElementOrder::Linear ? 4 : 10; }
};

/// Corner indices (into elements[e]) of local face f, outward oriented.
const std::array<int, 3>& face_corners(int f);
/// Local indices (into elements[e]) of the 3 midside nodes of face f, in the order of the edges
/// (c0,c1) (c1,c2) (c2,c0) of face_corners(f): the tri6 order.
const std::array<int, 3>& face_midsides(int f);

/// Signed volume (mm^3) of element e's corner tetrahedron.
double element_volume(const Model& model, std::size_t e);

/// Refuses a model no writer should write, with an InputError naming the culprit: size
/// mismatches, a node index out of range, a non-finite coordinate, an inverted or flat element
/// (by index and tissue), an element with an unknown tissue, a tissue without material or with
/// non-physical parameters, a node no element uses (orphan), an empty or badly named node/face
/// set, a sliding set without unit normals, a duplicated set name. Writers call it first.
void validate_model(const Model& model);

}  // namespace tissuemesh
