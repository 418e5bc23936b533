// Why: flips (sliver_flips.h) cannot repair a flat tet whose bad angle sits at an edge of the
// boundary or of an interface, and CGAL's exudation cannot move vertices. A free vertex's star
// (the tets around it) lies in one tissue and closes around it, so its outer faces stay where they
// are. Planar vertices are common on flat cuts: on the phantom's chest-wall plane CGAL leaves rows
// of surface vertices 0.1-0.3 mm apart midway between two protected junction curves.
// Near-planar vertices sit on nearly flat patches of a curved interface (e.g. a thin fat layer
// between skin and muscle whose tets span it); they move orthogonal to their tissue's volume
// gradient (recomputed at each move), which is the area-weighted sum of the face normals, hence
// the sin(2 angle) bound on the surface's move. On-surface moves project each trial position onto
// the reference patch, so only the boundary's triangles between its vertices change; a projection
// that lands further away than twice the step (the far side of a thin sheet of tissue) is not
// tried. The pattern search steps along the axes and along the normal of the face opposite the
// vertex in its star's worst tet (projected into its plane for a planar vertex), halving from a
// quarter of its mean edge length; a move is kept only when it raises the star's smallest angle,
// or keeps it and lowers the star's squared shortfall below the target.
#include "volume/sliver_smoothing.h"

#include "quality/mesh_quality.h"
#include "quality/tet_faces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace tissuemesh {

