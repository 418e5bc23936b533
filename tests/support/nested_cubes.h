// Two nested cubes, rotated and shifted so that their large triangles cut grid cells obliquely,
// with an exact region test: a closed two-tissue complex (outer shell = tissue 1, inner cube =
// tissue 2) for the free-cell grid and its CGAL domain (tests/volume/test_free_cell_*.cpp).
#pragma once

#include "core/tri_surface.h"

#include <Eigen/Geometry>

#include <array>
#include <vector>

namespace tissuemesh::test {

struct NestedCubes {
  Eigen::Matrix3d rotation;
  Eigen::Vector3d shift{3.1, -2.2, 0.7};
  double outer_half = 20, inner_half = 8;
  TriSurface surface;  ///< outer cube 0|1, inner cube 1|2, normals from p into q (inward)

  NestedCubes() {
    rotation = (Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitX()) *
                Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
    surface.tissue_names = {"shell", "core"};
    add_cube(outer_half, {0, 1});
    add_cube(inner_half, {1, 2});
  }
  /// 0 outside, 1 between the cubes, 2 inside the inner one; -1 exactly on a cube's boundary.
  int region(const Eigen::Vector3d& x) const {
    const double m = (rotation.transpose() * (x - shift)).cwiseAbs().maxCoeff();
    if (m == inner_half || m == outer_half) return -1;
    return m < inner_half ? 2 : m < outer_half ? 1 : 0;
  }
  /// The lowest corner of the cubes' bounding box.
  Eigen::Vector3d low() const {
    Eigen::Vector3d l = surface.points[0];
    for (const auto& p : surface.points) l = l.cwiseMin(p);
    return l;
  }

 private:
  // Corner c has x = bit 0, y = bit 1, z = bit 2; the faces below are listed outward, and their
  // triangles wound the other way, so the normals point inward, from p (outside) into q.
  void add_cube(double h, std::array<int, 2> labels) {
    const int base = static_cast<int>(surface.points.size());
    for (int c = 0; c < 8; ++c)
      surface.points.push_back(rotation * Eigen::Vector3d(c & 1 ? h : -h, c & 2 ? h : -h, c & 4 ? h : -h) + shift);
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces) {
      surface.triangles.push_back({base + f[0], base + f[2], base + f[1]});
      surface.triangles.push_back({base + f[0], base + f[3], base + f[2]});
      surface.labels.push_back(labels);
      surface.labels.push_back(labels);
    }
  }
};

}  // namespace tissuemesh::test
