// The radius-edge ratio a triangle surface forces on every tet mesh that keeps its triangles as
// faces: TetGen with -Y (volume/tetgen_mesher.h), and the mesh the surface was taken from
// (quality/mesh_interfaces.h). TetGen is asked for a ratio <= tetgen.radius_edge_ratio (its -q
// bound); this says how low the input lets the largest ratio of any such mesh go.
//
// Bound: a tet with a face whose smallest angle is theta has circumradius / shortest edge
// >= 1 / (2 sin theta) (proof in forced_radius_edge.cpp). With -Y every input triangle is a face
// of a kept tet, so the largest ratio of the mesh is at least the largest 1 / (2 sin theta) over
// the triangles. A mesher that may split boundary triangles (TetGen without -Y) is not bound by
// it. Deterministic. See docs/verification.md ("Cross-check with TetGen").
#pragma once

#include "core/tet_mesh.h"
#include "core/tri_surface.h"

#include <array>
#include <cstddef>
#include <limits>

namespace tissuemesh {

struct ForcedRadiusEdge {
  /// Largest 1 / (2 sin theta_min) over the triangles: 0 for a surface without triangles,
  /// +infinity when a triangle has zero area.
  double ratio = 0.0;
  /// The triangle that sets it (the first of equals): index into TriSurface::triangles (its
  /// patch pair is labels[triangle]); -1 without triangles.
  int triangle = -1;
  /// That triangle's smallest interior angle, degrees; NaN without triangles.
  double min_angle_deg = std::numeric_limits<double>::quiet_NaN();
  /// Triangles whose own 1 / (2 sin theta_min) exceeds the `bound` given.
  std::size_t triangles_above_bound = 0;
};

/// The bound of the header comment for `surface`, and how many of its triangles force a ratio
/// above `bound` (e.g. tetgen.radius_edge_ratio). O(triangles). Throws InputError when the surface
/// is invalid (TriSurface::validate).
ForcedRadiusEdge forced_radius_edge_ratio(const TriSurface& surface, double bound);

/// The tets of a mesh above a radius-edge bound, split by the cause the header comment proves:
/// a tet with a face that is a surface triangle forcing more than the bound cannot meet it
/// (forced; any mesh keeping that triangle has such a tet). For any other tet this bound proves
/// nothing (unforced): it may be the mesher's doing, or still unavoidable under its constraints.
struct RadiusEdgeAccount {
  /// Tets whose TetShape::radius_edge_ratio exceeds the bound, flat tets included
  /// (TissueQuality::tets_radius_edge_above_2 is this count at 2).
  std::size_t above = 0;
  std::size_t forced = 0;    ///< of them, those with a face that forces more than the bound
  std::size_t unforced = 0;  ///< above - forced
  /// Largest ratio among the unforced tets (0 when there are none; +infinity for a flat one).
  double max_unforced_ratio = 0.0;
  int max_unforced_tet = -1;  ///< index into mesh.tets of that tet, -1 when there is none
  /// The unforced tets by how many of their nodes are corners of surface triangles (0..4): 2 or
  /// more for tets that span thin layers between surface nodes.
  std::array<std::size_t, 5> unforced_by_surface_nodes{};
};

/// Accounts for the tets of `mesh` above `bound` against the triangles of `surface` (see
/// RadiusEdgeAccount). A surface triangle is recognised as a tet face by its corners' coordinates,
/// compared exactly: the meshes this is for (TetGen's -Y mesh of the surface, the mesh the surface
/// was taken from) keep the surface points as nodes, bit for bit. A triangle whose corners are not
/// all nodes of `mesh` forces nothing there. Mesh nodes at the same coordinates (a mesh that is
/// not conforming) are not told apart: a surface point goes to the first of them. Throws
/// InputError when the surface or the mesh is invalid, or when the mesh has kMaxFaceKeyNodes
/// (core/face_key.h) nodes or more. Deterministic; O(tets + (nodes + surface points) log nodes).
RadiusEdgeAccount account_radius_edge_above(const TetMesh& mesh, const TriSurface& surface, double bound);

}  // namespace tissuemesh
