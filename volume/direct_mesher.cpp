// The one CGAL-heavy translation unit of the direct pipeline (keeps builds short).
//
// Why: CGAL interpolates labels between voxel centres, so a tissue that touches the image border
// ends at the border voxels' centres, in sharp creases and triple lines that need protecting (see
// the border features below). CGAL's random initialisation misses small parts, so every image
// component is seeded explicitly (seed_components). Seeding every component of a fragmented map
// is what made it slow: thousands of islands of a few voxels, each with dozens of seeds, each
// refined to the criteria. So components too small to be meshed faithfully are absorbed first,
// and the seeds per component follow its volume.
#include "volume/direct_mesher.h"

#include "core/errors.h"
#include "core/face_key.h"
#include "core/number_format.h"
#include "image/label_components.h"
#include "image/local_thickness.h"
#include "volume/budget_refinement.h"
#include "volume/component_volume_fit.h"
#include "volume/image_sizing.h"
#include "volume/label_weights.h"
#include "volume/mesh3_steps.h"
#include "quality/conformity.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Image_3.h>
#include <CGAL/ImageIO.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_domain_with_polyline_features_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Mesh_3/polylines_to_protect.h>
#include <CGAL/make_mesh_3.h>
#include <CGAL/version.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <set>
#include <sstream>

namespace tissuemesh {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Image_domain = CGAL::Labeled_mesh_domain_3<K>;
// Polyline features: where tissue boundaries meet the image border (see seed/protect below).
using Domain = CGAL::Mesh_domain_with_polyline_features_3<Image_domain>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;
using Point = K::Point_3;

// Image in CGAL's frame: axis-aligned, voxel (i,j,k) at (i*vx, j*vy, k*vz).
// CGAL's labelled interpolation ignores the image translation, so the translation stays zero and
// the physical placement (origin, direction) is applied when the mesh is extracted.
CGAL::Image_3 make_cgal_image(const std::vector<std::uint8_t>& voxels, const std::array<int, 3>& dims,
                              const Eigen::Vector3d& spacing) {
  _image* im = _createImage(dims[0], dims[1], dims[2], 1, spacing[0], spacing[1], spacing[2], 1,
                            WK_FIXED, SGN_UNSIGNED);
  if (im == nullptr) throw MeshingError("cannot allocate the CGAL image");
  std::memcpy(im->data, voxels.data(), voxels.size());
  return CGAL::Image_3(im);
}

// Tissue ids as bytes (CGAL::Image_3 word type); ids were checked to be <= 255.
std::vector<std::uint8_t> id_bytes(const LabelImage& ids) {
  return std::vector<std::uint8_t>(ids.labels.begin(), ids.labels.end());
}

// Size field (mm): the base size (per tissue for cells) shrinks linearly to `refine_size` at the
// refined tissue, approximated by a ball (centroid, radius of its farthest voxel) — exact enough
// for a compact tumour and cheap enough to evaluate millions of times.
struct SizeField {
  typedef K::FT FT;
  typedef K::Point_3 Point_3;
  typedef Domain::Index Index;

  double base = 1.0;
  std::vector<double> per_tissue;  // index = tissue id; 0 = unused
  bool refine = false;
  Point_3 centre{0, 0, 0};
  double ball_radius = 0.0, refine_size = 1.0, refine_radius = 1.0;

  FT operator()(const Point_3& p, const int dim, const Index& index) const {
    int tissue = 0;
    if (dim == 3)
      if (const auto* sub = boost::get<Domain::Subdomain_index>(&index)) tissue = *sub;
    return at(p, tissue);
  }

  /// The size at `p` in `tissue` (0: on a boundary, the base size).
  double at(const Point_3& p, int tissue) const {
    double size = base;
    if (tissue > 0 && static_cast<std::size_t>(tissue) < per_tissue.size()) size = per_tissue[tissue];
    if (refine) {
      const double d = std::max(0.0, std::sqrt(CGAL::squared_distance(p, centre)) - ball_radius);
      size = std::min(size, refine_size + (size - refine_size) * std::min(1.0, d / refine_radius));
    }
    return size;
  }
};

// The edge field of ImageSizing as a CGAL size: `factor` converts an edge length to the radius CGAL
// bounds (0.577 for a facet's Delaunay ball, 0.612 for a tet's circumsphere: the equilateral
// triangle and the regular tet of that edge), capped by the fixed field.
struct GridSizeField {
  typedef K::FT FT;
  typedef K::Point_3 Point_3;
  typedef Domain::Index Index;

