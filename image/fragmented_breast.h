// Fragmented breast: a hard label map with the traits real breast segmentations have and the
// smooth built-in phantom lacks: thousands of disconnected FGT islands, a branching vessel tree
// of tubes near the voxel size, skin two to four voxels thick, chest and breast cut by the image
// borders, a tissue of a few tens of voxels, fine isotropic voxels in large numbers.
//
// Frame: millimetres, LPS, identity direction (i Left, j Posterior, k Superior), isotropic
// spacing. The box is size_mm (L-R, A-P, S-I) centred on x = z = 0; the chest wall (anterior
// muscle surface) passes through y = 0 at its centre and curves posteriorly; the field of view
// reaches 0.7 size_mm.y() anterior and 0.3 size_mm.y() posterior of it. The geometry scales with
// size_mm; the feature sizes (skin, vessels, islands, tumour) are absolute.
//  - muscle (0.1 size_mm.y() thick) and thorax behind it span the whole box: they touch the
//    left, right, superior, inferior and posterior faces;
//  - the breast, a lobulated half-ellipsoid hanging anteriorly, is wider S-I than the box: the
//    superior and inferior faces cut it (no skin on a cut face);
//  - skin: body voxels whose centre lies within skin_thickness_mm of an air voxel's centre, so an
//    axis ray from air into the body crosses floor(skin_thickness_mm / spacing_mm) skin voxels
//    where the surface is square to it, more where it is oblique;
//  - FGT: a main glandular body (noise-thresholded: lobular, with its own fragments) plus
//    fgt_islands islands in the fat, each a separate 6-connected component (one voxel up to
//    island_max_diameter_mm across) with at least one voxel of fat between it and anything else,
//    plus fgt_diagonal_contacts one-voxel islands that touch other FGT only along an edge or at
//    a corner (separate 6-connected components, a non-manifold contact for a mesher);
//  - vessels: a branching tree of tubes, diameter from vessel_max_diameter_mm at the chest wall
//    down to vessel_min_diameter_mm; a tube is painted at least a voxel diagonal wide (every
//    voxel its axis crosses), so the thinnest are 6-connected chains one or two voxels across;
//    the tree is cut where it meets skin, tumour or thorax;
//  - a lobulated tumour; a marker clip of 33 voxels (no_background.h) in the fat.
// Labels: 0 air, 1 fat, 2 fgt, 3 tumor, 4 skin, 5 muscle, 6 thorax (the phantom's values),
// 7 vessel, 8 clip; 9 padding is what make_phantom's no_background puts in place of air.
// Memory: the LabelImage (4 bytes per voxel), a list of the surface voxels and one of the FGT
// voxels (4 bytes each); no full-size scratch. Defaults: 200 x 200 x 160 voxels of 0.5 mm (6.4 M).
//
// Determinism: same parameters -> same image bit for bit (phantom_random.h).
#pragma once

#include "core/label_image.h"
#include "core/yaml_map.h"

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <string>

namespace tissuemesh {

/// Labels of the hard inputs beyond the phantom's 0-6.
namespace hard_label {
constexpr std::int32_t kVessel = 7;
constexpr std::int32_t kClip = 8;
constexpr std::int32_t kPadding = 9;
}  // namespace hard_label

/// Parameters of the fragmented breast; YAML keys (under phantom.fragmented_breast) are the
/// field names. Bounds are checked by parse_ and make_fragmented_breast (InputError naming the key).
struct FragmentedBreastParams {
  /// Random seed (shape, FGT, vessels, tumour, islands), integer in [0, 2147483647]. Default 1.
  std::uint32_t seed = 1;
  /// Isotropic voxel spacing, mm in [0.1, 2]. Default 0.5.
  double spacing_mm = 0.5;
  /// Field of view L-R, A-P, S-I, mm, each in [20, 600]; at most 60 million voxels.
  /// Default (100, 100, 80): 200 x 200 x 160 voxels at 0.5 mm.
  Eigen::Vector3d size_mm{100.0, 100.0, 80.0};
  /// Skin thickness, mm in [spacing_mm, 5]. Default 1.5 (3 voxels at 0.5 mm).
  double skin_thickness_mm = 1.5;
  /// Vessel diameters: the trunks' and the thinnest branches', mm in [0.1, 5], min <= max.
  /// Defaults 2 and 0.5.
  double vessel_max_diameter_mm = 2.0;
  double vessel_min_diameter_mm = 0.5;
  /// Isolated FGT islands in the fat, in [0, 200000]; throws if they do not fit. Default 3000.
  int fgt_islands = 3000;
  /// One-voxel FGT islands touching other FGT only by an edge or a corner, in [0, 100000];
  /// throws if they do not find room. Default 500.
  int fgt_diagonal_contacts = 500;
  /// Largest island extent, mm in [0, 10] (0: every island is one voxel). Sizes are skewed
  /// towards one voxel. Default 3.
  double island_max_diameter_mm = 3.0;
  /// Mean tumour diameter, mm in [1, 60] and at most 0.3 x the smallest size_mm. Default 12.
  double tumor_diameter_mm = 12.0;
};

/// Checks every bound; `where(key)` prefixes the InputError message (file and key path).
void check_fragmented_breast_params(const FragmentedBreastParams& params,
                                    const std::function<std::string(const char*)>& where);

/// Reads the keys of `map` (all optional) and checks them. Does not call map.finish().
FragmentedBreastParams parse_fragmented_breast_params(YamlMap& map);

/// Emits the parameters as one YAML map; parsing it gives back the same parameters.
void fragmented_breast_params_to_yaml(const FragmentedBreastParams& params, YAML::Emitter& out);

/// Generates the image. Throws InputError naming the key on a bound violation or when
/// fgt_islands islands do not fit in the fat.
LabelImage make_fragmented_breast(const FragmentedBreastParams& params);

}  // namespace tissuemesh
