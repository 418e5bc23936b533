// Element quality of a multi-material tetrahedral mesh, per tissue and in total.
//
// Shape measures follow the usual definitions (Shewchuk, "What is a good linear finite element?",
// 2002): the six interior dihedral angles, the normalised radius ratio 3 r / R (Gmsh's gamma),
// Gmsh's signed inverse condition number SICN and TetGen's radius-edge ratio (see TetShape).
// Volume fidelity is measured against a reference volume per tissue (e.g. its voxel volume).
//
// Units: lengths in mm, volumes in mm^3, angles in degrees. O(n) in tets. Deterministic: the
// per-tet loop runs serially in tet order.
#pragma once

#include "core/tet_mesh.h"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace tissuemesh {

/// Local node pairs of the six edges of a tet (a,b,c,d) = (0,1,2,3); TetShape::dihedral_deg[i] is
/// the dihedral angle at edge kTetEdges[i].
inline constexpr std::array<std::array<int, 2>, 6> kTetEdges{
    {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};

/// Shape of one tetrahedron.
struct TetShape {
  /// Interior dihedral angle at each edge (order: kTetEdges), degrees in [0, 180]. The regular
  /// tetrahedron has acos(1/3) = 70.5288 degrees everywhere. Independent of orientation: an
  /// inverted tet has the same angles as its mirror image.
  std::array<double, 6> dihedral_deg;
  /// 3 * inradius / circumradius in [0, 1]: 1 for the regular tet, 0 for a degenerate one
  /// (coplanar or coincident nodes). Independent of orientation.
  double radius_ratio;
  /// Signed inverse condition number as Gmsh defines it for a linear tet: with A the affine map
  /// from the unit regular tetrahedron to this one, 3 / (|A|_F |A^-1|_F), negative when the tet
  /// is inverted. 1 for the regular tet, 0 for a degenerate one, sqrt(2/3) for the right-corner
  /// tet; in [-1, 1].
  double sicn;
  /// Circumradius over shortest edge, TetGen's radius-edge ratio (its -q bound): sqrt(6)/4 =
  /// 0.612 for the regular tet, sqrt(3)/2 for the right-corner tet; +infinity for a flat or
  /// collapsed tet. Blind to slivers (four nearly coplanar nodes on a circle keep it near
  /// 1/sqrt(2)), hence the dihedral angles next to it. Independent of orientation.
  double radius_edge_ratio;
  /// Circumradius, mm (the size CGAL's and TetGen's cell criteria bound); +infinity when flat.
  double circumradius_mm;
  /// Signed volume, mm^3: positive for a positively oriented tet (see TetMesh), negative inverted.
  double volume_mm3;
};

/// Shape of the tetrahedron (a, b, c, d), coordinates in mm. Never throws; a degenerate tet gets
/// radius_ratio 0 and whatever angles its (near-)flat geometry defines (0 or 180 when flat, 0 for
/// an edge of zero length).
TetShape tet_shape(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d);

/// What the sliver repairs look at, bit for bit the values of tet_shape (the same arithmetic; the
/// file is compiled without floating-point contraction so that no build fuses it differently in
/// the two) at a fraction of its cost: the signed volume (mm^3) and the smallest dihedral angle
/// (degrees).
struct TetVolumeAndAngle {
  double volume_mm3;
  double min_dihedral_deg;
};
TetVolumeAndAngle tet_volume_and_min_dihedral(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                              const Eigen::Vector3d& c, const Eigen::Vector3d& d);

/// Histogram of dihedral angles: every tet contributes all six of its angles, so the counts sum to
/// 6 * tets. Bin i holds angles in [i * bin_width_deg, (i + 1) * bin_width_deg); 180 degrees falls
/// in the last bin. An angle within 1e-9 degrees below a bin edge counts in the upper bin, so that
/// exact angles of structured meshes (45, 60, 90 degrees) land in the same bin whatever the
/// round-off.
struct DihedralHistogram {
  double bin_width_deg = 5;
  std::vector<std::size_t> counts = std::vector<std::size_t>(36, 0);  ///< 36 bins over [0, 180]
};

/// Quality of one tissue (or of the whole mesh: QualityReport::total).
struct TissueQuality {
  static constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();

  std::string name;               ///< tissue name; "all tissues" for the total
  int id = 0;                     ///< 1-based tissue id; 0 for the total
  std::size_t tets = 0;           ///< tets of this tissue
  std::size_t vertices = 0;       ///< distinct nodes used by these tets (interface nodes count
                                  ///< in every tissue they touch; orphan nodes in none)
  double volume_mm3 = 0;          ///< sum of signed tet volumes (an inverted tet subtracts)
  double reference_volume_mm3 = kUnknown;  ///< e.g. voxel volume of the tissue; NaN when unknown
  double volume_error_rel = kUnknown;      ///< (volume - reference) / reference; NaN when unknown
  double min_dihedral_deg = kUnknown;      ///< smallest dihedral angle; NaN without tets
  double max_dihedral_deg = kUnknown;      ///< largest dihedral angle; NaN without tets
  std::size_t tets_below_10deg = 0;        ///< tets with any dihedral angle < 10 degrees
  std::size_t tets_below_5deg = 0;         ///< tets with any dihedral angle < 5 degrees
  double min_radius_ratio = kUnknown;      ///< NaN without tets
  double mean_radius_ratio = kUnknown;     ///< NaN without tets
  double min_sicn = kUnknown;              ///< smallest TetShape::sicn; NaN without tets
  /// Largest TetShape::radius_edge_ratio; NaN without tets, +infinity with a flat tet (JSON: null
  /// for both; the table prints "-" and "inf").
  double max_radius_edge_ratio = kUnknown;
  std::size_t tets_radius_edge_above_2 = 0;  ///< tets with radius_edge_ratio > 2 (TetGen's -q2)
  DihedralHistogram dihedral_histogram;
};

/// Per-tissue quality (one entry per tissue id 1..mesh.num_tissues(), in id order, including
/// tissues without tets so that a lost tissue shows) and the total over all tets.
struct QualityReport {
  std::vector<TissueQuality> tissues;
  TissueQuality total;  ///< reference volume: sum of all tissues' references if all are known
};

/// Quality report of `mesh`. reference_volumes maps tissue id -> reference volume in mm^3
/// (optional, any subset of the tissues). Throws InputError when the mesh is inconsistent
/// (TetMesh::validate) or a reference names an unknown tissue id or is not a positive finite
/// number.
QualityReport compute_quality(const TetMesh& mesh,
                              const std::map<int, double>& reference_volumes = {});

/// {"tissues": [...], "total": {...}}; each tissue object has the TissueQuality field names
/// (units in the key names: volume_mm3, min_dihedral_deg, ...), NaN written as null, and
/// "dihedral_histogram": {"bin_width_deg", "counts", "angles_per_tet": 6}.
nlohmann::json to_json(const QualityReport& report);

/// Human-readable fixed-width table: one row per tissue and a total row, units in the headers;
/// unknown values shown as "-". Ends with a newline.
std::string format_quality_table(const QualityReport& report);

}  // namespace tissuemesh
