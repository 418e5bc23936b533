// Why: a solver needs every one of these invariants. A duplicate node silently cuts the body along
// the faces that use one copy or the other; a shared tissue boundary meshed twice instead of
// stored once (a multi-material surface) shows as boundary faces where there should be interface
// faces. Face keys are bucketed by node, boundary edges and node cells sorted, so the check stays
// O(n log n) and needs no hash map.
#include "quality/conformity.h"

#include "core/errors.h"
#include "core/union_find.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <numeric>
#include <sstream>
#include <utility>

namespace tissuemesh {

namespace {

// Relative to the bounding-box diagonal so that the check means the same in mm or m and for a
// 1 mm phantom or a 300 mm breast.
constexpr double kCoincidentRel = 1e-9;
constexpr double kDegenerateVolumeRel = 1e-12;

/// Nodes of a face with the ids sorted: the same key whichever tet and local order it came from.
using FaceKey = std::array<int, 3>;

FaceKey face_key(int a, int b, int c) {
  if (a > b) std::swap(a, b);
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);
  return {a, b, c};
}

struct FaceOfTet {
  FaceKey key;
  int tet;
};

struct BoundingBox {
  Eigen::Vector3d min, max;
  double diagonal() const { return (max - min).norm(); }
};

BoundingBox bounding_box(const std::vector<Eigen::Vector3d>& points) {
  BoundingBox box{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  for (std::size_t i = 0; i < points.size(); ++i) {
    // Non-finite coordinates would make every distance and cell index below meaningless.
    if (!points[i].allFinite()) {
      std::ostringstream err;
      err << "conformity check: node " << i << " has a non-finite coordinate";
      throw InputError(err.str());
    }
    box.min = i == 0 ? points[i] : box.min.cwiseMin(points[i]);
    box.max = i == 0 ? points[i] : box.max.cwiseMax(points[i]);
  }
  return box;
}

/// The 4 faces of every tet, ordered so that equal faces are adjacent. A counting sort on the
/// smallest node id puts each face in the bucket of that node (equal faces share it), and only
/// the few faces of one bucket are then sorted, which is much cheaper than sorting all 4n faces.
std::vector<FaceOfTet> faces_grouped_by_key(const TetMesh& mesh) {
  static constexpr int kFaceNodes[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  std::vector<std::size_t> bucket_start(mesh.points.size() + 1, 0);
  for (const auto& tet : mesh.tets) {
    for (const auto& f : kFaceNodes) {
      ++bucket_start[1 + std::min({tet[f[0]], tet[f[1]], tet[f[2]]})];
    }
  }
  std::partial_sum(bucket_start.begin(), bucket_start.end(), bucket_start.begin());

  std::vector<FaceOfTet> faces(4 * mesh.tets.size());
  std::vector<std::size_t> next(bucket_start.begin(), bucket_start.end() - 1);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& tet = mesh.tets[t];
    for (const auto& f : kFaceNodes) {
      const FaceKey key = face_key(tet[f[0]], tet[f[1]], tet[f[2]]);
      faces[next[key[0]]++] = {key, static_cast<int>(t)};
    }
  }
  for (std::size_t b = 0; b + 1 < bucket_start.size(); ++b) {
    std::sort(faces.begin() + bucket_start[b], faces.begin() + bucket_start[b + 1],
              [](const FaceOfTet& x, const FaceOfTet& y) { return x.key < y.key; });
  }
  return faces;
}

void add_defect(ConformityReport& report, const char* kind, std::size_t count_so_far,
                const Eigen::Vector3d& position, int tissue) {
  if (count_so_far <= kMaxDefectsPerKind) report.defects.push_back({kind, position, tissue});
}

Eigen::Vector3d centroid(const TetMesh& mesh, const FaceKey& f) {
  return (mesh.points[f[0]] + mesh.points[f[1]] + mesh.points[f[2]]) / 3.0;
}

/// Fills the face counts of `report` and returns the boundary faces (for the edge check).
std::vector<FaceKey> match_faces(const TetMesh& mesh, ConformityReport& report) {
  const std::vector<FaceOfTet> faces = faces_grouped_by_key(mesh);

  // Dense per-pair counters: the map is only built at the end, from a handful of tissue pairs.
  const std::size_t ids = mesh.num_tissues() + 1;
  std::vector<std::size_t> pair_faces(ids * ids, 0);
  std::vector<FaceKey> boundary;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    const int ti = mesh.tissue_ids[faces[i].tet];
    if (j - i == 1) {
      boundary.push_back(faces[i].key);
      ++pair_faces[ti];  // (0, ti)
    } else if (j - i == 2) {
      const int tj = mesh.tissue_ids[faces[i + 1].tet];
      if (ti != tj) ++pair_faces[std::min(ti, tj) * ids + std::max(ti, tj)];
    } else {
      ++report.faces_shared_by_more_than_two;
      add_defect(report, "faces_shared_by_more_than_two", report.faces_shared_by_more_than_two,
                 centroid(mesh, faces[i].key), ti);
    }
    i = j;
  }
  report.boundary_faces = boundary.size();
  for (std::size_t a = 0; a < ids; ++a) {
    for (std::size_t b = a + 1; b < ids; ++b) {
      if (pair_faces[a * ids + b] > 0) {
        report.interface_faces[{static_cast<int>(a), static_cast<int>(b)}] =
            pair_faces[a * ids + b];
      }
    }
  }
  return boundary;
}

/// Edges of the boundary surface not used by exactly two boundary faces.
std::size_t count_nonmanifold_edges(const TetMesh& mesh, const std::vector<FaceKey>& boundary,
                                    ConformityReport& report) {
  std::vector<std::pair<int, int>> edges;  // (smaller id, larger id): face keys are sorted
  edges.reserve(3 * boundary.size());
  for (const auto& f : boundary) {
    edges.emplace_back(f[0], f[1]);
    edges.emplace_back(f[0], f[2]);
    edges.emplace_back(f[1], f[2]);
  }
  std::sort(edges.begin(), edges.end());
  std::size_t bad = 0;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i != 2) {
      ++bad;
      add_defect(report, "nonmanifold_boundary_edges", bad,
                 0.5 * (mesh.points[edges[i].first] + mesh.points[edges[i].second]), 0);
    }
    i = j;
  }
  return bad;
}

