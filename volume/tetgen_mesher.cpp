// Why -Y: without it TetGen flips and splits nearly coplanar boundary triangles and moves the
// surface by ~1e-6 of the volume, so the two meshes of a cross-check would not share their
// boundary. With it, a tet at the surface whose split point would land on the surface stays
// unsplit, hence the volume bound only inside. With -m a tet is split while its circumradius
// exceeds the value at any of its vertices. Every connected piece of a tissue's boundary (an
// island, a cavity's wall) gets a seed because TetGen silently drops a region without attribute;
// the seed lies halfway from the piece's largest triangle to the first other triangle hit by a
// ray into the tissue, so it is strictly inside whatever the tissue's thickness.
#include "volume/tetgen_mesher.h"

#include "volume/unseeded_cells.h"

#include "core/errors.h"
#include "core/isolated_run.h"
#include "core/union_find.h"

#define TETLIBRARY
#include <tetgen.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace tissuemesh {
namespace {

using Eigen::Vector3d;

/// Ray (origin o, direction d) against triangle abc (Moller-Trumbore): the ray parameter of the
/// hit, or +infinity.
double ray_hit(const Vector3d& o, const Vector3d& d, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d e1 = b - a, e2 = c - a, h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-300) return std::numeric_limits<double>::infinity();
  const Vector3d s = o - a;
  const double u = s.dot(h) / det;
  if (u < 0.0 || u > 1.0) return std::numeric_limits<double>::infinity();
  const Vector3d q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < 0.0 || u + v > 1.0) return std::numeric_limits<double>::infinity();
  const double t = e2.dot(q) / det;
  return t > 0.0 ? t : std::numeric_limits<double>::infinity();
}

/// The first triangle hit by the ray from `origin` along `direction`, skipping triangle `skip`:
/// the ray parameter, or +infinity.
double first_hit(const TriSurface& s, const Vector3d& origin, const Vector3d& direction, int skip) {
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t u = 0; u < s.triangles.size(); ++u) {
    if (static_cast<int>(u) == skip) continue;
    const auto& w = s.triangles[u];
    nearest = std::min(nearest, ray_hit(origin, direction, s.points[w[0]], s.points[w[1]], s.points[w[2]]));
  }
  return nearest;
}

/// Seed points strictly inside tissue `id`, one per connected piece of its boundary (a tissue in
/// several pieces, or with cavities, needs every piece seeded: TetGen drops unseeded regions), and
/// the mean edge of its boundary (for the default of TetgenParams::max_volume_mm3).
std::vector<Vector3d> seeds_inside(const TriSurface& s, int id, double& mean_edge) {
  std::vector<int> ids;
  std::vector<char> reversed;
  s.tissue_boundary(id, ids, reversed);
  if (ids.empty()) return {};  // a tissue absent from this surface: nothing to seed
  // Pieces: triangles joined through shared edges (union-find, smallest index as the root).
  std::vector<int> parent = singleton_sets(ids.size());
  auto root = [&](int k) { return find_root(parent, k); };
  std::vector<std::tuple<int, int, int>> edges;  // (min vertex, max vertex, entry)
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const auto& t = s.triangles[ids[k]];
    for (int e = 0; e < 3; ++e)
      edges.emplace_back(std::min(t[e], t[(e + 1) % 3]), std::max(t[e], t[(e + 1) % 3]), static_cast<int>(k));
  }
  std::sort(edges.begin(), edges.end());
  // Only manifold edges join: where pieces of a tissue touch along an edge (4 triangles), its two
  // sides may be different pieces of volume, and each must get its own seed.
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && std::get<0>(edges[j]) == std::get<0>(edges[i]) && std::get<1>(edges[j]) == std::get<1>(edges[i]))
      ++j;
    if (j - i == 2) {
      const int a = root(std::get<2>(edges[i])), b = root(std::get<2>(edges[i + 1]));
      parent[std::max(a, b)] = std::min(a, b);
    }
    i = j;
  }
  // Per piece: its largest triangle; the seed halfway to the next surface along the inward normal.
  std::vector<int> best(ids.size(), -1);
  std::vector<double> best_area(ids.size(), -1.0);
  double edge_sum = 0.0;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const auto& t = s.triangles[ids[k]];
    const Vector3d &a = s.points[t[0]], &b = s.points[t[1]], &c = s.points[t[2]];
    edge_sum += (b - a).norm() + (c - b).norm() + (a - c).norm();
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const int r = root(static_cast<int>(k));
    if (area > best_area[r]) {
      best_area[r] = area;
      best[r] = static_cast<int>(k);
    }
  }
  mean_edge = edge_sum / (3.0 * static_cast<double>(ids.size()));
  std::vector<Vector3d> seeds;
  for (std::size_t r = 0; r < ids.size(); ++r) {
    if (best[r] < 0) continue;
    const int k = best[r];
    const auto& t = s.triangles[ids[k]];
    const Vector3d &a = s.points[t[0]], &b = s.points[t[1]], &c = s.points[t[2]];
    // The stored normal points from p into q: into the tissue when the winding is reversed (q = id).
    Vector3d inward = (b - a).cross(c - a).normalized();
    if (!reversed[k]) inward = -inward;
    const Vector3d centroid = (a + b + c) / 3.0;
    const double hit = first_hit(s, centroid, inward, ids[k]);
    if (!std::isfinite(hit))
      throw MeshingError("tissue '" + s.tissue_names.at(id - 1) + "': no seed point found (its boundary is not closed)");
    seeds.push_back(centroid + 0.5 * hit * inward);
  }
  return seeds;
}

