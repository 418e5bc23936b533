#include "workflows/landmarks.h"

#include "core/errors.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace tissuemesh {

namespace {

/// A point counts as inside a tet when each barycentric coordinate is >= -kInsideSlack: round-off
/// of points on faces (relative ~1e-15) passes, a point 1e-6 of the tet's size outside does not.
constexpr double kInsideSlack = 1e-10;
/// A point this close to a node is that node (mm).
constexpr double kOnNodeMm = 1e-9;

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  const auto e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

bool parse_double(const std::string& text, double& value) {
  const std::string t = trim(text);
  if (t.empty()) return false;
  std::istringstream in(t);
  in >> value;
  return in && in.eof();
}

std::string point_text(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ") mm";
  return s.str();
}

}  // namespace

std::vector<Landmark> read_landmarks_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the landmark file");
  std::vector<Landmark> points;
  std::set<std::string> names;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::string where = path + ":" + std::to_string(number);
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    std::vector<std::string> fields;
    std::stringstream ss(t);
    std::string f;
    while (std::getline(ss, f, ',')) fields.push_back(trim(f));
    if (fields.size() != 4)
      throw InputError(where + ": expected 4 fields 'name,x,y,z' (mm, LPS), got " + std::to_string(fields.size()));
    Landmark p;
    p.name = fields[0];
    bool numeric = true;
    for (int i = 0; i < 3; ++i) numeric = parse_double(fields[1 + i], p.position_mm[i]) && numeric;
    if (!numeric) {
      if (points.empty() && names.empty()) {  // a header line
        names.insert("");
        continue;
      }
      throw InputError(where + ": coordinates of '" + p.name + "' are not numbers");
    }
    if (!p.position_mm.allFinite()) throw InputError(where + ": coordinates of '" + p.name + "' are not finite");
    if (p.name.empty()) throw InputError(where + ": a point without a name");
    if (!names.insert(p.name).second) throw InputError(where + ": point name '" + p.name + "' appears twice");
    points.push_back(p);
  }
  if (points.empty()) throw InputError(path + ": no point (expected lines 'name,x,y,z' in mm, LPS)");
  return points;
}

std::vector<LandmarkLocation> locate_landmarks(const Model& model, const std::vector<Landmark>& points) {
  std::vector<LandmarkLocation> out;
  out.reserve(points.size());
  for (const Landmark& p : points) {
    LandmarkLocation loc;
    // On a node: that node alone, in its lowest-numbered element.
    int nearest = -1;
    double nearest_d = INFINITY;
    for (int v = 0; v < model.num_corner_nodes; ++v) {
      const double d = (model.nodes[v] - p.position_mm).norm();
      if (d < nearest_d) {
        nearest_d = d;
        nearest = v;
      }
    }
    for (std::size_t e = 0; e < model.elements.size() && loc.element < 0; ++e) {
      const auto& el = model.elements[e];
      const Eigen::Vector3d& a = model.nodes[el[0]];
      Eigen::Matrix3d A;
      A << model.nodes[el[1]] - a, model.nodes[el[2]] - a, model.nodes[el[3]] - a;
      if (nearest_d <= kOnNodeMm) {
        for (int c = 0; c < 4; ++c)
          if (el[c] == nearest) {
            loc.element = static_cast<int>(e);
            loc.weights = {0.0, 0.0, 0.0, 0.0};
            loc.weights[c] = 1.0;
          }
      } else {
        const Eigen::Vector3d l = A.partialPivLu().solve(p.position_mm - a);
        const double l0 = 1.0 - l.sum();
        if (std::min({l0, l[0], l[1], l[2]}) >= -kInsideSlack) {
          loc.element = static_cast<int>(e);
          loc.weights = {l0, l[0], l[1], l[2]};
        }
      }
      if (loc.element >= 0) {
        for (int c = 0; c < 4; ++c) loc.corners[c] = el[c];
        loc.tissue = model.tissue_ids[e];
      }
    }
    if (loc.element < 0)
      throw InputError("landmark '" + p.name + "' at " + point_text(p.position_mm) +
                       " is outside the mesh (nearest mesh node " + std::to_string(nearest_d) +
                       " mm away); landmarks are given in the imaged (prone) LPS coordinates of the mesh");
    out.push_back(loc);
  }
  return out;
}

Eigen::Vector3d landmark_position(const LandmarkLocation& where, const std::vector<Eigen::Vector3d>& nodes) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int c = 0; c < 4; ++c)
    if (where.weights[c] != 0.0) x += where.weights[c] * nodes[where.corners[c]];
  return x;
}

}  // namespace tissuemesh
