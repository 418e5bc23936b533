// YamlMap: strict, typed access to one YAML mapping of a config file.
//
// Every key read is remembered; `finish()` throws InputError for any key that was not read, so that
// a typo ("facet_sise_mm") is an error and not a silently ignored setting. Errors name the file and
// the full key path ("configs/phantom.yaml: direct.cell_size_mm: expected a number, got 'big'").
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>

#include <set>
#include <string>
#include <vector>

namespace tissuemesh {

class YamlMap {
 public:
  /// `node` must be a map (or null/undefined = empty map); `path` is the key path of the node
  /// ("" at top level), `source` the file name used in messages.
  YamlMap(YAML::Node node, std::string path, std::string source);

  bool has(const std::string& key) const;
  /// Typed value of `key`, or `fallback` when absent. Throws InputError on a wrong type.
  double number(const std::string& key, double fallback);
  int integer(const std::string& key, int fallback);
  bool boolean(const std::string& key, bool fallback);
  std::string text(const std::string& key, const std::string& fallback);
  std::vector<int> integers(const std::string& key, const std::vector<int>& fallback);
  /// A list of 3 finite numbers [x, y, z], or `fallback` when absent.
  Eigen::Vector3d vector3(const std::string& key, const Eigen::Vector3d& fallback);
  /// Same, with a required key.
  std::string required_text(const std::string& key);

  /// A nested mapping (empty if absent); its own finish() must be called by the caller.
  YamlMap map(const std::string& key);
  /// The raw node of `key` (marks it as read); for lists of maps.
  YAML::Node raw(const std::string& key);
  /// Keys of this map in document order.
  std::vector<std::string> keys() const;

  /// "<source>: <path.key>" for messages.
  std::string where(const std::string& key) const;
  const std::string& source() const { return source_; }
  const std::string& path() const { return path_; }
  /// "<source>: <path>: " — the prefix of a message about this map as a whole.
  std::string here() const { return source_ + ": " + (path_.empty() ? std::string("(top level)") : path_) + ": "; }

  /// Throws InputError naming every unknown key and listing the known ones.
  void finish() const;

  /// Helpers for range checks; they throw InputError naming the key and the rule.
  double positive(const std::string& key, double fallback);
  double in_range(const std::string& key, double fallback, double lo, double hi);

 private:
  YAML::Node node_;
  std::string path_;
  std::string source_;
  std::set<std::string> read_;
  YAML::Node scalar(const std::string& key, const char* expected);
};

/// Loads a YAML file; throws InputError naming the file (missing, not a regular file, unreadable,
/// the parser's line/column on a syntax error, a key repeated in a mapping with its line, or more
/// than 100,000 nodes once aliases are expanded). The top level must be a mapping.
YAML::Node load_yaml_file(const std::string& path);

}  // namespace tissuemesh
