#include "core/tissue_table.h"

#include "core/errors.h"

#include <set>
#include <sstream>

namespace tissuemesh {

TissueTable::TissueTable(std::vector<Tissue> tissues, std::vector<std::int32_t> ignored,
                         const std::string& where)
    : tissues_(std::move(tissues)), ignored_(std::move(ignored)) {
  if (tissues_.empty()) throw InputError(where + ": tissues: at least one tissue is required");
  std::set<std::string> names;
  for (std::size_t t = 0; t < tissues_.size(); ++t) {
    Tissue& tissue = tissues_[t];
    tissue.id = static_cast<int>(t) + 1;
    if (tissue.name.empty()) throw InputError(where + ": tissues: a tissue has an empty name");
    if (!names.insert(tissue.name).second)
      throw InputError(where + ": tissues: tissue '" + tissue.name + "' is listed twice");
    if (tissue.labels.empty())
      throw InputError(where + ": tissues: tissue '" + tissue.name + "' has no labels");
    for (std::int32_t label : tissue.labels) {
      if (!label_to_tissue_.emplace(label, tissue.id).second) {
        std::ostringstream msg;
        msg << where << ": tissues: label " << label << " is mapped to more than one tissue";
        throw InputError(msg.str());
      }
    }
  }
  for (std::int32_t label : ignored_) {
    if (!label_to_tissue_.emplace(label, 0).second) {
      std::ostringstream msg;
      msg << where << ": ignore_labels: label " << label << " is also mapped to a tissue";
      throw InputError(msg.str());
    }
  }
}

TissueTable TissueTable::from_config(YamlMap& top) {
  YAML::Node list = top.raw("tissues");
  const std::string where = top.where("tissues");
  if (!list.IsDefined() || list.IsNull())
    throw InputError(where + ": required key is missing (a list of {name, labels})");
  if (!list.IsSequence())
    throw InputError(where + ": expected a list of {name: ..., labels: [...]}");
  std::vector<Tissue> tissues;
  for (std::size_t i = 0; i < list.size(); ++i) {
    YamlMap entry(list[i], "tissues[" + std::to_string(i) + "]", top.source());
    Tissue t;
    t.name = entry.required_text("name");
    std::vector<int> labels = entry.integers("labels", {});
    t.labels.assign(labels.begin(), labels.end());
    entry.finish();
    tissues.push_back(std::move(t));
  }
  std::vector<int> ignored = top.integers("ignore_labels", {0});
  return TissueTable(std::move(tissues), {ignored.begin(), ignored.end()}, top.source());
}

void TissueTable::to_yaml(YAML::Emitter& out) const {
  out << YAML::Key << "tissues" << YAML::Value << YAML::BeginSeq;
  for (const Tissue& t : tissues_) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << t.name
        << YAML::Key << "labels" << YAML::Value << YAML::Flow << t.labels << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "ignore_labels" << YAML::Value << YAML::Flow << ignored_;
}

std::vector<std::string> TissueTable::names() const {
  std::vector<std::string> out;
  for (const Tissue& t : tissues_) out.push_back(t.name);
  return out;
}

int TissueTable::tissue_of_label(std::int32_t label) const {
  auto it = label_to_tissue_.find(label);
  return it == label_to_tissue_.end() ? -1 : it->second;
}

void TissueTable::check_against(const std::map<std::int32_t, std::size_t>& counts,
                                const std::string& what) const {
  for (const auto& [label, count] : counts) {
    if (tissue_of_label(label) < 0) {
      std::ostringstream msg;
      msg << what << ": label " << label << " (" << count
          << " voxels) is neither mapped to a tissue nor listed in ignore_labels";
      throw InputError(msg.str());
    }
  }
  for (const Tissue& t : tissues_) {
    std::size_t n = 0;
    for (std::int32_t label : t.labels) {
      auto it = counts.find(label);
      if (it != counts.end()) n += it->second;
    }
    if (n == 0) {
      std::ostringstream msg;
      msg << what << ": tissue '" << t.name << "' (labels";
      for (std::int32_t label : t.labels) msg << " " << label;
      msg << ") has no voxels in this image";
      throw InputError(msg.str());
    }
  }
}

LabelImage TissueTable::to_tissue_ids(const LabelImage& image) const {
  LabelImage out = image;
  // Most images hold few distinct labels: cache the last lookup.
  std::int32_t last_label = image.labels.empty() ? 0 : image.labels[0];
  std::int32_t last_id = tissue_of_label(last_label);
  for (auto& v : out.labels) {
    if (v != last_label) {
      last_label = v;
      last_id = tissue_of_label(v);
    }
    v = last_id < 0 ? 0 : last_id;
  }
  return out;
}

}  // namespace tissuemesh
