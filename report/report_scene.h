// What report.html draws in 3D, built from a tet mesh: node positions, each tissue's boundary
// (outward triangles, interfaces included, so that every tissue is a closed surface), the outer
// boundary, and per tet its tissue and smallest dihedral angle (the section colours). Optional
// overlays: a displacement field, polylines (e.g. a tumour centroid's path), an approach corridor
// and junction curves.
//
// Units: mm, degrees. Display data only: positions are stored as float32 in the page.
#pragma once

#include "core/tet_mesh.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace tissuemesh {

struct ReportPath {
  std::string name;                       ///< shown in the legend, e.g. "tumour centroid"
  std::vector<Eigen::Vector3d> points;    ///< mm, in order
};

struct ReportCorridor {
  Eigen::Vector3d entry_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d target_mm = Eigen::Vector3d::Zero();
  double radius_mm = 0;
};

struct ReportScene {
  std::vector<Eigen::Vector3d> nodes;                          ///< mm
  std::vector<std::string> tissue_names;                       ///< tissue id i -> [i - 1]
  std::vector<std::vector<std::array<int, 3>>> tissue_faces;   ///< per tissue id - 1, outward
  std::vector<std::array<int, 3>> outer_faces;                 ///< mesh boundary, outward
  std::vector<std::array<int, 4>> tets;                        ///< for the section (may be a subset)
  std::vector<unsigned char> tet_tissue;                       ///< per entry of tets, 1-based id
  std::vector<float> tet_min_dihedral_deg;                     ///< per entry of tets
  std::size_t mesh_tets = 0;                                   ///< tets of the whole mesh
  std::vector<Eigen::Vector3d> displacement_mm;                ///< per node, or empty
  std::string displacement_label;                              ///< e.g. "deformed by gravity"
  std::vector<ReportPath> paths;
  std::optional<ReportCorridor> corridor;
  std::vector<std::array<Eigen::Vector3d, 2>> junction_segments;  ///< mm
  std::optional<Eigen::Vector3d> clip_at_mm;                   ///< where the section starts
};

/// The scene of `mesh`: boundaries from its multi-material surface (quality/mesh_interfaces.h),
/// every tet with its tissue and smallest dihedral angle. The section starts through the centroid
/// of a tissue named "tumor" or "tumour" when there is one, else through the bounding box centre.
/// Throws InputError for a mesh whose faces are shared by more than two tets, or with more than
/// 255 tissues.
ReportScene scene_of_mesh(const TetMesh& mesh);

/// 1-based id of the tissue named "tumor" or "tumour", or 0 when there is none.
int tumour_tissue_id(const std::vector<std::string>& tissue_names);

/// Volume-weighted centroid (mm) of tissue `id` (1-based) of `mesh` with its nodes at `positions`
/// (one per mesh node); nullopt when the tissue has no volume.
std::optional<Eigen::Vector3d> tissue_centroid(const TetMesh& mesh, int id, const std::vector<Eigen::Vector3d>& positions);

/// Bytes the scene takes in the page (base64 arrays), for the size cap.
std::size_t scene_page_bytes(const ReportScene& scene);

/// Shrinks the scene to at most `max_bytes` in the page, for display only, and says what it did
/// (empty when nothing was needed): first the section keeps one tet in k, then the surfaces are
/// simplified by vertex clustering on a grid coarse enough to fit. Never touches the displacement
/// beyond the nodes kept.
std::string fit_scene(ReportScene& scene, std::size_t max_bytes);

}  // namespace tissuemesh
