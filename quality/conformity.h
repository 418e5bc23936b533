// Conformity of a multi-material tetrahedral mesh: is it one valid, conforming FE mesh?
//
// Checks that every interior face is shared by exactly two tets, no node is duplicated at one
// position, no node is unused, no tet is inverted or degenerate, and the boundary surface is a
// closed 2-manifold; also counts the faces between each pair of tissues. The invariants are those
// of docs/verification.md ("Mesh invariants"). O(n log n) in tets and nodes. Deterministic.
#pragma once

#include "core/tet_mesh.h"

#include <Eigen/Core>

#include <nlohmann/json.hpp>

#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace tissuemesh {

/// One place where a "must be 0" count is violated (the first kMaxDefectsPerKind of each kind).
struct ConformityDefect {
  std::string kind;          ///< the count's field name, e.g. "degenerate_tets"
  Eigen::Vector3d position;  ///< mm: the tet's or face's centroid, the edge's midpoint, the node
  int tissue = 0;            ///< tissue id of the (first) tet involved; 0 for an orphan node
};
inline constexpr std::size_t kMaxDefectsPerKind = 10;

/// Counts describing the conformity of a mesh. The counts documented as "must be 0" are the ones
/// conforming() checks.
struct ConformityReport {
  std::size_t nodes = 0;                         ///< mesh.points.size()
  std::size_t tets = 0;                          ///< mesh.tets.size()
  std::size_t faces_shared_by_more_than_two = 0; ///< distinct faces in >= 3 tets; must be 0
  std::size_t boundary_faces = 0;                ///< faces with exactly one tet
  /// (tissue a, tissue b) with a < b -> number of faces between a tet of a and a tet of b;
  /// a = 0 means outside, i.e. the boundary faces of tissue b. Pairs without faces are absent;
  /// faces in more than two tets are counted only in faces_shared_by_more_than_two.
  std::map<std::pair<int, int>, std::size_t> interface_faces;
  /// Groups of >= 2 nodes within 1e-9 * bounding-box diagonal of each other (transitively);
  /// must be 0.
  std::size_t duplicate_node_groups = 0;
  std::size_t orphan_nodes = 0;                  ///< nodes used by no tet; must be 0
  std::size_t inverted_tets = 0;                 ///< signed volume < 0, not degenerate; must be 0
  /// |volume| <= 1e-12 * (bbox diagonal)^3, or a node repeated in the tet; must be 0. A degenerate
  /// tet is not also counted as inverted: the sign of a round-off volume means nothing.
  std::size_t degenerate_tets = 0;
  /// Edges of the boundary surface (the boundary faces) not shared by exactly two boundary faces:
  /// 1 shows a hole or a non-conforming interface (hanging node, mismatched diagonals), >= 3 a
  /// non-manifold boundary (e.g. bodies touching along an edge, a cut along duplicate nodes);
  /// must be 0.
  std::size_t nonmanifold_boundary_edges = 0;
  /// Where the violations are: up to kMaxDefectsPerKind per kind, in mesh order.
  std::vector<ConformityDefect> defects;
  /// tissue id i -> tissue_names[i-1], copied from the mesh so that to_json can name tissues.
  std::vector<std::string> tissue_names;

  /// True when every "must be 0" count is 0.
  bool conforming() const;
};

/// Checks `mesh`. Faces are matched by their node ids (not positions: coincident but distinct
/// nodes are reported as duplicate_node_groups, and their faces as boundary faces). Tets with a
/// repeated node take part in face matching like any other tet. Throws InputError when the mesh
/// is inconsistent (TetMesh::validate) or a coordinate is not finite.
ConformityReport check_conformity(const TetMesh& mesh);

/// {"conforming", "nodes", "tets", every count under its field name, "interface_faces": [{
/// "tissue_a", "tissue_b" (names, "outside" for 0), "tissue_a_id", "tissue_b_id", "faces"}],
/// "defects": [{"kind", "position_mm": [x, y, z], "tissue"}]}.
nlohmann::json to_json(const ConformityReport& report);

/// Human-readable text: the counts, one per line with a verdict, where the defects are (when the
/// mesh does not conform), then a table of interface faces
/// per tissue pair named from `tissue_names` (id i -> tissue_names[i-1], 0 -> "outside"). Ends
/// with a newline.
std::string format_conformity_table(const ConformityReport& report,
                                    const std::vector<std::string>& tissue_names);

}  // namespace tissuemesh