/// Groups of >= 2 nodes within `tolerance` of each other (transitively). Nodes are binned in cubic
/// cells of edge 16 * tolerance, found by binary search in the sorted cell list (O(n log n), and no
/// plane sweep that would compare whole slices of a structured grid). A node is compared with the
/// nodes of its own cell and of the neighbour cells whose border is within 2 * tolerance: two
/// nodes within tolerance in different cells are each that close to the border between them (the
/// factor 2 absorbs round-off in the cell coordinates), so no pair across a border is missed,
/// while most nodes are near no border and cost one run scan instead of 26 neighbour lookups.
std::size_t count_duplicate_groups(const std::vector<Eigen::Vector3d>& points,
                                   const BoundingBox& box, double tolerance, ConformityReport& report) {
  const int n = static_cast<int>(points.size());
  if (n < 2) return 0;
  if (!(tolerance > 0)) {  // zero-size box: all nodes coincide
    add_defect(report, "duplicate_node_groups", 1, points[0], 0);
    return 1;
  }

  const double cell_size = 16.0 * tolerance;
  const double near_border = 2.0 * tolerance / cell_size;  // as a fraction of a cell
  using Cell = std::array<std::int64_t, 3>;
  // At most diagonal / cell_size ~ 6e7 cells per axis: fits an int64 comfortably.
  const auto cell_coordinates = [&](int i) -> Eigen::Array3d {
    return (points[i] - box.min).array() / cell_size;
  };
  std::vector<std::pair<Cell, int>> cells(n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Array3d c = cell_coordinates(i).floor();
    cells[i] = {{static_cast<std::int64_t>(c.x()), static_cast<std::int64_t>(c.y()),
                 static_cast<std::int64_t>(c.z())},
                i};
  }
  std::sort(cells.begin(), cells.end());

  std::vector<int> parent = singleton_sets(static_cast<std::size_t>(n));
  const auto join_if_close = [&](int i, int j) {
    if ((points[i] - points[j]).norm() <= tolerance) {
      parent[find_root(parent, i)] = find_root(parent, j);
    }
  };
  for (std::size_t s = 0; s < cells.size(); ++s) {
    const auto& [cell, i] = cells[s];
    for (std::size_t r = s + 1; r < cells.size() && cells[r].first == cell; ++r) {
      join_if_close(i, cells[r].second);
    }
    // Per axis, the neighbour offsets worth visiting: 0, and -1 / +1 when near that border.
    std::array<std::array<int, 3>, 3> offsets;
    std::array<int, 3> count;
    const Eigen::Array3d coordinates = cell_coordinates(i);
    for (int a = 0; a < 3; ++a) {
      const double fraction = coordinates[a] - static_cast<double>(cell[a]);
      count[a] = 0;
      offsets[a][count[a]++] = 0;
      if (fraction < near_border) offsets[a][count[a]++] = -1;
      if (fraction > 1.0 - near_border) offsets[a][count[a]++] = 1;
    }
    for (int x = 0; x < count[0]; ++x) {
      for (int y = 0; y < count[1]; ++y) {
        for (int z = x + y == 0 ? 1 : 0; z < count[2]; ++z) {  // own cell done above
          const Cell other{cell[0] + offsets[0][x], cell[1] + offsets[1][y],
                           cell[2] + offsets[2][z]};
          auto r = std::lower_bound(cells.begin(), cells.end(), other,
                                    [](const auto& e, const Cell& c) { return e.first < c; });
          for (; r != cells.end() && r->first == other; ++r) join_if_close(i, r->second);
        }
      }
    }
  }

  std::vector<int> group_size(n, 0);
  for (int i = 0; i < n; ++i) ++group_size[find_root(parent, i)];
  std::size_t groups = 0;
  for (int i = 0; i < n; ++i) {
    if (group_size[i] >= 2) add_defect(report, "duplicate_node_groups", ++groups, points[i], 0);
  }
  return groups;
}

