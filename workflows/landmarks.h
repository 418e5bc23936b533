// Landmarks carried through a deformation: each point is located in the mesh of the imaged shape
// (the tet that contains it and its barycentric coordinates there) and mapped to any other
// configuration of the same mesh by the same barycentric combination of that tet's corners
// (linear interpolation: exact for tet4, the corner interpolation for tet10).
//
// Points and positions in LPS mm. A point within 1e-9 mm of a mesh node takes that node alone, so
// it maps to that node's positions exactly. A point on a face or edge shared by several tets takes
// the lowest-numbered one (every choice gives the same position: the interpolation is continuous).
#pragma once

#include "core/model.h"

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace tissuemesh {

struct Landmark {
  std::string name;
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
};

/// Where a landmark lies in the mesh.
struct LandmarkLocation {
  int element = -1;                   ///< model element (0-based)
  std::array<int, 4> corners{};       ///< its corner nodes
  std::array<double, 4> weights{};    ///< barycentric coordinates (sum 1, each >= 0 up to round-off)
  int tissue = 0;                     ///< 1-based tissue id of the element
};

/// Reads a landmark CSV: lines "name,x,y,z" (mm, LPS); an optional header line whose coordinates
/// are not numbers ("name,x,y,z"), blank lines and lines starting with '#' are skipped. Throws
/// InputError naming the file and line for a missing file, a wrong number of fields, a non-finite
/// or non-numeric coordinate, an empty or duplicated name, or no point at all.
std::vector<Landmark> read_landmarks_csv(const std::string& path);

/// Locates every landmark in `model` (its nodes: the configuration the points are given in).
/// Throws InputError naming the first point outside the mesh (with its distance to the nearest
/// node), before returning anything.
std::vector<LandmarkLocation> locate_landmarks(const Model& model, const std::vector<Landmark>& points);

/// The position of a located landmark in a configuration given by every model node's position (mm).
Eigen::Vector3d landmark_position(const LandmarkLocation& where, const std::vector<Eigen::Vector3d>& nodes);

}  // namespace tissuemesh
