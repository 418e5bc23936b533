// Volume restoration of a remeshed multi-material surface: small normal offsets of its patches so
// that every tissue encloses its reference volume (e.g. its voxel volume) again.
//
// Remeshing to a vertex budget cuts the convex side of curved sheets and shaves thin parts, so a
// tissue loses volume, a few per cent for a thin one. With a volume mesher that keeps the
// surface (volume/surface_tetgen.h) that loss goes straight into the tet mesh. Each patch k (the
// triangles between regions p < q, area A_k) moves by a distance d_k along its normal (from p into
// q): tissue p gains A_k d_k, tissue q loses it (outside, region 0, is free). The d_k are the
// least-norm solution, weighted by area (minimise sum A_k d_k^2), of "every tissue's volume change
// equals its deficit", so that a tissue's deficit is shared by all its patches and every interface
// moves once, consistently for both its sides. Vertices move along their area-weighted normal in
// the patch, weighted: 0 on junction curves (they belong to several patches), 1/3 and 2/3 on the
// next two rings, less where the patch bends at the vertex by more than 10 degrees (none beyond
// 60: the rim of a thin sheet, where diverging normals would stretch the triangles; beyond 80 on a
// component of the surface that touches no junction, a closed island such as a marker clip, which
// inflates like a ball however few vertices it has), and 0 at the triangles within 2 degrees of
// the surface's smallest angle. The areas in the solve carry the
// same weights; the volumes are then measured and the offsets solved again, a few rounds.
//
// Where a round would turn a triangle's normal by more than 60 degrees, take a triangle's angle
// below the surface's smallest, or make the surface invalid or self-intersecting
// (surface_checks.h), the vertices of those triangles and their neighbours stop moving for good
// and the offsets are solved again (up to 8 times a round): on a fragmented or folded surface a
// few tight spots then no longer hold every patch back. A round still failing is retried at half
// its offsets, three times, then undone, and the rounds stop; so is a round that does not lower
// the sum of the tissues' relative errors or raises one of them by more than 0.1 % (plus 5 % of
// that sum). A vertex's move in a round is clipped at its shortest edge (no spikes where few
// vertices of a patch may move); the next round measures the volumes again and goes on from
// there; a vertex's moves over all rounds add up to at most `max_total_move_mm`. A tissue at least
// 1 % off that a round (undone) brought less than a tenth of the way, such as a vessel one element
// across whose moves are clipped, is released: it stops constraining the offsets, its vertices
// move no more from then on, and the round is solved again for the others (never the last
// constrained tissue). The surface stays valid and keeps its Table 1 minimum angle. Units mm, mm^3.
// Deterministic.
#pragma once

#include "core/tri_surface.h"

#include <functional>
#include <limits>
#include <map>
#include <vector>

namespace tissuemesh {

struct VolumeRestoration {
  int rounds = 0;                           ///< offset rounds kept
  double max_offset_mm = 0.0;               ///< largest vertex move over all rounds kept
  std::map<int, double> volume_before_mm3;  ///< tissue id -> enclosed volume before
  std::map<int, double> volume_after_mm3;   ///< and after
  /// A round was undone (at an eighth of its offsets still invalid, flipped or a smaller angle).
  bool stopped_early = false;
  std::size_t frozen_vertices = 0;          ///< vertices held in place where a round broke the surface
  /// Tissues released, in order: at least 1 % off and brought less than a tenth of the way by a
  /// round, they stopped constraining the offsets and their vertices moved no more from then on.
  std::vector<int> released;
};

/// Volume each tissue encloses (tissue id -> mm^3), from the signed volumes of its boundary.
std::map<int, double> enclosed_volumes(const TriSurface& surface);

/// What makes a round's positions acceptable besides the triangle rules above (no normal turned
/// past 60 degrees, no angle under the smallest): true when `moved` is acceptable, else false with
/// the vertices at fault in `bad_vertices` (they and their neighbours are then held). The default
/// (an empty function) requires a valid, intersection-free surface (surface_checks.h); the tets of
/// a mesh whose surface this is have their own rule (volume/tet_volume_restoration.h).
using RestorationCheck = std::function<bool(const TriSurface& moved, std::vector<int>& bad_vertices)>;

/// Moves `surface`'s non-junction vertices as above so that every tissue of `reference_mm3`
/// (tissue id -> volume, > 0) encloses that volume; rounds stop when every tissue not released is
/// within `tolerance_rel` (relative) or after `max_rounds`. No vertex moves further than
/// `max_total_move_mm` over all rounds (the sum of its moves; infinity: no bound). With the default
/// check, `surface` must be valid and intersection free. Throws InputError for a reference naming
/// an unknown tissue or not > 0, or a bound not > 0.
VolumeRestoration restore_volumes(TriSurface& surface, const std::map<int, double>& reference_mm3,
                                  double tolerance_rel = 1e-4, int max_rounds = 8,
                                  const RestorationCheck& check = {},
                                  double max_total_move_mm = std::numeric_limits<double>::infinity());

}  // namespace tissuemesh
