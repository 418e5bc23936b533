// Why: small dihedral angles spoil the conditioning of the stiffness matrix and angles near 180
// degrees spoil interpolation, so both ends of the angle range are reported. Volume fidelity
// against a reference sits next to the shape measures because a mesher that silently loses thin
// tissue is the failure users care about most.
#include "quality/mesh_quality.h"

#include "core/errors.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <utility>

namespace tissuemesh {

namespace {

constexpr double kDegPerRad = 180.0 / 3.14159265358979323846;

// Structured meshes have exact 45/60/90 degree angles that round-off puts a hair below or above
// the bin edge; snapping by far less than any meaningful angle difference makes the histogram
// reproducible across compilers and input transformations.
constexpr double kBinEdgeSnapDeg = 1e-9;

std::size_t histogram_bin(const DihedralHistogram& h, double angle_deg) {
  const double x = (angle_deg + kBinEdgeSnapDeg) / h.bin_width_deg;
  // Written so that NaN (non-finite coordinates) lands in bin 0 instead of an undefined cast.
  if (!(x >= 1.0)) return 0;
  return std::min(static_cast<std::size_t>(x), h.counts.size() - 1);
}

// Starting values of the running extremes and sums that accumulate() updates.
TissueQuality empty_quality(std::string name, int id) {
  TissueQuality q;
  q.name = std::move(name);
  q.id = id;
  q.min_dihedral_deg = std::numeric_limits<double>::infinity();
  q.max_dihedral_deg = -std::numeric_limits<double>::infinity();
  q.min_radius_ratio = std::numeric_limits<double>::infinity();
  q.mean_radius_ratio = 0;  // running sum until finish()
  q.min_sicn = std::numeric_limits<double>::infinity();
  q.max_radius_edge_ratio = 0;
  return q;
}

void accumulate(TissueQuality& q, const TetShape& s) {
  ++q.tets;
  q.volume_mm3 += s.volume_mm3;
  const auto [lo, hi] = std::minmax_element(s.dihedral_deg.begin(), s.dihedral_deg.end());
  q.min_dihedral_deg = std::min(q.min_dihedral_deg, *lo);
  q.max_dihedral_deg = std::max(q.max_dihedral_deg, *hi);
  if (*lo < 10.0) ++q.tets_below_10deg;
  if (*lo < 5.0) ++q.tets_below_5deg;
  q.min_radius_ratio = std::min(q.min_radius_ratio, s.radius_ratio);
  q.mean_radius_ratio += s.radius_ratio;
  q.min_sicn = std::min(q.min_sicn, s.sicn);
  q.max_radius_edge_ratio = std::max(q.max_radius_edge_ratio, s.radius_edge_ratio);
  if (s.radius_edge_ratio > 2.0) ++q.tets_radius_edge_above_2;
  auto& histogram = q.dihedral_histogram;
  for (double angle : s.dihedral_deg) ++histogram.counts[histogram_bin(histogram, angle)];
}

void finish(TissueQuality& q, const std::vector<bool>& used_nodes, double reference_mm3) {
  q.vertices = static_cast<std::size_t>(std::count(used_nodes.begin(), used_nodes.end(), true));
  if (q.tets == 0) {
    q.min_dihedral_deg = q.max_dihedral_deg = TissueQuality::kUnknown;
    q.min_radius_ratio = q.mean_radius_ratio = q.min_sicn = q.max_radius_edge_ratio = TissueQuality::kUnknown;
  } else {
    q.mean_radius_ratio /= static_cast<double>(q.tets);
  }
  q.reference_volume_mm3 = reference_mm3;
  q.volume_error_rel = (q.volume_mm3 - reference_mm3) / reference_mm3;  // NaN propagates
}

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

nlohmann::json tissue_json(const TissueQuality& q) {
  return {{"name", q.name},
          {"id", q.id},
          {"tets", q.tets},
          {"vertices", q.vertices},
          {"volume_mm3", q.volume_mm3},
          {"reference_volume_mm3", number_or_null(q.reference_volume_mm3)},
          {"volume_error_rel", number_or_null(q.volume_error_rel)},
          {"min_dihedral_deg", number_or_null(q.min_dihedral_deg)},
          {"max_dihedral_deg", number_or_null(q.max_dihedral_deg)},
          {"tets_below_10deg", q.tets_below_10deg},
          {"tets_below_5deg", q.tets_below_5deg},
          {"min_radius_ratio", number_or_null(q.min_radius_ratio)},
          {"mean_radius_ratio", number_or_null(q.mean_radius_ratio)},
          {"min_sicn", number_or_null(q.min_sicn)},
          {"max_radius_edge_ratio", number_or_null(q.max_radius_edge_ratio)},
          {"tets_radius_edge_above_2", q.tets_radius_edge_above_2},
          {"dihedral_histogram",
           {{"bin_width_deg", q.dihedral_histogram.bin_width_deg},
            {"counts", q.dihedral_histogram.counts},
            {"angles_per_tet", 6}}}};
}

// Fixed-point cell of a value that may be unknown (NaN): unknown values print as "-".
std::string cell(double v, int width, int precision) {
  std::ostringstream s;
  s << std::setw(width);
  if (std::isnan(v)) {
    s << "-";
  } else {
    s << std::fixed << std::setprecision(precision) << v;
  }
  return s.str();
}

std::string table_row(const TissueQuality& q, int name_width) {
  std::ostringstream row;
  row << std::left << std::setw(name_width) << q.name << std::right << std::setw(10) << q.tets
      << std::setw(10) << q.vertices << cell(q.volume_mm3, 15, 2)
      << cell(q.reference_volume_mm3, 15, 2) << cell(100.0 * q.volume_error_rel, 9, 2)
      << cell(q.min_dihedral_deg, 9, 2) << cell(q.max_dihedral_deg, 9, 2) << std::setw(9)
      << q.tets_below_10deg << std::setw(9) << q.tets_below_5deg << cell(q.min_radius_ratio, 9, 3)
      << cell(q.mean_radius_ratio, 9, 3) << cell(q.min_sicn, 9, 3) << cell(q.max_radius_edge_ratio, 9, 3)
      << std::setw(9) << q.tets_radius_edge_above_2 << "\n";
  return row.str();
}

/// The edge vectors from a, the area vectors of the faces opposite each node, all pointing towards
/// that node when the tet is positively oriented (all away from it when inverted), so that the
/// interior angle formula of dihedral_deg holds for either orientation, and 6 * signed volume.
struct TetFrame {
  Eigen::Vector3d ab, ac, ad;
  std::array<Eigen::Vector3d, 4> n;
  double det;
  TetFrame(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d)
      : ab(b - a), ac(c - a), ad(d - a), n{(d - b).cross(c - b), ac.cross(ad), ad.cross(ab), ab.cross(ac)},
        det(ab.dot(n[1])) {}
  /// Dihedral angle at edge kTetEdges[i]: the faces through it are those opposite the nodes of the
  /// opposite edge (5 - i). With inward normals the interior angle is pi minus the angle between
  /// them; atan2 stays accurate near 0 and 180 degrees where acos of a cosine loses half the digits.
  double dihedral_deg(std::size_t i) const {
    const auto [sine, cosine] = dihedral_sin_cos(i);
    return std::atan2(sine, cosine) * kDegPerRad;
  }
  /// The arguments of dihedral_deg's atan2: |sin| and cos of the angle times the same positive
  /// factor (the product of the two face areas, doubled).
  std::pair<double, double> dihedral_sin_cos(std::size_t i) const {
    const auto [k, l] = kTetEdges[5 - i];
    return {n[k].cross(n[l]).norm(), -n[k].dot(n[l])};
  }
  /// The smallest of the six dihedral_deg, the same double, with one atan2 where the angles are
  /// apart: in [0, pi] the angle of (cos, sin) grows as the cross product of two such vectors
  /// says, so the smallest is found by comparisons, and only it and the angles within 1e-10 rad
  /// of it (a tie, or a comparison rounding could have got wrong) go through atan2.
  double min_dihedral_deg() const {
    std::array<std::pair<double, double>, 6> v;
    for (std::size_t i = 0; i < 6; ++i) v[i] = dihedral_sin_cos(i);
    // (theta_j - theta_i) has the sign of cos_i sin_j - sin_i cos_j.
    auto ahead = [&](std::size_t i, std::size_t j) { return v[i].second * v[j].first - v[i].first * v[j].second; };
    std::size_t best = 0;
    for (std::size_t i = 1; i < 6; ++i)
      if (ahead(i, best) > 0.0) best = i;
    constexpr double kTieRad = 1e-10;
    const double best_norm2 = v[best].first * v[best].first + v[best].second * v[best].second;
    double smallest = 0.0;
    bool first = true;
    for (std::size_t i = 0; i < 6; ++i) {
      const double gap = ahead(best, i);  // > 0: angle i above the best
      const double norm2 = v[i].first * v[i].first + v[i].second * v[i].second;
      if (i != best && gap > 0.0 && gap * gap > kTieRad * kTieRad * best_norm2 * norm2) continue;
      const double angle = std::atan2(v[i].first, v[i].second) * kDegPerRad;
      if (first || angle < smallest) smallest = angle;  // std::min_element's rule, as over tet_shape's
      first = false;
    }
    return smallest;
  }
};

}  // namespace

TetVolumeAndAngle tet_volume_and_min_dihedral(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                              const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  const TetFrame f(a, b, c, d);
  return {f.det / 6.0, f.min_dihedral_deg()};
}

TetShape tet_shape(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d) {
  const TetFrame f(a, b, c, d);
  const Eigen::Vector3d &ab = f.ab, &ac = f.ac, &ad = f.ad;
  const std::array<Eigen::Vector3d, 4>& n = f.n;
  const double det = f.det;  // 6 * signed volume

  TetShape s;
  s.volume_mm3 = det / 6.0;
  for (std::size_t i = 0; i < kTetEdges.size(); ++i) s.dihedral_deg[i] = f.dihedral_deg(i);

  // r = 3|V| / area = |det| / (2 area) and R = |m| / (2 |det|), where m / (2 det) is the
  // circumcentre relative to a; so 3 r / R = 3 det^2 / (area |m|): no division by a tiny det.
  const double area = 0.5 * (n[0].norm() + n[1].norm() + n[2].norm() + n[3].norm());
  const Eigen::Vector3d m = ab.squaredNorm() * n[1] + ac.squaredNorm() * n[2] +
                            ad.squaredNorm() * n[3];
  const double denominator = area * m.norm();
  s.radius_ratio = denominator > 0 ? 3.0 * det * det / denominator : 0.0;
  // R = |m| / (2 |det|) over the shortest of the six edges.
  const double shortest = std::sqrt(std::min({ab.squaredNorm(), ac.squaredNorm(), ad.squaredNorm(),
                                              (c - b).squaredNorm(), (d - b).squaredNorm(),
                                              (d - c).squaredNorm()}));
  s.circumradius_mm = det != 0.0 ? m.norm() / (2.0 * std::abs(det)) : std::numeric_limits<double>::infinity();
  s.radius_edge_ratio = det != 0.0 && shortest > 0.0 ? s.circumradius_mm / shortest
                                                     : std::numeric_limits<double>::infinity();

  // SICN = 3 / (|E W^-1|_F |W E^-1|_F) with E = [ab ac ad] and W the same for the unit regular
  // tet. E^-1 = adj(E) / det, whose rows are n[1..3], so SICN = 3 det / (|E W^-1|_F |W adj(E)|_F):
  // again no division by a tiny det, and the sign of det carries the orientation.
  static const Eigen::Matrix3d w = [] {
    Eigen::Matrix3d m;
    m.col(0) = Eigen::Vector3d(1, 0, 0);
    m.col(1) = Eigen::Vector3d(0.5, std::sqrt(3.0) / 2, 0);
    m.col(2) = Eigen::Vector3d(0.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3.0));
    return m;
  }();
  static const Eigen::Matrix3d w_inverse = w.inverse();
  Eigen::Matrix3d e, adjugate;
  e << ab, ac, ad;
  adjugate << n[1].transpose(), n[2].transpose(), n[3].transpose();
  const double sicn_denominator = (e * w_inverse).norm() * (w * adjugate).norm();
  s.sicn = sicn_denominator > 0 ? 3.0 * det / sicn_denominator : 0.0;
  return s;
}

