// The optimisation and sliver-repair steps after CGAL Mesh_3's Delaunay refinement, shared by the
// direct pipeline (`direct:`) and the volume mesher of the surface pipeline (`volume:`); the keys
// sit in those sections, flat. What each step does: CGAL Mesh_3 manual ("Optimization"),
// volume/boundary_slivers.h and volume/sliver_flips.h. Times are seconds, angles degrees.
#pragma once

#include "core/tet_mesh.h"
#include "core/yaml_map.h"
#include "volume/boundary_pinches.h"
#include "volume/boundary_slivers.h"
#include "volume/sliver_flips.h"
#include "volume/sliver_smoothing.h"
#include "volume/sliver_splits.h"

#include <string>
#include <vector>

namespace tissuemesh {

struct Mesh3Optimisation {
  bool lloyd = false;                   ///< Lloyd optimisation (slow; off by default)
  bool odt = false;                     ///< ODT optimisation (slow; off by default)
  double optimise_time_limit_s = 10.0;  ///< time limit of each of Lloyd / ODT, s
  /// Sliver perturbation. Off by default: CGAL 5.5's perturber gives a different mesh on every
  /// run, and the same input must give the same output files.
  bool perturb = false;
  bool exude = true;                    ///< sliver exudation
  double sliver_bound_deg = 15.0;       ///< dihedral angle the perturber / exuder aim for, degrees
  double sliver_time_limit_s = 20.0;    ///< time limit of each of perturb / exude, s
  /// Remove tets with a dihedral below this (degrees) that have >= 2 faces on the outer boundary
  /// (flat caps no vertex move can repair; boundary_slivers.h). 0 = keep them.
  double remove_boundary_slivers_deg = 10.0;
  /// Improve tets with a dihedral below this (degrees) by 2-3 flips and edge removals inside one
  /// tissue (sliver_flips.h): interfaces and volumes unchanged. 0 = off.
  double flip_slivers_below_deg = 15.0;
  /// Let those flips give a flat wedge on an interface to the neighbouring tissue (moves the
  /// interface by the wedge's thickness; the moved volume is reported).
  bool interface_flips = true;
  /// Let the edge splits (tets still under 10 degrees) do the same before a split
  /// (sliver_splits.h). Not a config key: it follows interface_flips, except where a caller keeps
  /// the surface and allows only these last few relabels (volume/surface_tetgen.h).
  bool split_relabels = true;
  /// Then move the vertices of tets with a dihedral below this (degrees) to raise the smallest
  /// angle around them (sliver_smoothing.h): vertices inside one tissue freely, vertices on a
  /// flat boundary or interface within its plane; interfaces, boundary and volumes unchanged.
  /// In the surface pipeline also vertices on a curved boundary or interface, over the input
  /// surface (they stay on it). 0 = off.
  double smooth_slivers_below_deg = 15.0;
  /// Let that smoothing also move vertices of nearly flat boundary or interface patches (face
  /// normals within this angle, degrees) in the plane that keeps every tissue's volume: the
  /// surface moves off its place by at most sin(2 x this angle) times the move (sliver_smoothing.h).
  /// 0 = off (exactly flat patches only).
  double smooth_near_planar_deg = 0.0;
  /// Last resort for what is still under 10 degrees after the splits: the smoothing again, its
  /// vertices on boundaries and interfaces (junctions included) now free to move off them by at
  /// most this times their mean edge length, then the splits again (sliver_smoothing.h). The
  /// boundary and interfaces move by at most that at those vertices. 0 = off.
  double sliver_offset_edge_ratio = 0.1;
  /// Where the outer boundary touches itself along an edge (non-manifold), remove the tets of the
  /// smaller side around that edge (boundary_pinches.h). Off leaves such a mesh to fail the
  /// conformity check.
  bool open_boundary_pinches = true;

  /// Reads these keys from the open section map `m` (range-checked, the key named in errors);
  /// keys absent keep the defaults above.
  void read(YamlMap& m);
  /// Writes these keys into an open map of `out`.
  void emit(YAML::Emitter& out) const;
};

/// What the sliver repairs did to a mesh.
struct SliverRepair {
  BoundarySliverRemoval boundary_slivers;  ///< flat caps removed from the outer boundary
  SliverFlipResult sliver_flips;           ///< flips applied inside tissues
  SliverSmoothingResult sliver_smoothing;  ///< vertices moved (free, in-plane, on the surface)
  SliverSplitResult sliver_splits;         ///< interior edges split where moves could not help
  SliverSmoothingResult sliver_offsets;    ///< the last resort's moves off the surface (sliver_offset_edge_ratio)
  BoundaryPinchRepair boundary_pinches;    ///< tets removed where the outer boundary pinches at an edge
};

/// The repairs `options` asks for (remove_boundary_slivers_deg, flip_slivers_below_deg,
/// smooth_slivers_below_deg and then, for what is still below 10 degrees, splits of edges inside one
/// tissue (sliver_splits.h), the moves off the surface of sliver_offset_edge_ratio and splits again,
/// open_boundary_pinches; in that order), on a mesh just extracted from
/// CGAL; a mesh too large for them is left as it is, with a warning.
/// `onto_surface` (optional): the surface the mesh's boundary and interfaces approximate, for the
/// smoothing of vertices on curved ones (sliver_smoothing.h).
SliverRepair repair_slivers(TetMesh& mesh, const Mesh3Optimisation& options, std::vector<std::string>& warnings,
                            const SurfaceProjector& onto_surface = {});

}  // namespace tissuemesh