namespace {

TetVolumeAndAngle shape(const TetMesh& mesh, const std::array<int, 4>& k) {
  return tet_volume_and_min_dihedral(mesh.points[k[0]], mesh.points[k[1]], mesh.points[k[2]], mesh.points[k[3]]);
}

// Unit normals of surface faces at a vertex that are this close (radians) count as one plane: a
// move by d within it leaves the surface within d * 1e-6 of where it was.
constexpr double kPlanarRad = 1e-6;
// A vertex moves over the reference surface only where its oriented face normals are within this
// angle (radians) of the first one's: a curved patch, not a crease or the rim of a thin sheet, which a
// move projected onto one side would cut. 45 degrees still admits bent sheets of tissue, whose
// slivers a tighter limit (30 degrees) leaves unrepaired.
constexpr double kOnSurfaceMaxRad = 45.0 * M_PI / 180.0;

// How a vertex may move without changing any tissue's boundary (near-planar: its volume).
struct Mobility {
  /// kOffSurface: anywhere within the offset bound of where it was (smooth_slivers' offset_edge_ratio).
  enum Kind : char { kFixed, kFree, kInPlane, kOnSurface, kOffSurface } kind = kFixed;
  /// The region pair of its faces (pair.second: the tissue whose volume near-planar moves keep).
  std::pair<int, int> pair{-1, -1};
  /// Unit normal of its first face, oriented from pair.first into pair.second (kInPlane: of the
  /// plane it moves in), and the smallest |cos| and signed cos between it and its other faces'
  /// oriented normals: a fold (the rim of a thin sheet of tissue, faces facing each other) has a
  /// negative signed one, however flat it looks unoriented.
  Eigen::Vector3d normal{0, 0, 0};
  double min_cos = 1.0;
  double min_oriented_cos = 1.0;
  /// kInPlane with faces not all in one plane (min_cos below cos(kPlanarRad)): moves in the plane
  /// that keeps its tissue's volume (volume_plane), computed at each move from the star's nodes.
  bool near_planar() const { return kind == kInPlane && min_cos < std::cos(kPlanarRad); }
};

// Free: on no boundary face and no interface face (its star lies in one tissue and closes around
// it). In plane: every boundary or interface face at it lies on one region pair and one plane
// (e.g. the cut chest-wall plane), so it may slide in that plane; with `near_planar_rad` > 0 also
// when their normals are within that angle of the first one's (then it moves in the plane that
// keeps its tissue's volume; see volume_plane). On surface (only with `on_surface`): one region
// pair, faces in no common plane. Fixed: everything else (junction and corner vertices, and
// curved patches without `on_surface`).
std::vector<Mobility> mobility(const TetMesh& mesh, double near_planar_rad, bool on_surface) {
  const double min_cos = std::cos(std::max(kPlanarRad, near_planar_rad));
  struct Face {
    int tets = 0, tissue = 0, other = 0;  // tissue of the first tet and of the second (0 = none)
    std::array<int, 3> nodes{};
  };
  const TetFaces ids = number_tet_faces(mesh.tets);
  std::vector<Face> faces(ids.count);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& k = mesh.tets[t];
    for (int f = 0; f < 4; ++f) {
      Face& face = faces[static_cast<std::size_t>(ids.of(t, f))];
      if (face.tets == 0) {  // first seen from this tet
        face.tissue = mesh.tissue_ids[t];
        face.nodes = {k[(f + 1) % 4], k[(f + 2) % 4], k[(f + 3) % 4]};
      } else {
        face.other = mesh.tissue_ids[t];
      }
      ++face.tets;
    }
  }
  std::vector<Mobility> out(mesh.points.size());
  for (auto& m : out) m.kind = Mobility::kFree;
  // Visit the faces in tet order (from each side), not in id order.
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& k = mesh.tets[t];
    for (int f = 0; f < 4; ++f) {
      const Face& face = faces[static_cast<std::size_t>(ids.of(t, f))];
      if (face.tets == 2 && face.tissue == face.other) continue;  // inside one tissue
      const std::pair<int, int> pair = std::minmax(face.tissue, face.tets == 1 ? 0 : face.other);
      const Eigen::Vector3d a = mesh.points[face.nodes[0]], b = mesh.points[face.nodes[1]], c = mesh.points[face.nodes[2]];
      Eigen::Vector3d n = (b - a).cross(c - a);
      if (n.norm() > 0) n.normalize();
      // Outward from this tet's tissue (away from its fourth node), then from pair.first into pair.second.
      Eigen::Vector3d o = n.dot(mesh.points[static_cast<std::size_t>(k[f])] - a) > 0 ? Eigen::Vector3d(-n) : n;
      if (mesh.tissue_ids[t] != pair.first) o = -o;
      for (int v : face.nodes) {
        Mobility& m = out[static_cast<std::size_t>(v)];
        if (m.kind == Mobility::kFree) {
          m.kind = n.norm() > 0 ? Mobility::kInPlane : Mobility::kFixed;
          m.normal = o;
          m.pair = pair;
        } else if (m.kind == Mobility::kInPlane) {
          m.min_cos = std::min(m.min_cos, std::abs(m.normal.dot(o)));
          m.min_oriented_cos = std::min(m.min_oriented_cos, m.normal.dot(o));
          if (m.pair != pair || n.norm() == 0) m.kind = Mobility::kFixed;
        }
      }
    }
  }
  // One region pair: in plane while the normals agree (exactly, or within near_planar_rad), else
  // on the surface when there is one to move over.
  for (Mobility& m : out)
    if (m.kind == Mobility::kInPlane) {
      const bool planar = m.min_cos >= std::cos(kPlanarRad);
      if (!planar && on_surface && m.min_oriented_cos >= std::cos(kOnSurfaceMaxRad)) m.kind = Mobility::kOnSurface;
      else if (m.min_cos < min_cos) m.kind = Mobility::kFixed;
    }
  return out;
}