  const ImageSizing* sizing = nullptr;
  double factor = 0.612;
  const SizeField* fixed = nullptr;

  FT operator()(const Point_3& p, const int dim, const Index& index) const {
    return std::min(factor * sizing->edge_at(p.x(), p.y(), p.z()), (*fixed)(p, dim, index));
  }
};

// The island volume fit scales a component by at most this factor, and never leaves a tet it moves
// below this dihedral angle (or below its angle before, if that was smaller).
constexpr double kIslandMaxScale = 1.25;
constexpr double kIslandMinDihedralDeg = 10.0;
// The volume restoration moves a node by at most this many of the largest voxel spacing in all:
// the labels fix a boundary only to within a voxel, and a tissue thinner than its elements (a
// vessel one element across) cannot get its volume back by offsets; larger moves there would
// only make spikes.
constexpr double kRestorationMaxMoveOfVoxel = 1.0;

// Edge / radius conversions of GridSizeField.
constexpr double kFacetRadiusPerEdge = 0.5773502691896258;  // 1 / sqrt(3)
constexpr double kCellRadiusPerEdge = 0.6123724356957945;   // sqrt(6) / 4

Point voxel_point(const std::array<int, 3>& ijk, const Eigen::Vector3d& spacing) {
  return Point(ijk[0] * spacing[0], ijk[1] * spacing[1], ijk[2] * spacing[2]);
}

// True if `p` lies in the protecting ball of a feature vertex (weighted point): inserting it
// there would hide the ball and break the protection.
bool inside_protecting_ball(const Tr& tr, const Point& p) {
  if (tr.dimension() < 3) {
    for (auto v = tr.finite_vertices_begin(); v != tr.finite_vertices_end(); ++v) {
      const auto& wp = tr.point(v);
      if (wp.weight() > 0 && CGAL::squared_distance(p, wp.point()) <= wp.weight()) return true;
    }
    return false;
  }
  // As CGAL's Triangulation_helpers::inside_protecting_balls: the nearest vertex in the power
  // metric is the only ball that can contain p.
  const Tr::Vertex_handle v = tr.nearest_power_vertex(p);
  if (v == Tr::Vertex_handle() || tr.is_infinite(v)) return false;
  const auto& wp = tr.point(v);
  return wp.weight() > 0 && CGAL::squared_distance(p, wp.point()) <= wp.weight();
}

// Start voxels per component: one per cube of side facet_size_mm in its volume, at least one and
// at most kMaxStarts. One start finds a component; refinement then grows its surface from the
// points found. More starts on a large component spread its first surface points (CGAL's own
// initialisation shoots ~20 rays), but a small one seeded from many voxels gets dozens of points
// closer together than the facet size, all of which refinement must then grade away from.
constexpr std::size_t kMaxStarts = 9;

std::size_t start_count(const LabelComponent& c, double voxel_mm3, double facet_size_mm) {
  const double cubes = static_cast<double>(c.voxels) * voxel_mm3 / (facet_size_mm * facet_size_mm * facet_size_mm);
  return std::clamp<std::size_t>(static_cast<std::size_t>(std::ceil(cubes)), 1, kMaxStarts);
}

// Seeds surface points on every component (see header): from a voxel of the component walk along
// each axis to the first voxel of another id; the segment between the two voxel centres crosses
// the boundary, which CGAL's intersection oracle locates.
std::size_t seed_components(C3t3& c3t3, const Domain& domain, const LabelImage& ids,
                            const ComponentMap& comps, double facet_size_mm) {
  Tr& tr = c3t3.triangulation();
  auto construct_intersection = domain.construct_intersection_object();
  const Eigen::Vector3d& spacing = ids.spacing;
  // The component's first boundary voxel, then every stride-th voxel in scan order.
  std::vector<std::vector<std::array<int, 3>>> starts(comps.components.size());
  std::vector<std::size_t> seen(comps.components.size(), 0), wanted(comps.components.size(), 1);
  for (std::size_t c = 0; c < comps.components.size(); ++c) {
    starts[c].push_back(comps.components[c].seed);
    wanted[c] = start_count(comps.components[c], ids.voxel_volume(), facet_size_mm);
  }
  for (int k = 0; k < ids.dims[2]; ++k)
    for (int j = 0; j < ids.dims[1]; ++j)
      for (int i = 0; i < ids.dims[0]; ++i) {
        const std::int32_t c = comps.component_of_voxel[ids.index(i, j, k)];
        if (c < 0 || wanted[c] < 2) continue;
        const std::size_t stride = std::max<std::size_t>(1, comps.components[c].voxels / (wanted[c] - 1));
        if (++seen[c] % stride == 0 && starts[c].size() < wanted[c]) starts[c].push_back({i, j, k});
      }
  const int steps[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::size_t inserted = 0;
  // Each boundary crossing is used once: starts on the same voxel line reach the same crossing,
  // and two seeds a round-off apart would make near-flat tets that no optimiser removes.
  std::set<std::pair<std::size_t, int>> used;
  for (std::size_t c = 0; c < comps.components.size(); ++c) {
    const int id = comps.components[c].tissue_id;
    for (const auto& a : starts[c]) {
      for (int dir = 0; dir < 6; ++dir) {
        const int* st = steps[dir];
        std::array<int, 3> last = a, b = a;
        bool crossing = false;
        while (true) {
          b = {b[0] + st[0], b[1] + st[1], b[2] + st[2]};
          if (b[0] < 0 || b[1] < 0 || b[2] < 0 || b[0] >= ids.dims[0] || b[1] >= ids.dims[1] ||
              b[2] >= ids.dims[2])
            break;  // the component reaches the image border this way: no crossing to seed
          if (ids.at(b[0], b[1], b[2]) != id) {
            crossing = true;
            break;
          }
          last = b;
        }
        if (!crossing || !used.emplace(ids.index(last[0], last[1], last[2]), dir).second) continue;
        // One voxel step: the labels differ at its two ends, so the oracle's bisection finds
        // exactly this crossing.
        const auto hit = construct_intersection(K::Segment_3(voxel_point(last, spacing), voxel_point(b, spacing)));
        if (std::get<2>(hit) == 0) continue;
        if (inside_protecting_ball(tr, std::get<0>(hit))) continue;
        const Tr::Vertex_handle v = tr.insert(Tr::Weighted_point(std::get<0>(hit)));
        if (v == Tr::Vertex_handle()) continue;
        c3t3.set_dimension(v, 2);
        c3t3.set_index(v, std::get<1>(hit));
        ++inserted;
      }
    }
  }
  return inserted;
}

// Moves x (CGAL frame, mm) onto the labelled interface between tissues p and q near it, as the
// sliver smoothing asks (volume/sliver_smoothing.h): along the 26 directions of a voxel stencil,
// within 1.5 voxels, the segments from x whose far end has the other tissue are cut by the same
// intersection oracle that placed the mesh's surface vertices; the nearest cut wins. False when x
// is in neither tissue or no such interface is that close.
bool onto_label_interface(const Domain& domain, const Eigen::Vector3d& spacing, int p, int q, Point& x) {
  const auto label = [&](const Point& y) {
    const auto in = domain.is_in_domain_object()(y);
    return in ? static_cast<int>(*in) : 0;
  };
  const int here = label(x);
  if (here != p && here != q) return false;
  const int other = here == p ? q : p;
  const double reach = 1.5 * spacing.maxCoeff();
  auto construct_intersection = domain.construct_intersection_object();
  double best = 1e300;
  Point found = x;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0 && dz == 0) continue;
        const double len = std::sqrt(static_cast<double>(dx * dx + dy * dy + dz * dz));
        const Point end(x.x() + reach * dx / len, x.y() + reach * dy / len, x.z() + reach * dz / len);
        if (label(end) != other) continue;
        const auto hit = construct_intersection(K::Segment_3(x, end));
        if (std::get<2>(hit) == 0) continue;
        const auto* patch = boost::get<Domain::Surface_patch_index>(&std::get<1>(hit));
        if (patch == nullptr || std::minmax(patch->first, patch->second) != std::minmax(p, q)) continue;
        const double d = CGAL::squared_distance(x, std::get<0>(hit));
        if (d < best) {
          best = d;
          found = std::get<0>(hit);
        }
      }
  if (best == 1e300) return false;
  x = found;
  return true;
}

