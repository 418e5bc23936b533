// Dispatch over the phantom kinds; make_phantom.h states the contract.
#include "image/make_phantom.h"

#include "core/errors.h"
#include "image/no_background.h"

namespace tissuemesh {

LabelImage make_phantom(const PhantomParams& p) {
  if (p.kind == "folded-layers") return make_folded_layers(p.folded_layers, p.no_background);
  LabelImage image;
  if (p.kind == "fragmented-breast") {
    image = make_fragmented_breast(p.fragmented_breast);
  } else if (p.kind == "breast") {
    image = make_breast_phantom(p);
    if (p.no_background) add_tiny_tissue(image, kFat, hard_label::kClip, p.seed + 7);
  } else {
    throw InputError("phantom parameter kind: unknown phantom kind '" + p.kind +
                     "' (supported: breast, fragmented-breast, folded-layers)");
  }
  if (p.no_background) fill_background(image, hard_label::kPadding);
  return image;
}

}  // namespace tissuemesh