// Unit normal of the plane in which moves of v keep the volume of `tissue` (and so of every
// region of v's star): the volume of each tet is linear in v's position, so the tissue's volume
// gradient g, the sum over its tets at v of d(volume)/dv, is constant, and moves orthogonal to g
// keep that volume exactly. In a closed star the other tissue's volume is the star's (fixed) minus
// it; in an open one (boundary) the other region is the outside. Zero if g vanishes.
Eigen::Vector3d volume_plane(const TetMesh& mesh, const std::vector<std::size_t>& star, int v, int tissue) {
  // An even permutation of (0,1,2,3) that brings index i first, keeping the orientation.
  static const int kFirst[4][4] = {{0, 1, 2, 3}, {1, 0, 3, 2}, {2, 3, 0, 1}, {3, 2, 1, 0}};
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  for (std::size_t t : star) {
    if (mesh.tissue_ids[t] != tissue) continue;
    const auto& k = mesh.tets[t];
    const int i = static_cast<int>(std::find(k.begin(), k.end(), v) - k.begin());
    const Eigen::Vector3d& x1 = mesh.points[static_cast<std::size_t>(k[kFirst[i][1]])];
    const Eigen::Vector3d& x2 = mesh.points[static_cast<std::size_t>(k[kFirst[i][2]])];
    const Eigen::Vector3d& x3 = mesh.points[static_cast<std::size_t>(k[kFirst[i][3]])];
    g -= (x2 - x1).cross(x3 - x1) / 6.0;  // d/dx0 of (x1 - x0).((x2 - x0) x (x3 - x0)) / 6
  }
  return g.norm() > 0 ? Eigen::Vector3d(g.normalized()) : Eigen::Vector3d::Zero();
}

class Smoother {
 public:
  Smoother(TetMesh& mesh, double target_deg, const SurfaceProjector& onto_surface, double offset_edge_ratio)
      : mesh_(mesh), target_deg_(target_deg), onto_surface_(onto_surface), star_start_(mesh.points.size() + 1, 0) {
    for (const auto& k : mesh.tets)
      for (int v : k) ++star_start_[static_cast<std::size_t>(v) + 1];
    for (std::size_t i = 1; i < star_start_.size(); ++i) star_start_[i] += star_start_[i - 1];
    star_.resize(star_start_.back());
    std::vector<std::size_t> fill(star_start_.begin(), star_start_.end() - 1);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
      for (int v : mesh.tets[t]) star_[fill[static_cast<std::size_t>(v)]++] = t;
    if (offset_edge_ratio > 0.0) {
      origin_ = mesh.points;
      max_offset_.resize(mesh.points.size());
      for (std::size_t v = 0; v < mesh.points.size(); ++v)
        max_offset_[v] = offset_edge_ratio * mean_edge(static_cast<int>(v));
    }
  }

  /// Mean distance from v to the other nodes of its star's tets (each counted once per tet), mm.
  double mean_edge(int v) const {
    const Eigen::Vector3d& x = mesh_.points[static_cast<std::size_t>(v)];
    double sum = 0;
    std::size_t edges = 0;
    for (std::size_t i = star_start_[v]; i < star_start_[v + 1]; ++i)
      for (int w : mesh_.tets[star_[i]])
        if (w != v) {
          sum += (mesh_.points[static_cast<std::size_t>(w)] - x).norm();
          ++edges;
        }
    return sum / static_cast<double>(std::max<std::size_t>(edges, 1));
  }

  /// v's star at v's current position: its smallest dihedral angle (-inf when a tet is not
  /// positive), the tet that has it, and the sum over its tets of (target - smallest angle)^2 for
  /// those below the target.
  struct StarQuality {
    double min_deg = std::numeric_limits<double>::infinity();
    double shortfall = 0;
    std::size_t worst = 0;
    /// Better: a larger minimum, or the same minimum with less shortfall (a star whose worst tet
    /// no move of v can improve, e.g. one with a flat face opposite v, still lets v fix the
    /// others).
    bool better_than(const StarQuality& o) const {
      return min_deg > o.min_deg || (min_deg == o.min_deg && shortfall < o.shortfall);
    }
  };
  /// With `floor_deg`: stops (min_deg -inf) at the first tet under it, whose star cannot beat one
  /// whose smallest angle is at least floor_deg; the figures of a star that passes are the same.
  StarQuality star_quality(int v, double floor_deg = -std::numeric_limits<double>::infinity()) const {
    StarQuality q;
    for (std::size_t i = star_start_[v]; i < star_start_[v + 1]; ++i) {
      const TetVolumeAndAngle s = shape(mesh_, mesh_.tets[star_[i]]);
      if (!(s.volume_mm3 > 0) || s.min_dihedral_deg < floor_deg) {
        q.min_deg = -std::numeric_limits<double>::infinity();
        return q;
      }
      const double m = s.min_dihedral_deg;
      if (m < target_deg_) q.shortfall += (target_deg_ - m) * (target_deg_ - m);
      if (m < q.min_deg) {
        q.min_deg = m;
        q.worst = star_[i];
      }
    }
    return q;
  }

