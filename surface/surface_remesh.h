// Controlled-resolution remeshing of a multi-material TriSurface to a vertex budget (Alqaoud et
// al., "Multi-material, approach-guided, controlled-resolution breast meshing";
// docs/surface-pipeline.md, "2. Remeshing to a vertex budget").
//
// All patches (region pairs p|q) are remeshed at once by the local operations of
// surface/remesh_complex.h (split, collapse, flip, centroidal relaxation, with its shape and
// intersection guards) against a size field h(x) = L s(x); with a budget, L is rescaled from the
// measured count and a final pass makes the vertex count exactly the budget. Then a polish (flips,
// relaxation, angle-improving smoothing, removal and splits around triangles with an angle under
// 30 degrees), an optional repair around the triangles still under 30 degrees (kept only when
// improves_table1_minima, surface/surface_quality.h; while the smallest angle is under 26.5
// degrees, repeated on what a kept one left, at most RemeshOptions::repair_attempts attempts,
// each with the approximation bound 1.5 times looser near those triangles), and a last
// quality-raising smoothing when Q_min is under kQualitySmoothingBelow (it never lowers the
// smallest angle below min(its value, 30 degrees) nor adds angles under 30 degrees), and, when
// RemeshOptions::mean_quality_passes asks for it, a mean-quality smoothing that raises Q_av and
// the mean smallest angle under the same rules (Q_min kept at min(its value, 0.6)). Near
// junction edges that stay far shorter than h, h is capped (surface/graded_size_cap.h). An
// absolute bound from the local thickness (RemeshOptions::max_edge_mm) keeps thin sheets and
// tubes at edges that fit them; when those would take more than half the budget, all of them are
// scaled up by one factor (reported), or dropped when that factor would exceed 2.5 (they no
// longer fit the parts they are for). Progress:
// a note per round (vertices, L in mm), after the polish, after each repair attempt and after the
// quality smoothing.
// Validity: no operation makes two triangles intersect (an exact guard), so a valid input gives an
// intersection-free result at any budget; the result is checked again (surface/surface_checks.h)
// and the checks returned, the caller decides. Deterministic; the same result on one thread as on
// two (surface/remesh_partition.cpp).
#pragma once

#include "core/progress.h"
#include "core/tri_surface.h"
#include "surface/surface_checks.h"
#include "surface/surface_projection.h"

#include <Eigen/Core>

#include <cstddef>
#include <functional>

namespace tissuemesh {

/// Triangles with a Frey-Borouchaki quality under this get quality-raising moves as the last step
/// of remesh_surface (RemeshComplex::smooth_low_quality): the paper's Q_min at 2.1K vertices
/// (Alqaoud et al., Table 1), which an obtuse isosceles triangle reaches at an apex of about
/// 117.3 degrees.
constexpr double kQualitySmoothingBelow = 0.486;
/// The mean-quality smoothing (RemeshOptions::mean_quality_passes) moves the vertices of triangles
/// with a quality under this (an isosceles triangle with an apex of 46 or 70 degrees); the nearly
/// equilateral rest gain little.
constexpr double kMeanQualitySmoothingBelow = 0.9;
/// Nor does that smoothing take a triangle's quality below this (an isosceles apex of about 103
/// degrees), or below what it was when that was less: Q_min never drops.
constexpr double kMeanQualityFloor = 0.6;

struct RemeshOptions {
  int target_vertices = 0;      ///< total vertex budget (> 0), or 0 to use target_edge_mm
  double target_edge_mm = 0.0;  ///< edge length where s = 1 (used when target_vertices == 0)
  int iterations = 10;          ///< split/collapse/flip/relax rounds before the budget pass
  /// A collapse is refused when the removed vertex would lie farther than this from the new
  /// triangles (mm; 0 = no bound): small features keep their vertices whatever the size field says.
  double max_deviation_mm = 0.0;
  /// Relative size s(x) in (0, 1] (the density is 1 / s^2); empty = uniform.
  std::function<double(const Eigen::Vector3d&)> relative_size;
  /// An absolute bound on the size (mm, > 0; +infinity = none) that the budget's rescaling of L
  /// does not change: e.g. from the local thickness of the tissues (surface/thickness_size.h).
  std::function<double(const Eigen::Vector3d&)> max_edge_mm;
  /// Try the repair of triangles left under 30 degrees (header comment); false returns the
  /// polished result as is (what a discarded repair returns too).
  bool repair = true;
  /// Repair attempts at most (>= 1; header comment): the first with the approximation bound as
  /// it is, each later one 1.5 times looser near the poor triangles.
  int repair_attempts = 4;
  /// Refuse every operation that would fold two triangles of one patch flat against each other
  /// (RemeshComplex::kFoldCos) further than their neighbourhood already was: a volume mesher that
  /// keeps the surface (TetGen -Y) must fill the wedge between them with tets at least as flat.
  bool fold_guard = false;
  /// Passes of the mean-quality smoothing (RemeshComplex::smooth_mean_quality), last of all, over
  /// the vertices of triangles with a quality under kMeanQualitySmoothingBelow: they raise Q_av
  /// and the mean smallest angle of Table 1 and never lower Q_min, the smallest angle (below 30
  /// degrees) nor add angles under 30 degrees. They move vertices within the approximation bound,
  /// away from where the input is most curved, so the surface may end farther from the input (its
  /// Hausdorff distance grows). 0 = none. Each pass visits most vertices.
  int mean_quality_passes = 0;
  /// Threads of the partitioned sweeps (surface/remesh_complex.h): 2, or 1 to run the two halves
  /// one after the other. The result is the same either way.
  int threads = 2;
};

struct RemeshResult {
  TriSurface surface;
  SurfaceCheckReport checks;    ///< surface/surface_checks.h of `surface`
  double edge_length_mm = 0.0;  ///< L, the size where s = 1, after the budget rescaling
  /// Factor (>= 1) the thin parts' size bounds were scaled by to fit the budget (1: as asked; 0:
  /// dropped, the budget cannot resolve them: more than 2.5 would have been needed).
  double thickness_scale = 1.0;
  std::size_t splits = 0, collapses = 0, flips = 0;
  std::size_t angle_moves = 0;  ///< vertex moves of the angle-improving smoothing (a kept repair's included)
  std::size_t quality_moves = 0;  ///< vertex moves of the final quality-raising smoothing
  std::size_t mean_quality_moves = 0;  ///< vertex moves of the mean-quality smoothing
  std::size_t partitioned_sweeps = 0;  ///< collapse and relaxation sweeps run as two halves (the others: none was large enough)
};

/// `input` must be valid and closed per tissue (surface/surface_checks.h), `projection` built on it.
/// Throws InputError when options give neither a budget nor an edge length, and InputError naming
/// surface.target_vertices, with the smallest count it can offer, when the budget cannot be met:
/// below what the corners, closed junction curves and closed islands need (before any work), the
/// count still above twice the budget after the second round (folds or sheets thinner than the
/// edge length refuse the collapses), or the final budget pass stopped short; MeshingError when
/// the remeshed complex is broken (a junction curve lost).
RemeshResult remesh_surface(const TriSurface& input, const SurfaceProjection& projection, const RemeshOptions& options,
                            Progress& progress);

}  // namespace tissuemesh
