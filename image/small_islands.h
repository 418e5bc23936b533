// Absorption of sub-resolution islands before meshing (both pipelines).
//
// Every 6-connected component of a tissue (image/label_components.h) with fewer than `min_voxels`
// voxels, except the tissue's largest (the first in find_components' order of equals: a tissue is
// never removed whole, so a small tumour or a marker clip stays and is reported as kept), takes
// the region most of its face neighbours belong to (ties: the lowest id; the image
// border counts as outside, 0). Components are visited in find_components' order and relabelled
// in place; passes repeat (at most 10) until none is left, so an island inside another small
// island ends with the region around both. Cavities of outside (id 0) are not touched.
// What went is counted per tissue against the image as it came in, so that a report can name it
// (tissue, components, voxels, volume, and where the voxels went). Deterministic.
#pragma once

#include "core/label_image.h"

#include <cstddef>
#include <map>
#include <vector>

namespace tissuemesh {

/// The islands one tissue lost.
struct TissueIslands {
  int tissue_id = 0;                       ///< tissue the islands belonged to (> 0)
  std::size_t islands = 0;                 ///< its components (in the image as it came in) that lost voxels
  std::size_t voxels = 0;                  ///< its voxels whose id changed
  double volume_mm3 = 0.0;                 ///< voxels * voxel volume
  std::map<int, std::size_t> voxels_into;  ///< id they took (0 = outside) -> voxels
};

struct IslandAbsorption {
  std::size_t min_voxels = 0;  ///< the threshold: components with fewer voxels went
  std::size_t islands = 0;  ///< sum of TissueIslands::islands
  std::size_t voxels = 0;   ///< voxels whose id changed
  double volume_mm3 = 0.0;  ///< their volume
  bool complete = true;     ///< no island left (false: the pass cap ended it, a pathological labeling)
  std::vector<TissueIslands> tissues;  ///< tissues that lost voxels, by ascending id
  /// Tissues whose largest component is under min_voxels and kept: tissue id -> its voxels (as of
  /// the last full pass; a later absorption's entries replace these tissue by tissue).
  std::map<int, std::size_t> kept_whole;

  /// Adds the counts of a later absorption (e.g. of the next repair round) tissue by tissue;
  /// `complete` and `min_voxels` become those of `later`, its kept_whole entries are merged in.
  void add(const IslandAbsorption& later);
};

/// Relabels the islands of `ids` (tissue ids, 0 = outside) with fewer than `min_voxels` voxels;
/// min_voxels <= 1 changes nothing. `changed_since`, when given, lists every voxel whose id changed
/// since `ids` last had no island (e.g. since the last absorption with the same min_voxels that was
/// `complete`); every entry must be a voxel index of `ids` (else std::invalid_argument). Then
/// only the components at those voxels and their face neighbours are searched for islands (a
/// bounded search each), and the whole image is labelled only when one is found. The result is
/// the one without the hint; wrong hints give wrong results.
IslandAbsorption absorb_small_islands(LabelImage& ids, std::size_t min_voxels,
                                      const std::vector<std::size_t>* changed_since = nullptr);

}  // namespace tissuemesh