  /// v's star (tet indices).
  std::vector<std::size_t> star(int v) const {
    return {star_.begin() + static_cast<std::ptrdiff_t>(star_start_[v]),
            star_.begin() + static_cast<std::ptrdiff_t>(star_start_[v + 1])};
  }

  /// Pattern search on v's position, in its plane when it has one; true when v moved.
  bool improve(int v, Mobility mobility) {
    if (mobility.near_planar()) {
      mobility.normal = volume_plane(mesh_, star(v), v, mobility.pair.second);
      if (mobility.normal.isZero()) return false;
    }
    Eigen::Vector3d& p = mesh_.points[static_cast<std::size_t>(v)];
    const Eigen::Vector3d start = p;
    const StarQuality q0 = star_quality(v);
    // Off the surface the move is as short as it can be: steps of a quarter of the bound, and no
    // gain counted past the target angle, so the vertex stops once its star is over it.
    const bool off_surface = mobility.kind == Mobility::kOffSurface;
    // A star that already holds a flat or inverted tet is left alone: no move is measured against
    // it, and its worst tet is unknown.
    if (!std::isfinite(q0.min_deg)) return false;
    StarQuality best = q0;
    auto better = [&](const StarQuality& a, const StarQuality& b) {
      if (!off_surface) return a.better_than(b);
      const double ma = std::min(a.min_deg, target_deg_), mb = std::min(b.min_deg, target_deg_);
      return ma > mb || (ma == mb && a.shortfall < b.shortfall);
    };
    double step = off_surface ? 0.25 * max_offset_[static_cast<std::size_t>(v)] : 0.25 * mean_edge(v);
    constexpr int kHalvings = 8, kMovesPerStep = 16;
    for (int level = 0; level < kHalvings; ++level, step *= 0.5) {
      for (int move = 0; move < kMovesPerStep; ++move) {
        // Directions: the axes and the outward normal of the face opposite v in the worst tet,
        // projected into v's plane when it has one.
        std::array<Eigen::Vector3d, 8> directions{Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitX(),
                                                  Eigen::Vector3d::UnitY(), -Eigen::Vector3d::UnitY(),
                                                  Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitZ(),
                                                  Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
        const auto& k = mesh_.tets[best.worst];
        std::array<Eigen::Vector3d, 3> face;
        int n = 0;
        for (int w : k)
          if (w != v && n < 3) face[static_cast<std::size_t>(n++)] = mesh_.points[static_cast<std::size_t>(w)];
        Eigen::Vector3d normal = (face[1] - face[0]).cross(face[2] - face[0]);
        if (normal.norm() > 0) {
          normal.normalize();
          if (normal.dot(p - face[0]) < 0) normal = -normal;
          directions[6] = normal;
          directions[7] = -normal;
        }
        if (mobility.kind != Mobility::kFree && mobility.kind != Mobility::kOffSurface)
          for (Eigen::Vector3d& d : directions) {
            d -= d.dot(mobility.normal) * mobility.normal;
            if (d.norm() < 1e-3) d.setZero();  // (nearly) along the normal: no move in the plane
            else d.normalize();
          }
        const Eigen::Vector3d here = p;
        Eigen::Vector3d best_point = here;
        for (const Eigen::Vector3d& d : directions) {
          if (d.isZero()) continue;
          p = here + step * d;
          if (mobility.kind == Mobility::kOnSurface &&
              (!onto_surface_(mobility.pair.first, mobility.pair.second, p) || (p - here).norm() > 2.0 * step))
            continue;
          if (mobility.kind == Mobility::kOffSurface &&
              (p - origin_[static_cast<std::size_t>(v)]).norm() > max_offset_[static_cast<std::size_t>(v)])
            continue;
          // A candidate with a tet under the best star's smallest angle (capped at the target off
          // the surface) loses whatever its other tets, so the best star's worst tet is tried
          // first and the rest of the star only while every tet stays at or over that angle.
          const double floor_deg = off_surface ? std::min(best.min_deg, target_deg_) : best.min_deg;
          const std::array<int, 4>& w = mesh_.tets[best.worst];
          const TetVolumeAndAngle at_worst = shape(mesh_, w);
          if (!(at_worst.volume_mm3 > 0) || at_worst.min_dihedral_deg < floor_deg) continue;
          const StarQuality q = star_quality(v, floor_deg);
          if (better(q, best)) {
            best = q;
            best_point = p;
          }
        }
        p = best_point;
        if (best_point == here) break;
      }
    }
    if (better(best, q0)) return true;
    p = start;
    return false;
  }

  /// How far v is from where it was when the smoother was made (0 without an offset bound).
  double offset(int v) const {
    return origin_.empty() ? 0.0 : (mesh_.points[static_cast<std::size_t>(v)] - origin_[static_cast<std::size_t>(v)]).norm();
  }

 private:
  TetMesh& mesh_;
  double target_deg_;
  const SurfaceProjector& onto_surface_;
  // With an offset bound only: the positions at the start and how far each node may leave them.
  std::vector<Eigen::Vector3d> origin_;
  std::vector<double> max_offset_;
  std::vector<std::size_t> star_start_;
  std::vector<std::size_t> star_;
};

}  // namespace

