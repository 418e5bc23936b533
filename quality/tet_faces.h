// The faces of a tet mesh, numbered: face q of tet i (the face opposite its node q) gets an id
// shared with the neighbouring tet across it. Ids follow the order of the faces' keys
// (core/face_key.h), so they are deterministic. Requires node ids below kMaxFaceKeyNodes.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace tissuemesh {

struct TetFaces {
  std::vector<int> id;  ///< id[4 i + q]: the id of face q of tet i
  std::size_t count = 0;  ///< number of distinct faces (ids 0 .. count - 1)
  int of(std::size_t tet, int q) const { return id[4 * tet + static_cast<std::size_t>(q)]; }
};

TetFaces number_tet_faces(const std::vector<std::array<int, 4>>& tets);

}  // namespace tissuemesh