/// What the TetGen child sends back: nodes (x, y, z), tets (4 node indices) and each tet's
/// region attribute (the tissue id, 0 without one), as raw arrays behind their three sizes.
struct TetgenOutput {
  std::vector<double> points;
  std::vector<int> tets, ids;

  std::string serialise() const {
    const std::uint64_t sizes[3] = {points.size(), tets.size(), ids.size()};
    std::string b(reinterpret_cast<const char*>(sizes), sizeof sizes);
    b.append(reinterpret_cast<const char*>(points.data()), points.size() * sizeof(double));
    b.append(reinterpret_cast<const char*>(tets.data()), tets.size() * sizeof(int));
    b.append(reinterpret_cast<const char*>(ids.data()), ids.size() * sizeof(int));
    return b;
  }
  static TetgenOutput parse(const std::string& b) {
    TetgenOutput o;
    std::uint64_t sizes[3];
    if (b.size() < sizeof sizes) throw MeshingError("TetGen's result came back truncated");
    std::memcpy(sizes, b.data(), sizeof sizes);
    if (sizes[0] % 3 != 0 || sizes[1] != 4 * sizes[2] ||
        b.size() != sizeof sizes + sizes[0] * sizeof(double) + (sizes[1] + sizes[2]) * sizeof(int))
      throw MeshingError("TetGen's result came back malformed");
    o.points.resize(sizes[0]);
    o.tets.resize(sizes[1]);
    o.ids.resize(sizes[2]);
    const char* p = b.data() + sizeof sizes;
    std::memcpy(o.points.data(), p, sizes[0] * sizeof(double));
    p += sizes[0] * sizeof(double);
    std::memcpy(o.tets.data(), p, sizes[1] * sizeof(int));
    p += sizes[1] * sizeof(int);
    std::memcpy(o.ids.data(), p, sizes[2] * sizeof(int));
    return o;
  }
};

std::string tetgen_failure(int code) {
  switch (code) {
    case 1: return "out of memory";
    case 3: return "the input surface intersects itself";
    case 4: return "an input feature is too small for TetGen's tolerance";
    case 5: return "two input facets are too close to each other";
    case 10: return "TetGen rejected the input";
    default: return "internal error " + std::to_string(code);
  }
}

}  // namespace

