// One entry point for every built-in label-map generator: the smooth breast phantom
// (phantom.h), the fragmented breast (fragmented_breast.h) and the folded layers
// (folded_layers.h), chosen by PhantomParams::kind, with or without background.
//
// no_background: no voxel of the result has label 0. The breasts put padding (label 9) where the
// air was, so that the tissues run into every face of the box, and add a 33-voxel marker clip
// (label 8) in the fat (the fragmented breast always has it); the folded layers grow past the
// box corners (folded_layers.h). Deterministic: the same parameters give the same image bit for
// bit. Throws InputError naming the key as the generators do.
#pragma once

#include "core/label_image.h"
#include "image/phantom.h"

namespace tissuemesh {

/// Generates the label map of params.kind.
LabelImage make_phantom(const PhantomParams& params);

}  // namespace tissuemesh
