// Folded layers: six nested tissues (like scalp, skull, CSF, grey matter, white matter, deep
// grey) whose two middle interfaces fold like a cortex with a period of a few voxels. A hard
// input for a mesher: thin sheets (the grey layer, a few voxels thick) that fold tightly, and
// interfaces that never touch their non-neighbours.
//
// Frame: millimetres, LPS, identity direction, isotropic spacing, a cube of size_mm centred on
// the origin. With r the distance from the centre and g(x) = (sin(2 pi x / P + a) +
// sin(2 pi y / P + b) + sin(2 pi z / P + c)) / 3 a periodic fold field (P = fold_period_mm,
// phases a, b, c from the seed), the interfaces from outside in are spheres except the two
// folded ones: outer (air/scalp) r = R0, scalp/skull, skull/CSF, CSF/grey r = R3 + A g(x),
// grey/white r = R4 + A g(x) (A = fold_amplitude_mm: grey keeps its radial thickness while it
// folds), white/deep r = deep_radius_mm. R0 = 0.45 size_mm; layer_thickness_mm gives the radial
// thickness of scalp, skull, CSF (between the sphere and the folds' mean) and grey.
// Each layer is thick enough at the voxel scale that 6-neighbouring voxels never skip a layer
// (checked: thickness >= spacing + A (+ the fold's change over one voxel)); so every tissue
// touches only its two neighbours (and the tiny tissue). At a few voxels per period the folds
// alias: CSF, grey and white hold small detached pieces, each still between its neighbours.
// no_background (make_folded_layers' argument): R0 grows to reach past the box corners, so no
// voxel is air and scalp, skull, CSF, grey and white are cut by the box: each touches all six
// faces, with the folded interfaces running into them.
// Labels: 0 air, 1 scalp, 2 skull, 3 csf, 4 grey, 5 white, 6 deep, 7 lesion (33 voxels inside
// the white matter, no_background.h). Defaults: 120^3 voxels of 1 mm (1.7 M).
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

namespace layer_label {
constexpr std::int32_t kScalp = 1, kSkull = 2, kCsf = 3, kGrey = 4, kWhite = 5, kDeep = 6, kLesion = 7;
}  // namespace layer_label

/// Parameters of the folded layers; YAML keys (under phantom.folded_layers) are the field names.
struct FoldedLayersParams {
  /// Seed of the fold phases and the lesion's place, integer in [0, 2147483647]. Default 1.
  std::uint32_t seed = 1;
  /// Isotropic voxel spacing, mm in [0.1, 5]. Default 1.
  double spacing_mm = 1.0;
  /// Edge of the cubic field of view, mm in [10, 1000]; at most 60 million voxels. Default 120.
  double size_mm = 120.0;
  /// Period of the folds, mm in [2 spacing, 100]. Default 3.
  double fold_period_mm = 3.0;
  /// Radial amplitude of the folds, mm in [0, 20]. Default 1.5.
  double fold_amplitude_mm = 1.5;
  /// Radial thickness of scalp, skull, CSF and grey, mm, each > 0 and thick enough not to be
  /// skipped between neighbouring voxels (see above). Default (4, 5, 5, 4).
  Eigen::Vector4d layer_thickness_mm{4.0, 5.0, 5.0, 4.0};
  /// Radius of the deep core, mm; the white matter fills the rest. Default 15.
  double deep_radius_mm = 15.0;
};

/// Checks every bound (for the geometry without background, and with it when `no_background`);
/// `where(key)` prefixes the InputError message.
void check_folded_layers_params(const FoldedLayersParams& params, bool no_background,
                                const std::function<std::string(const char*)>& where);

/// Reads the keys of `map` (all optional) and checks them. Does not call map.finish().
FoldedLayersParams parse_folded_layers_params(YamlMap& map);

/// Emits the parameters as one YAML map; parsing it gives back the same parameters.
void folded_layers_params_to_yaml(const FoldedLayersParams& params, YAML::Emitter& out);

/// Generates the image; throws InputError naming the key on a bound violation.
LabelImage make_folded_layers(const FoldedLayersParams& params, bool no_background = false);

}  // namespace tissuemesh