SliverSmoothingResult smooth_slivers(TetMesh& mesh, double target_deg, double near_planar_deg,
                                     const SurfaceProjector& onto_surface, int max_passes, double offset_edge_ratio) {
  SliverSmoothingResult r;
  std::vector<Mobility> mobile = mobility(mesh, near_planar_deg * M_PI / 180.0, bool(onto_surface));
  if (offset_edge_ratio > 0.0)
    for (Mobility& m : mobile)
      if (m.kind != Mobility::kFree) m.kind = Mobility::kOffSurface;
  auto movable = [&](int v) { return mobile[static_cast<std::size_t>(v)].kind != Mobility::kFixed; };
  Smoother smoother(mesh, target_deg, onto_surface, offset_edge_ratio);
  for (int pass = 0; pass < max_passes; ++pass) {
    // Every tet's smallest angle on two threads (each tet on its own), gathered in tet order.
    const auto n = static_cast<std::ptrdiff_t>(mesh.tets.size());
    std::vector<double> smallest(mesh.tets.size());
#pragma omp parallel for schedule(static) num_threads(2)
    for (std::ptrdiff_t t = 0; t < n; ++t)
      smallest[static_cast<std::size_t>(t)] = shape(mesh, mesh.tets[static_cast<std::size_t>(t)]).min_dihedral_deg;
    std::vector<std::pair<double, std::size_t>> bad;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
      if (smallest[t] < target_deg) bad.emplace_back(smallest[t], t);
    bool any_movable = false;
    for (const auto& [m, t] : bad)
      for (int v : mesh.tets[t]) any_movable = any_movable || movable(v);
    if (!any_movable) break;
    std::sort(bad.begin(), bad.end());
    ++r.passes;
    std::size_t moved = 0;
    for (const auto& [m0, t] : bad) {
      if (shape(mesh, mesh.tets[t]).min_dihedral_deg >= target_deg) continue;  // an earlier move fixed it
      for (int v : mesh.tets[t]) {
        const Mobility& m = mobile[static_cast<std::size_t>(v)];
        if (movable(v) && smoother.improve(v, m)) {
          ++moved;
          if (m.kind == Mobility::kOnSurface) ++r.moved_on_surface;
          if (m.kind == Mobility::kOffSurface) {
            ++r.moved_off_surface;
            r.max_offset_mm = std::max(r.max_offset_mm, smoother.offset(v));
          }
        }
      }
    }
    r.moved_vertices += moved;
    if (moved == 0) break;
  }
  return r;
}

}  // namespace tissuemesh