std::string tissue_label(int id, const std::vector<std::string>& names) {
  if (id == 0) return "outside";
  if (id >= 1 && id <= static_cast<int>(names.size())) return names[id - 1];
  return "tissue " + std::to_string(id);
}

}  // namespace

bool ConformityReport::conforming() const {
  return faces_shared_by_more_than_two == 0 && duplicate_node_groups == 0 && orphan_nodes == 0 &&
         inverted_tets == 0 && degenerate_tets == 0 && nonmanifold_boundary_edges == 0;
}

ConformityReport check_conformity(const TetMesh& mesh) {
  mesh.validate("conformity check");
  ConformityReport report;
  report.nodes = mesh.points.size();
  report.tets = mesh.tets.size();
  report.tissue_names = mesh.tissue_names;

  const BoundingBox box = bounding_box(mesh.points);
  const double diagonal = box.diagonal();
  const double degenerate_volume = kDegenerateVolumeRel * diagonal * diagonal * diagonal;

  std::vector<bool> used(mesh.points.size(), false);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& tet = mesh.tets[t];
    for (int v : tet) used[v] = true;
    std::array<int, 4> sorted = tet;
    std::sort(sorted.begin(), sorted.end());
    const bool repeated = std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
    const double volume = signed_tet_volume(mesh.points[tet[0]], mesh.points[tet[1]],
                                            mesh.points[tet[2]], mesh.points[tet[3]]);
    const Eigen::Vector3d center =
        (mesh.points[tet[0]] + mesh.points[tet[1]] + mesh.points[tet[2]] + mesh.points[tet[3]]) / 4.0;
    if (repeated || std::abs(volume) <= degenerate_volume) {
      add_defect(report, "degenerate_tets", ++report.degenerate_tets, center, mesh.tissue_ids[t]);
    } else if (volume < 0) {
      add_defect(report, "inverted_tets", ++report.inverted_tets, center, mesh.tissue_ids[t]);
    }
  }
  for (std::size_t i = 0; i < used.size(); ++i) {
    if (!used[i]) add_defect(report, "orphan_nodes", ++report.orphan_nodes, mesh.points[i], 0);
  }

  report.nonmanifold_boundary_edges = count_nonmanifold_edges(mesh, match_faces(mesh, report), report);
  report.duplicate_node_groups =
      count_duplicate_groups(mesh.points, box, kCoincidentRel * diagonal, report);
  return report;
}

