// TissueTable: which image label values make up which tissue.
//
// Config form (a list keeps the tissue order, which fixes the tissue ids 1..N):
//   tissues:
//     - { name: fat,   labels: [1] }
//     - { name: fgt,   labels: [2, 7] }     # several glandular codes -> one tissue
//   ignore_labels: [0, 6]                    # -> outside the model
// Rules: names unique and non-empty, each label used once; a label present in an image but neither
// mapped nor ignored is an error naming it; a mapped tissue with no voxels is an error naming it.
#pragma once

#include "core/label_image.h"
#include "core/yaml_map.h"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace tissuemesh {

struct Tissue {
  std::string name;
  int id = 0;                          ///< 1-based, order of the config list
  std::vector<std::int32_t> labels;    ///< image label values mapped to this tissue
};

class TissueTable {
 public:
  TissueTable() = default;
  TissueTable(std::vector<Tissue> tissues, std::vector<std::int32_t> ignored,
              const std::string& where);

  /// Reads `tissues` and `ignore_labels` from the top-level config map.
  static TissueTable from_config(YamlMap& top);
  /// Writes the same keys back (for --print-config).
  void to_yaml(YAML::Emitter& out) const;

  const std::vector<Tissue>& tissues() const { return tissues_; }
  const std::vector<std::int32_t>& ignored() const { return ignored_; }
  std::vector<std::string> names() const;
  /// Tissue id (1..N) of a label, 0 if ignored, -1 if unknown.
  int tissue_of_label(std::int32_t label) const;

  /// Throws InputError if a label in `counts` is unknown or a tissue has no voxels; `what` names
  /// the image in the message.
  void check_against(const std::map<std::int32_t, std::size_t>& counts,
                     const std::string& what) const;

  /// Same geometry, voxel values replaced by tissue ids (0 = outside). Call check_against first.
  LabelImage to_tissue_ids(const LabelImage& labels) const;

 private:
  std::vector<Tissue> tissues_;
  std::vector<std::int32_t> ignored_;
  std::map<std::int32_t, int> label_to_tissue_;
};

}  // namespace tissuemesh
