// Built-in breast phantom: a deterministic label volume that looks like the segmentation of a
// breast MRI of a PRONE patient, made to exercise everything a real label map does to a mesher
// (thin skin, anisotropic oblique voxels, muscle touching the image border, branching and
// fragmented fibroglandular tissue, small isolated islands, a lobulated spiculated tumour).
//
// Patient frame: millimetres, LPS (+x Left, +y Posterior, +z Superior), origin at the centre of
// the breast base on the chest wall (the anterior surface of the pectoral muscle). The breast
// hangs anteriorly (towards -y): a slightly conical, gently irregular half-ellipsoid of
// breast_width_mm (L-R) x breast_height_mm (S-I) at the base, protruding breast_depth_mm, joined
// by a smooth fillet to the chest. Layers over the chest, anterior to posterior: skin, ~8 mm
// subcutaneous fat, pectoral muscle (muscle_thickness_mm, spans the whole field of view), thorax
// to the posterior image border. FGT is a tree of ducts radiating from behind the nipple towards
// the chest wall with branches and lobules, plus `fgt_islands` isolated islands in the fat.
//
// Voxel grid: i along patient Right, j Anterior, k Superior, then rotated by oblique_deg about
// the superior axis (direction is a proper rotation, det +1, not axis-aligned). The field of view
// reaches about 15 mm beyond the breast laterally and S-I (filled by the chest) and leaves a
// 5 mm air margin around the breast. Defaults give 201 x 180 x 88 voxels of 0.7 x 0.7 x 1.5 mm.
//
// Determinism: same parameters give the same image bit for bit, on any IEEE-754 platform (the
// random numbers come from std::mt19937 converted by hand, and no libm transcendental function
// is used; see phantom.cpp).
#pragma once

#include "core/label_image.h"
#include "core/yaml_map.h"
#include "image/folded_layers.h"
#include "image/fragmented_breast.h"

#include <Eigen/Core>

#include <cstdint>
#include <string>

namespace tissuemesh {

/// Label values the phantom writes (the shipped configs/phantom.yaml maps them).
enum PhantomLabel : std::int32_t {
  kAir = 0,
  kFat = 1,
  kFgt = 2,
  kTumor = 3,
  kSkin = 4,
  kMuscle = 5,
  kThorax = 6
};

/// Parameters of the phantom; YAML keys are the field names. Bounds are checked by
/// parse_phantom_params and make_breast_phantom (InputError naming the key).
struct PhantomParams {
  /// Random seed: FGT tree, tumour lobulation and spicules, islands, surface irregularity.
  /// Integer in [0, 2^31 - 1]. Default 1.
  std::uint32_t seed = 1;
  /// Voxel spacing along i, j, k in mm, each in [0.1, 5]; the grid may hold at most 60 million
  /// voxels. Default (0.7, 0.7, 1.5): anisotropic like a breast MR acquisition.
  Eigen::Vector3d spacing_mm{0.7, 0.7, 1.5};
  /// Rotation of the voxel axes about the superior axis, degrees in [-30, 30] (beyond, the box
  /// holding the receding chest wall grows fast). Default 8.
  double oblique_deg = 8.0;
  /// Left-right size of the breast base on the chest wall, mm in [40, 250]. Default 110.
  double breast_width_mm = 110.0;
  /// Superior-inferior size of the breast base, mm in [40, 250]. Default 100.
  double breast_height_mm = 100.0;
  /// Anterior protrusion of the breast from the chest wall, mm in [20, 200]. Default 70.
  double breast_depth_mm = 70.0;
  /// Minimum skin thickness in the label image, mm in [half the smallest spacing, 10]. A body
  /// voxel is skin when any part of its box lies closer than this to an air voxel's box, so
  /// along any line into the body the skin is at least this thick; on axis-aligned surfaces it
  /// is less than one voxel thicker (default 1.5 mm: 3 voxels of 0.7 mm in-plane, 1 voxel of
  /// 1.5 mm across slices), on oblique ones up to ~2.7x (voxel staircase; median ~1.7x).
  double skin_thickness_mm = 1.5;
  /// Thickness of the pectoral muscle slab, mm in [2, 40]. Default 12.
  double muscle_thickness_mm = 12.0;
  /// Tumour centre in the patient frame (LPS mm). It must lie in the breast, at least
  /// skin_thickness_mm + 2 mm under its surface (along the ray from the base centre, for the
  /// breast shrunk by its largest irregularity) and anterior to the chest wall (y < 0).
  /// Default (10, -28, 8): mid-depth, slightly left and superior, inside the main FGT.
  Eigen::Vector3d tumor_center_mm{10.0, -28.0, 8.0};
  /// Mean diameter of the tumour, mm in [2, 60]; its surface is modulated by +-18% and carries
  /// 2-3 short spicules. The tumour replaces fat and FGT only. Default 15.
  double tumor_diameter_mm = 15.0;
  /// Number of isolated FGT islands (radius 1.5-4 mm) in the fat, in [0, 20]. Each is a separate
  /// 6-connected component with 3 whole voxels of fat (4 largest spacings between voxel centres)
  /// between it and any other FGT, tumour, muscle or skin. The default breast holds 20; small
  /// breasts hold fewer (make_breast_phantom then throws). Default 5.
  int fgt_islands = 5;

  // Which generator make_phantom (image/make_phantom.h) runs; the keys above are the breast's.
  /// "breast" (this file), "fragmented-breast" or "folded-layers". Default "breast".
  std::string kind = "breast";
  /// No label 0: air becomes padding (label 9) and a 33-voxel marker clip (label 8) goes into
  /// the fat for the two breasts; the folded layers fill the box instead. Default false.
  bool no_background = false;
  /// Parameters of kind fragmented-breast (YAML: fragmented_breast).
  FragmentedBreastParams fragmented_breast;
  /// Parameters of kind folded-layers (YAML: folded_layers).
  FoldedLayersParams folded_layers;
};

/// Reads the phantom keys of `map` (all optional; absent keys keep their default) and validates
/// them. Throws InputError naming the key (via map.where) on a wrong type or a value out of
/// bounds. Does not call map.finish(): the caller owns the map and checks for unknown keys.
PhantomParams parse_phantom_params(YamlMap& map);

/// Emits the parameters as one YAML map with the keys parse_phantom_params reads (for
/// --print-config); parsing the emitted text gives back the same parameters exactly.
void phantom_params_to_yaml(const PhantomParams& params, YAML::Emitter& out);

/// Generates the phantom (labels are PhantomLabel values). Deterministic: the same parameters
/// give the same image bit for bit. Throws InputError naming the key if a parameter is out of
/// bounds, or naming fgt_islands if that many islands do not fit in the breast fat.
LabelImage make_breast_phantom(const PhantomParams& params);

}  // namespace tissuemesh