// Each tissue's voxel volume, mm^3.
std::map<int, double> voxel_volumes(const LabelImage& ids) {
  std::map<int, double> volume;
  for (const std::int32_t id : ids.labels)
    if (id > 0) volume[id] += 1.0;
  for (auto& [id, v] : volume) v *= ids.voxel_volume();
  return volume;
}

}  // namespace

std::string cgal_version() { return CGAL_STR(CGAL_VERSION); }

DirectMeshResult mesh_labels_direct(const LabelImage& input, const std::vector<std::string>& names,
                                    const DirectMeshParams& params, Progress& progress) {
  if (names.size() > 255) throw InputError("at most 255 tissues can be meshed");
  auto tissue_id = [&](const std::string& name, const std::string& key) {
    for (std::size_t t = 0; t < names.size(); ++t)
      if (names[t] == name) return static_cast<int>(t) + 1;
    throw InputError("direct." + key + ": '" + name + "' is not a tissue of the tissue table");
  };

  DirectMeshResult result;
  // The image meshed: the input, or a copy without the components below the threshold.
  LabelImage absorbed;
  const std::size_t below_voxels = params.absorb_below_voxels(input.voxel_volume());
  const bool absorb = below_voxels > 1;
  const LabelImage& ids = absorb ? absorbed : input;
  ComponentMap comps;
  std::vector<std::uint8_t> bytes;
  std::vector<std::uint8_t> weights;
  {
    auto stage = progress.stage("prepare image");
    comps = find_components(input);
    result.image_components = comps.components.size();
    if (absorb) {
      absorbed = input;
      result.absorbed = absorb_small_islands(absorbed, below_voxels);
      if (result.absorbed.voxels > 0) comps = find_components(absorbed);
    }
    result.meshed_components = comps.components.size();
    bytes = id_bytes(ids);
    if (params.smooth_boundaries) {
      const double sigma = params.smoothing_sigma_mm > 0 ? params.smoothing_sigma_mm : 0.5 * ids.spacing.maxCoeff();
      weights = label_weights(ids, sigma);
    }
    std::ostringstream note;
    note << result.image_components << " tissue components in " << ids.voxel_count() << " voxels";
    if (absorb)
      note << "; " << result.absorbed.islands << " under " << below_voxels << " voxels ("
           << result.absorbed.voxels << " voxels) joined their surroundings, " << comps.components.size() << " left";
    stage.note(note.str());
  }

  CGAL::Image_3 image = make_cgal_image(bytes, ids.dims, ids.spacing);
  CGAL::Image_3 weight_image;
  if (!weights.empty()) weight_image = make_cgal_image(weights, ids.dims, ids.spacing);
  namespace p = CGAL::parameters;
  // relative_error_bound: the boundary search stops at 1e-6 of the image diagonal (CGAL's weighted
  // image example), far below a voxel; the default 1e-3 would be ~0.3 mm here.
  auto domain_stage = std::make_unique<Progress::Stage>(progress, "domain and border features");
  Domain domain = weights.empty()
                      ? Domain::create_labeled_image_mesh_domain(image, p::relative_error_bound = 1e-6)
                      : Domain::create_labeled_image_mesh_domain(image, p::weights = weight_image,
                                                                 p::relative_error_bound = 1e-6);
  {
    // Where tissue boundaries meet the image border they form sharp creases and triple lines;
    // unprotected, Delaunay refinement clusters thousands of near-flat tets there. CGAL 5.5
    // computes these polylines on the image's bounding box; protecting balls keep them sharp.
    std::vector<std::vector<Point>> polylines;
    const std::vector<std::vector<Point>> none;
    CGAL::polylines_to_protect<Point, std::uint8_t>(image, polylines, none.begin(), none.end());
    domain.add_features(polylines.begin(), polylines.end());
    domain_stage->note(std::to_string(polylines.size()) + " polylines protected on the image border");
  }
  domain_stage.reset();

  // With a budget the base sizes are the budget's to choose, up to a quarter of the size of the
  // body (a cube of the tissues' volume): the fixed facet and cell sizes would put a floor under
  // the count that a small budget cannot go below.
  double budget_max_edge = 0.0, tissue_mm3 = 0.0;
  if (params.target_tets > 0) {
    std::size_t tissue_voxels = 0;
    for (std::int32_t v : ids.labels) tissue_voxels += v != 0;
    tissue_mm3 = static_cast<double>(tissue_voxels) * ids.voxel_volume();
    budget_max_edge = 0.25 * std::cbrt(tissue_mm3);
  }
  SizeField facet_field, cell_field;
  facet_field.base = params.target_tets > 0 ? kFacetRadiusPerEdge * budget_max_edge : params.facet_size_mm;
  cell_field.base = params.target_tets > 0 ? kCellRadiusPerEdge * budget_max_edge : params.cell_size_mm;
  cell_field.per_tissue.assign(names.size() + 1, cell_field.base);
  for (const auto& [name, size] : params.cell_size_per_tissue_mm)
    cell_field.per_tissue[tissue_id(name, "cell_size_per_tissue_mm")] = size;
  if (!params.refine_tissue.empty()) {
    const int rid = tissue_id(params.refine_tissue, "refine_tissue");
    Eigen::Vector3d lo(1e300, 1e300, 1e300), hi(-1e300, -1e300, -1e300), sum(0, 0, 0);
    std::size_t n = 0;
    std::vector<Eigen::Vector3d> pts;
    for (int k = 0; k < ids.dims[2]; ++k)
      for (int j = 0; j < ids.dims[1]; ++j)
        for (int i = 0; i < ids.dims[0]; ++i)
          if (ids.at(i, j, k) == rid) {
            const Eigen::Vector3d q(i * ids.spacing[0], j * ids.spacing[1], k * ids.spacing[2]);
            pts.push_back(q);
            sum += q;
            ++n;
          }
    if (n > 0) {
      const Eigen::Vector3d c = sum / static_cast<double>(n);
      double r = 0.0;
      for (const auto& q : pts) r = std::max(r, (q - c).norm());
      for (SizeField* f : {&facet_field, &cell_field}) {
        f->refine = true;
        f->centre = Point(c[0], c[1], c[2]);
        f->ball_radius = r;
        f->refine_size = params.refine_size_mm;
        f->refine_radius = params.refine_radius_mm;
      }
    }
  }
  // Thin tissue and small components need a boundary tolerance below the voxel size; a coarser
  // one loses their volume (named per tissue by the volume checks, but the cause is here).
  if (params.target_tets == 0 && params.facet_distance_mm > ids.spacing.minCoeff()) {
    std::ostringstream w;
    w << "direct.facet_distance_mm (" << params.facet_distance_mm << " mm) is larger than the smallest voxel spacing ("
      << ids.spacing.minCoeff() << " mm): thin tissue and small components lose volume; about half a voxel "
      << "resolves them";
    result.warnings.push_back(w.str());
  }

  C3t3 c3t3;
  auto build = [&](const auto& criteria) {
    c3t3.clear();
    {
      auto stage = progress.stage("protect border features");
      CGAL::Mesh_3::internal::init_c3t3_with_features(c3t3, domain, criteria);
      stage.note(std::to_string(c3t3.triangulation().number_of_vertices()) + " protecting balls");
    }
    {
      auto stage = progress.stage("seed components");
      result.initial_points = seed_components(c3t3, domain, ids, comps, params.facet_size_mm);
      stage.note(std::to_string(result.initial_points) + " initial surface points");
    }
    mesh3::refine(c3t3, domain, criteria, progress);
  };

  if (params.target_tets == 0) {
    build(Criteria(p::edge_size = facet_field, p::facet_angle = params.facet_angle_deg, p::facet_size = facet_field,
                   p::facet_distance = params.facet_distance_mm,
                   p::cell_radius_edge_ratio = params.cell_radius_edge_ratio, p::cell_size = cell_field));
  } else {
    ImageSizingParams sp;
    sp.target_tets = params.target_tets;
    sp.thickness_edge_ratio = params.thickness_edge_ratio;
    sp.growth = params.size_growth;
    sp.min_edge_mm = params.min_edge_mm > 0 ? params.min_edge_mm : ids.spacing.minCoeff();
    sp.max_edge_mm = std::max(sp.min_edge_mm, budget_max_edge);
    SizeField distance_cap;  // no cap: the distance follows the edge
    distance_cap.base = budget_max_edge;
    std::vector<float> thickness;
    {
      auto stage = progress.stage("local thickness");
      // Thickness matters only where it asks for edges below what the budget can spend: up to three
      // times the edge of a uniform mesh of the budget (the painted balls then stay small).
      const double uniform_edge =
          std::cbrt(tissue_mm3 / (sp.tet_volume_factor * static_cast<double>(params.target_tets)));
      thickness = local_thickness(ids, std::min(sp.max_edge_mm, 3.0 * uniform_edge) / sp.thickness_edge_ratio);
    }
    auto cap = [&](int i, int j, int k) {
      const Point q = voxel_point({i, j, k}, ids.spacing);
      return cell_field.at(q, ids.at(i, j, k)) / kCellRadiusPerEdge;
    };
    result.sizing = refine_to_budget(
        sp, comps.components.size(),
        [&](const ImageSizingParams& round) {
          auto stage = progress.stage("sizes from the image");
          ImageSizing z = size_from_image(ids, thickness, cap, names, round);
          std::ostringstream note;
          note << "edges " << z.min_edge_mm << " to " << z.global_edge_mm << " mm for about "
               << std::lround(z.predicted_tets) << " tets";
          if (z.thickness_scale > 1.0) note << "; thin parts coarsened x" << z.thickness_scale;
          stage.note(note.str());
          return z;
        },
        [&](const ImageSizing& z) {  // z outlives the refinement, which is all the fields need
          GridSizeField facet_grid{&z, kFacetRadiusPerEdge, &facet_field};
          GridSizeField cell_grid{&z, kCellRadiusPerEdge, &cell_field};
          GridSizeField edge_grid{&z, 1.0, &facet_field};
          GridSizeField distance_grid{&z, params.facet_distance_ratio, &distance_cap};
          build(Criteria(p::edge_size = edge_grid, p::facet_angle = params.facet_angle_deg, p::facet_size = facet_grid,
                         p::facet_distance = distance_grid,
                         p::cell_radius_edge_ratio = params.cell_radius_edge_ratio, p::cell_size = cell_grid));
          return static_cast<std::size_t>(c3t3.number_of_cells_in_complex());
        });
  }
  mesh3::optimise(c3t3, domain, params.optimise, progress, result.warnings);

  auto stage = progress.stage("extract mesh");
  const Eigen::Matrix3d& D = ids.direction;
  result.mesh = mesh3::cells(
      c3t3, [&](double x, double y, double z) -> Eigen::Vector3d { return ids.origin + D * Eigen::Vector3d(x, y, z); },
      D.determinant() < 0, names);
  TetMesh& mesh = result.mesh;
  // The sliver smoothing may slide vertices of curved interfaces and boundaries over the labelled
  // image's own interfaces (physical LPS <-> CGAL frame: x = origin + D c, c = D^T (x - origin)).
  const SurfaceProjector onto_labels = [&](int p, int q, Eigen::Vector3d& x) {
    const Eigen::Vector3d c = D.transpose() * (x - ids.origin);
    Point y(c[0], c[1], c[2]);
    if (!onto_label_interface(domain, ids.spacing, p, q, y)) return false;
    x = ids.origin + D * Eigen::Vector3d(y.x(), y.y(), y.z());
    return true;
  };
  result.repair = repair_slivers(mesh, params.optimise, result.warnings, onto_labels);

  // Which image components are covered by tets of their tissue? A tet credits the component of
  // the voxel under its centroid or, when that voxel has another tissue (the mesh boundary is
  // smooth, the voxels are not), the nearest voxel of its own tissue among the 26 neighbours.
  // The rest is reported by name, size and place.
  std::vector<char> covered(comps.components.size(), 0);
  std::vector<std::int32_t> tet_component(mesh.tets.size(), -1);
  const Eigen::Matrix3d to_index = ids.index_to_physical().inverse();
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int v : mesh.tets[t]) centroid += mesh.points[v] / 4.0;
    const Eigen::Vector3d ijk = to_index * (centroid - ids.origin);
    const int ci = static_cast<int>(std::lround(ijk[0])), cj = static_cast<int>(std::lround(ijk[1])),
              ck = static_cast<int>(std::lround(ijk[2]));
    double best = 1e300;
    std::int32_t best_comp = -1;
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int i = ci + di, j = cj + dj, k = ck + dk;
          if (i < 0 || j < 0 || k < 0 || i >= ids.dims[0] || j >= ids.dims[1] || k >= ids.dims[2]) continue;
          if (ids.at(i, j, k) != mesh.tissue_ids[t]) continue;
          const double d = (Eigen::Vector3d(i, j, k) - ijk).squaredNorm();
          if (d < best) {
            best = d;
            best_comp = comps.component_of_voxel[ids.index(i, j, k)];
          }
        }
    if (best_comp >= 0) covered[best_comp] = 1;
    tet_component[t] = best_comp;
  }
  if (params.fit_island_volumes_below_mm3 > 0) {
    std::vector<ComponentTarget> targets(comps.components.size());
    for (std::size_t c = 0; c < targets.size(); ++c)
      targets[c] = {comps.components[c].tissue_id, static_cast<double>(comps.components[c].voxels) * ids.voxel_volume()};
    result.island_fit = fit_component_volumes(mesh, tet_component, targets, params.fit_island_volumes_below_mm3,
                                              kIslandMaxScale, kIslandMinDihedralDeg);
  }
  std::map<int, double> missed_mm3;  // by tissue id
  for (std::size_t c = 0; c < comps.components.size(); ++c) {
    if (covered[c]) continue;
    const auto& cc = comps.components[c];
    result.missed.push_back({names[cc.tissue_id - 1], cc.voxels, cc.voxels * ids.voxel_volume(), cc.centroid_mm});
    missed_mm3[cc.tissue_id] += cc.voxels * ids.voxel_volume();
  }
  stage.note(std::to_string(mesh.tets.size()) + " tets, " + std::to_string(mesh.points.size()) + " nodes");
  // Last, so that no later step undoes it: the repairs' flips across interfaces and the smoothing's
  // projections onto the image's interfaces would move the restored boundary back.
  if (params.restore_volumes) {
    if (check_conformity(mesh).conforming()) {
      auto restore = progress.stage("tet volume restoration");
      // Tissues with tets; one without is reported as not meshed. A component left unmeshed is
      // reported too, and kept out of its tissue's target so that the rest does not grow into it.
      std::map<int, double> target;
      for (const auto& [id, v] : voxel_volumes(ids))
        if (std::find(mesh.tissue_ids.begin(), mesh.tissue_ids.end(), id) != mesh.tissue_ids.end())
          target[id] = v - missed_mm3[id];
      result.restoration = restore_tet_volumes(mesh, target, kRestorationMaxMoveOfVoxel * ids.spacing.maxCoeff());
      restore.note(std::to_string(result.restoration->offsets.rounds) + " rounds, " +
                   std::to_string(result.restoration->nodes_moved) + " nodes moved by at most " +
                   format_double("%.3f", result.restoration->max_offset_mm) + " mm");
    } else {
      result.warnings.push_back("volume restoration skipped: the mesh does not conform (see the conformity counts)");
    }
  }
  return result;
}

}  // namespace tissuemesh