QualityReport compute_quality(const TetMesh& mesh, const std::map<int, double>& reference_volumes) {
  mesh.validate("mesh quality");
  const int ntissues = static_cast<int>(mesh.num_tissues());
  std::vector<double> reference(ntissues + 1, TissueQuality::kUnknown);  // index 0: total
  for (const auto& [id, volume] : reference_volumes) {
    std::ostringstream err;
    if (id < 1 || id > ntissues) {
      err << "reference volume given for tissue id " << id << " but the mesh names tissues 1.."
          << ntissues;
      throw InputError(err.str());
    }
    if (!(std::isfinite(volume) && volume > 0)) {
      err << "reference volume of tissue '" << mesh.tissue_names[id - 1] << "' is " << volume
          << " mm^3; it must be a positive number";
      throw InputError(err.str());
    }
    reference[id] = volume;
  }
  if (ntissues > 0 && reference_volumes.size() == static_cast<std::size_t>(ntissues)) {
    reference[0] = 0;
    for (int id = 1; id <= ntissues; ++id) reference[0] += reference[id];
  }

  // Index 0 accumulates the total, index id the tissue. Serial on purpose: the loop is cheap next
  // to meshing, and a serial sum is the simplest way to make the volumes bit-identical run to run.
  std::vector<TissueQuality> acc;
  acc.push_back(empty_quality("all tissues", 0));
  for (int id = 1; id <= ntissues; ++id) {
    acc.push_back(empty_quality(mesh.tissue_names[id - 1], id));
  }
  std::vector<std::vector<bool>> used(ntissues + 1, std::vector<bool>(mesh.points.size(), false));

  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& tet = mesh.tets[t];
    const int id = mesh.tissue_ids[t];
    const TetShape s = tet_shape(mesh.points[tet[0]], mesh.points[tet[1]], mesh.points[tet[2]],
                                 mesh.points[tet[3]]);
    accumulate(acc[id], s);
    accumulate(acc[0], s);
    for (int v : tet) used[id][v] = used[0][v] = true;
  }
  for (int id = 0; id <= ntissues; ++id) finish(acc[id], used[id], reference[id]);

  QualityReport report;
  report.total = std::move(acc[0]);
  report.tissues.assign(std::make_move_iterator(acc.begin() + 1),
                        std::make_move_iterator(acc.end()));
  return report;
}

