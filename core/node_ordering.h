// Node ordering for a small stiffness-matrix profile: reverse Cuthill-McKee (RCM; Cuthill & McKee,
// "Reducing the bandwidth of sparse symmetric matrices", 1969), and the profile itself, so that
// build_model, the writers' notes and the tests share one definition.
//
// Both functions see a mesh as `elements` (only slots 0..nodes_per_element-1 of each entry are
// read; negative slots are skipped) over nodes 0..num_nodes-1. Two nodes are adjacent when an
// element holds both: the sparsity pattern of the assembled matrix, one row per node.
#pragma once

#include <array>
#include <vector>

namespace tissuemesh {

/// Reverse Cuthill-McKee ordering. Returns new_index_of_old: a permutation of 0..num_nodes-1.
///
/// Fully deterministic (depends only on the arguments, never on addresses or hashing):
/// - connected components are numbered one after the other, in increasing old index of their
///   lowest-index node; each component gets a contiguous block of new indices;
/// - in a component, the start is a pseudo-peripheral node (George & Liu): begin at the
///   lowest-index node of minimum degree, BFS, move to the lowest-index node of minimum degree in
///   the last level, and repeat while the number of levels grows;
/// - Cuthill-McKee BFS from the start visits each node's unvisited neighbours in increasing
///   (degree, old index) order; the component's sequence is then reversed.
/// Nodes no element uses are components of their own. Throws std::invalid_argument for a node
/// index >= num_nodes or nodes_per_element outside 1..10.
std::vector<int> reverse_cuthill_mckee(int num_nodes, const std::vector<std::array<int, 10>>& elements,
                                       int nodes_per_element);

/// The matrix profile in node rows: sum over rows i of (i - lowest column index j <= i adjacent to
/// i, or i itself). Multiply by the dofs per node squared for a dof matrix (x9 in 3D). This is the
/// number FEBio's skyline note reports. Same argument checks as reverse_cuthill_mckee.
long long matrix_profile(int num_nodes, const std::vector<std::array<int, 10>>& elements, int nodes_per_element);

}  // namespace tissuemesh
