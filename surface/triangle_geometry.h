// Small geometry of one triangle in 3D (mm): area vector, interior angles, point distance.
// Shared by the surface quality figures (surface/surface_quality.h) and the surface remesher, so
// both judge a triangle's angles by the same formula.
#pragma once

#include <Eigen/Core>

#include <array>

namespace tissuemesh {

/// Half the cross product (b - a) x (c - a): normal by the right-hand rule, norm = area.
Eigen::Vector3d area_vector(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Interior angles (radians) at a, b and c, each as atan2(2 area, dot of its two edges): accurate
/// for every shape; all zero for a zero-area triangle.
std::array<double, 3> triangle_angles(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Interior angle (radians) at c, computed as triangle_angles(a, b, c)[2] is (the same value).
double angle_at_c(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Smallest interior angle (radians): the angle of triangle_angles' formula at the vertex whose two
/// edges have the largest dot product; 0 for a zero-area triangle. The smallest of triangle_angles
/// exactly when atan2 never grows with its second argument; glibc's may break that by an ulp at
/// near-ties (tests/surface/test_triangle_geometry.cpp compares the two within that).
double min_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Frey-Borouchaki (1997) quality Q = 6/sqrt(3) A / (p h_max) (A area, p half-perimeter, h_max
/// longest edge; as in Table 1 of Alqaoud et al.): 1 for the equilateral triangle, 0 for a
/// degenerate one.
double triangle_quality(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// The point of the closed triangle abc closest to p (Ericson, Real-Time Collision Detection, 5.1.5).
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c);
/// Distance from p to the closed triangle abc: |p - closest_point_on_triangle(p, a, b, c)|.
double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c);

}  // namespace tissuemesh