TetgenResult tetgen_mesh(const TriSurface& surface, const TetgenParams& params, Progress& progress,
                         const std::vector<double>& point_radius_mm) {
  if (!(params.radius_edge_ratio > 1.0))
    throw InputError("tetgen.radius_edge_ratio must be > 1 (TetGen's -q bound), got " +
                     std::to_string(params.radius_edge_ratio));
  if (!(params.min_dihedral_deg >= 0.0 && params.min_dihedral_deg < 70.0))
    throw InputError("tetgen.min_dihedral_deg must be in [0, 70), got " + std::to_string(params.min_dihedral_deg));
  for (const auto& [name, v] : params.max_volume_mm3) {
    if (!(v > 0.0)) throw InputError("tetgen.max_volume_mm3." + name + " must be > 0 mm^3");
    bool known = false;
    for (const std::string& t : surface.tissue_names) known = known || t == name;
    if (!known) throw InputError("tetgen.max_volume_mm3 names unknown tissue '" + name + "'");
  }
  if (!point_radius_mm.empty()) {
    if (point_radius_mm.size() != surface.points.size())
      throw InputError("TetGen sizes: " + std::to_string(point_radius_mm.size()) + " values for " +
                       std::to_string(surface.points.size()) + " surface points");
    for (std::size_t v = 0; v < point_radius_mm.size(); ++v)
      if (!(point_radius_mm[v] >= 0.0 && std::isfinite(point_radius_mm[v])))
        throw InputError("TetGen sizes: the circumradius bound at surface point " + std::to_string(v) +
                         " is not a finite value >= 0 mm");
  }
  surface.validate("surface for TetGen");
  auto stage = progress.stage("TetGen volume mesh");

  tetgenio in;
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(surface.points.size());
  in.pointlist = new REAL[3 * surface.points.size()];
  for (std::size_t v = 0; v < surface.points.size(); ++v)
    for (int i = 0; i < 3; ++i) in.pointlist[3 * v + i] = surface.points[v][i];
  if (!point_radius_mm.empty()) {
    in.numberofpointmtrs = 1;
    in.pointmtrlist = new REAL[surface.points.size()];
    std::copy(point_radius_mm.begin(), point_radius_mm.end(), in.pointmtrlist);
  }
  in.numberoffacets = static_cast<int>(surface.triangles.size());
  in.facetlist = new tetgenio::facet[surface.triangles.size()];
  in.facetmarkerlist = new int[surface.triangles.size()];
  for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
    tetgenio::facet& f = in.facetlist[t];
    tetgenio::init(&f);
    f.numberofpolygons = 1;
    f.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&f.polygonlist[0]);
    f.polygonlist[0].numberofvertices = 3;
    f.polygonlist[0].vertexlist = new int[3];
    for (int i = 0; i < 3; ++i) f.polygonlist[0].vertexlist[i] = surface.triangles[t][i];
    in.facetmarkerlist[t] = 1000 * surface.labels[t][0] + surface.labels[t][1];
  }
  const int n_tissues = static_cast<int>(surface.tissue_names.size());
  std::vector<std::array<double, 5>> regions;  // seed x, y, z, tissue id, maximum volume
  for (int id = 1; id <= n_tissues; ++id) {
    double mean_edge = 0.0;
    const std::vector<Vector3d> seeds = seeds_inside(surface, id, mean_edge);
    const auto it = params.max_volume_mm3.find(surface.tissue_names[id - 1]);
    // The regular tetrahedron of edge e has volume e^3 / (6 sqrt 2); TetGen reads a bound <= 0 as none.
    const double max_volume = it != params.max_volume_mm3.end() ? it->second
                              : point_radius_mm.empty()           ? std::pow(mean_edge, 3) / (6.0 * std::sqrt(2.0))
                                                                : -1.0;
    for (const Vector3d& p : seeds) regions.push_back({p[0], p[1], p[2], static_cast<double>(id), max_volume});
  }
  in.numberofregions = static_cast<int>(regions.size());
  in.regionlist = new REAL[5 * regions.size()];
  for (std::size_t r = 0; r < regions.size(); ++r)
    for (int i = 0; i < 5; ++i) in.regionlist[5 * r + i] = regions[r][i];

  TetgenResult result;
  {
    char q[64];
    std::snprintf(q, sizeof q, "q%.6g/%.6g", params.radius_edge_ratio, params.min_dihedral_deg);
    result.switches = std::string(point_radius_mm.empty() ? "pzQAaY" : "pzQAamY") + q;
  }
  std::vector<char> switches(result.switches.begin(), result.switches.end());
  switches.push_back('\0');
  // In a child process: TetGen may fault while it unwinds from an input it cannot recover
  // (core/isolated_run.h). The child sends back the nodes, the tets and their tissue ids.
  const IsolatedRun run = run_isolated([&](std::string& bytes) {
    tetgenio out;
    try {
      tetrahedralize(switches.data(), &in, &out);
    } catch (int code) {
      throw std::runtime_error(tetgen_failure(code));
    }
    TetgenOutput o;
    o.points.assign(out.pointlist, out.pointlist + 3 * static_cast<std::size_t>(out.numberofpoints));
    o.tets.resize(4 * static_cast<std::size_t>(out.numberoftetrahedra));
    o.ids.resize(static_cast<std::size_t>(out.numberoftetrahedra), 0);
    for (int t = 0; t < out.numberoftetrahedra; ++t) {
      for (int i = 0; i < 4; ++i) o.tets[4 * t + i] = out.tetrahedronlist[out.numberofcorners * t + i];
      if (out.numberoftetrahedronattributes > 0)
        o.ids[t] = static_cast<int>(std::lround(out.tetrahedronattributelist[out.numberoftetrahedronattributes * t]));
    }
    bytes = o.serialise();
  });
  if (!run.ok)
    throw MeshingError("TetGen failed (-" + result.switches + "): " +
                       (run.crashed ? "it crashed (" + run.failure +
                                          ") on this surface; TetGen 1.5 can fault when it stops on nearly coplanar or "
                                          "nearly touching facets"
                                    : run.failure));
  const TetgenOutput out = TetgenOutput::parse(run.bytes);
  const int n_points = static_cast<int>(out.points.size() / 3), n_tets = static_cast<int>(out.ids.size());

  TetMesh& mesh = result.mesh;
  mesh.tissue_names = surface.tissue_names;
  mesh.points.resize(n_points);
  for (int v = 0; v < n_points; ++v) mesh.points[v] = Vector3d(out.points[3 * v], out.points[3 * v + 1], out.points[3 * v + 2]);
  std::vector<char> keep(n_tets, 1);
  mesh.tets.resize(n_tets);
  mesh.tissue_ids.resize(n_tets);
  for (int t = 0; t < n_tets; ++t) {
    std::array<int, 4> tet;
    for (int i = 0; i < 4; ++i) tet[i] = out.tets[4 * t + i];
    if (signed_tet_volume(mesh.points[tet[0]], mesh.points[tet[1]], mesh.points[tet[2]], mesh.points[tet[3]]) < 0.0)
      std::swap(tet[2], tet[3]);
    mesh.tets[t] = tet;
    mesh.tissue_ids[t] = out.ids[t];
  }
  result.unseeded = label_unseeded_cells(mesh.points, mesh.tets, surface, mesh.tissue_ids);
  for (int t = 0; t < n_tets; ++t) keep[t] = mesh.tissue_ids[t] >= 1 && mesh.tissue_ids[t] <= n_tissues;
  keep_tets(mesh, keep);
  std::vector<char> used(surface.points.size(), 0);
  for (const auto& tri : surface.triangles)
    for (int v : tri) used[v] = 1;
  std::size_t surface_vertices = 0;
  for (char u : used) surface_vertices += u;
  result.steiner_points = mesh.points.size() > surface_vertices ? mesh.points.size() - surface_vertices : 0;
  std::ostringstream note;
  note << mesh.tets.size() << " tets, " << mesh.points.size() << " nodes (-" << result.switches << ")";
  stage.note(note.str());
  return result;
}

}  // namespace tissuemesh