nlohmann::json to_json(const ConformityReport& report) {
  nlohmann::json interfaces = nlohmann::json::array();
  for (const auto& [pair, faces] : report.interface_faces) {
    interfaces.push_back({{"tissue_a", tissue_label(pair.first, report.tissue_names)},
                          {"tissue_b", tissue_label(pair.second, report.tissue_names)},
                          {"tissue_a_id", pair.first},
                          {"tissue_b_id", pair.second},
                          {"faces", faces}});
  }
  nlohmann::json defects = nlohmann::json::array();
  for (const ConformityDefect& d : report.defects) {
    defects.push_back({{"kind", d.kind},
                       {"position_mm", {d.position.x(), d.position.y(), d.position.z()}},
                       {"tissue", d.tissue == 0 ? std::string() : tissue_label(d.tissue, report.tissue_names)}});
  }
  return {{"conforming", report.conforming()},
          {"nodes", report.nodes},
          {"tets", report.tets},
          {"faces_shared_by_more_than_two", report.faces_shared_by_more_than_two},
          {"boundary_faces", report.boundary_faces},
          {"duplicate_node_groups", report.duplicate_node_groups},
          {"orphan_nodes", report.orphan_nodes},
          {"inverted_tets", report.inverted_tets},
          {"degenerate_tets", report.degenerate_tets},
          {"nonmanifold_boundary_edges", report.nonmanifold_boundary_edges},
          {"interface_faces", std::move(interfaces)},
          {"defects", std::move(defects)}};
}

std::string format_conformity_table(const ConformityReport& report,
                                    const std::vector<std::string>& tissue_names) {
  std::ostringstream out;
  out << std::left;
  const auto count = [&](const char* what, std::size_t value, bool must_be_zero) {
    out << std::setw(32) << what << std::right << std::setw(10) << value << std::left;
    if (must_be_zero) out << (value == 0 ? "  ok" : "  FAIL (must be 0)");
    out << "\n";
  };
  count("nodes", report.nodes, false);
  count("tets", report.tets, false);
  count("boundary faces", report.boundary_faces, false);
  count("faces shared by more than two", report.faces_shared_by_more_than_two, true);
  count("duplicate node groups", report.duplicate_node_groups, true);
  count("orphan nodes", report.orphan_nodes, true);
  count("inverted tets", report.inverted_tets, true);
  count("degenerate tets", report.degenerate_tets, true);
  count("non-manifold boundary edges", report.nonmanifold_boundary_edges, true);
  out << (report.conforming() ? "conforming: yes\n" : "conforming: NO\n");
  if (!report.defects.empty()) {
    out << "where (first " << kMaxDefectsPerKind << " of each kind; LPS mm):\n" << std::fixed
        << std::setprecision(2);
    for (const ConformityDefect& d : report.defects) {
      out << "  " << std::setw(30) << d.kind << " (" << d.position.x() << ", " << d.position.y() << ", "
          << d.position.z() << ")";
      if (d.tissue != 0) out << "  " << tissue_label(d.tissue, tissue_names);
      out << "\n";
    }
    out << std::defaultfloat << std::setprecision(6);
  }

  std::size_t width = std::string("tissue a").size();
  for (const auto& [pair, faces] : report.interface_faces) {
    width = std::max({width, tissue_label(pair.first, tissue_names).size(),
                      tissue_label(pair.second, tissue_names).size()});
  }
  const int w = static_cast<int>(width);
  out << "\n" << std::setw(w) << "tissue a" << "  " << std::setw(w) << "tissue b" << std::right
      << std::setw(10) << "faces" << std::left << "\n";
  for (const auto& [pair, faces] : report.interface_faces) {
    out << std::setw(w) << tissue_label(pair.first, tissue_names) << "  " << std::setw(w)
        << tissue_label(pair.second, tissue_names) << std::right << std::setw(10) << faces
        << std::left << "\n";
  }
  return out.str();
}

}  // namespace tissuemesh
