// Junction polylines of a multi-material triangle complex (TriSurface::junctions), from its
// junction graph: the edges around which three or more regions meet.
//
// Shared by the surface extraction (junction edges from the voxel lattice) and the interface
// surface of a tet mesh (junction edges from the triangles' label pairs).
#pragma once

#include <cstdint>
#include <vector>

namespace tissuemesh {

/// Surface: on no junction; Curve: exactly two junction neighbours (inside one polyline);
/// Corner: a polyline end or a point where curves meet (or where >= 3 regions pinch together).
enum class VertexKind : std::uint8_t { Surface, Curve, Corner };

/// Polylines of the junction graph `adj` (per vertex, its neighbours along junction edges, sorted):
/// open chains from corner to corner first, then closed loops (first vertex repeated at the end),
/// each found from its lowest-indexed start. Deterministic.
std::vector<std::vector<int>> trace_junctions(const std::vector<std::vector<int>>& adj,
                                              const std::vector<VertexKind>& kind);

}  // namespace tissuemesh