nlohmann::json to_json(const QualityReport& report) {
  nlohmann::json tissues = nlohmann::json::array();
  for (const auto& q : report.tissues) tissues.push_back(tissue_json(q));
  return {{"tissues", std::move(tissues)}, {"total", tissue_json(report.total)}};
}

std::string format_quality_table(const QualityReport& report) {
  int name_width = static_cast<int>(std::string("tissue").size());
  for (const auto& q : report.tissues) {
    name_width = std::max(name_width, static_cast<int>(q.name.size()));
  }
  name_width = std::max(name_width, static_cast<int>(report.total.name.size()));

  std::ostringstream header;
  header << std::left << std::setw(name_width) << "tissue" << std::right << std::setw(10)
         << "tets" << std::setw(10) << "vertices" << std::setw(15) << "volume[mm^3]"
         << std::setw(15) << "ref.vol[mm^3]" << std::setw(9) << "err[%]" << std::setw(9)
         << "min[deg]" << std::setw(9) << "max[deg]" << std::setw(9) << "<10deg" << std::setw(9)
         << "<5deg" << std::setw(9) << "min RR" << std::setw(9) << "mean RR" << std::setw(9) << "min SICN"
         << std::setw(9) << "max R/l" << std::setw(9) << "R/l>2" << "\n";
  std::string out = header.str();
  for (const auto& q : report.tissues) out += table_row(q, name_width);
  out += table_row(report.total, name_width);
  out += "min/max: dihedral angles; <10deg, <5deg: tets with a dihedral below; RR: radius ratio "
         "3r/R (1 = regular, Gmsh's gamma); SICN: Gmsh's signed inverse condition number (1 = regular, < 0 "
         "inverted); R/l: circumradius / shortest edge (TetGen's radius-edge ratio; 0.612 = regular), R/l>2: "
         "tets above 2; err: volume vs reference\n";
  return out;
}

}  // namespace tissuemesh
