// The surface pipeline's job: label image + config -> multi-material surface with its checks and
// quality (Tables 1 and 2 of Alqaoud et al., "Multi-material, approach-guided,
// controlled-resolution breast meshing", and per-tissue volume against voxel volume) -> tet mesh
// of that surface with its quality and conformity: CGAL Mesh_3 (volume/complex_mesher.h) or, with
// volume.mesher: tetgen, TetGen keeping every surface triangle (volume/surface_tetgen.h).
// The volume mesher's size field is the surface's: h(x) = L s(x) with L the remesher's edge length
// (the mean edge of the extracted surface without remeshing) and s the approach grading (1 without
// it). Nothing is printed; stages go through `progress`.
#pragma once

#include "core/label_image.h"
#include "core/progress.h"
#include "pipeline/mesh_config.h"
#include "surface/approach_field.h"
#include "volume/complex_mesher.h"
#include "volume/surface_tetgen.h"
#include "quality/conformity.h"
#include "quality/mesh_quality.h"
#include "surface/surface_distance.h"
#include "surface/surface_extraction.h"
#include "surface/surface_quality.h"
#include "surface/surface_remesh.h"
#include "surface/volume_restoration.h"

#include <map>
#include <optional>
#include <string>

namespace tissuemesh {

/// The tet mesh of the surface and what it measured.
struct VolumeStage {
  /// The mesh, its sliver repairs and warnings; the CGAL counters (pieces, initial points) stay 0
  /// with TetGen.
  ComplexMeshResult meshing;
  std::string mesher = "cgal";   ///< volume.mesher
  std::string tetgen_switches;   ///< TetGen only: the switches of the mesh kept
  std::size_t steiner_points = 0;   ///< TetGen only: nodes added to the surface's
  double cell_edge_factor = 0.0;    ///< TetGen only: the size factor used (solved under target_tets)
  std::vector<BudgetRound> budget;  ///< TetGen only: the rounds under volume.target_tets
  double size_mm = 0.0;          ///< L of the size field h(x) = L s(x), mm
  QualityReport quality;         ///< per tissue, voxel volume as reference
  ConformityReport conformity;
  std::vector<VolumeDeviation> volume_deviations;  ///< tissues outside checks.volume_tolerance_percent
};

/// The remeshing and the volume stage run again with the fold guard (volume.mesher tetgen, when
/// tets under 10 degrees remained).
struct FoldRerun {
  double sharpest_before_deg = 180.0;  ///< sharpest_fold_deg of the first surface
  double sharpest_after_deg = 180.0;   ///< and of the guarded one
  std::size_t tets_under_10_before = 0, tets_under_10_after = 0;
  /// The guarded result replaced the first: it conforms and has fewer tets under 10 degrees (or as
  /// many and a larger smallest dihedral angle).
  bool kept = false;
};

struct SurfaceJobResult {
  SurfaceExtraction extraction;             ///< extracted surface, repair, vertex counts and its checks
  SurfaceQuality extracted_quality;         ///< Table 1 figures of the extracted surface
  std::optional<RemeshResult> remesh;       ///< when the config asks for remeshing
  std::optional<FoldRerun> fold_rerun;      ///< when the remeshing ran again with the fold guard
  /// surface.thickness_edge_ratio the remeshing ran with (0: sizes not bounded by thickness).
  double thickness_edge_ratio = 0.0;
  std::optional<VolumeRestoration> restoration;  ///< with surface.restore_volumes (remesh->surface moved)
  std::optional<SurfaceDistance> hausdorff; ///< remeshed vs extracted surface
  std::optional<ApproachField> approach;    ///< when approach.enabled
  std::optional<ApproachGrading> grading;   ///< measured on surface() when approach.enabled
  SurfaceCheckReport checks;                ///< of surface()
  SurfaceQuality quality;                   ///< Table 1 figures of surface()
  double sharpest_fold_deg = 180.0;         ///< sharpest_fold_deg(surface()), degrees
  std::map<int, double> voxel_volume_mm3;   ///< tissue id -> voxel volume of the tissue
  std::optional<VolumeStage> volume;        ///< the tet mesh, when the surface passes its checks
  /// Why no tet mesh was made although the surface passed its checks (empty otherwise): a surface
  /// with a near-zero angle (under kMinAngleForVolumeDeg) that Mesh_3's junction protection
  /// would not finish on.
  std::string volume_refused;

  /// The pipeline's result: the remeshed surface, or the extracted one without remeshing.
  const TriSurface& surface() const { return remesh ? remesh->surface : extraction.surface; }
};

/// Smallest triangle angle (degrees) of a surface the volume stage accepts.
inline constexpr double kMinAngleForVolumeDeg = 1.0;

/// Throws InputError for bad labels (see tissue_id_image), MeshingError when the image has no
/// boundary. A surface failing its checks, or with an angle under kMinAngleForVolumeDeg
/// (volume_refused), is returned without a volume mesh (the caller reports it), not thrown.
SurfaceJobResult run_surface_job(const LabelImage& labels, const std::string& image_name, const MeshConfig& config,
                                 Progress& progress);

}  // namespace tissuemesh
