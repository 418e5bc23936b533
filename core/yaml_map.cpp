#include "core/yaml_map.h"

#include "core/errors.h"

#include <cmath>
#include <filesystem>
#include <set>
#include <fstream>
#include <sstream>

namespace tissuemesh {

YamlMap::YamlMap(YAML::Node node, std::string path, std::string source)
    : node_(std::move(node)), path_(std::move(path)), source_(std::move(source)) {
  if (node_.IsDefined() && !node_.IsNull() && !node_.IsMap()) {
    throw InputError(source_ + ": " + (path_.empty() ? std::string("top level") : path_) +
                     ": expected a mapping of keys");
  }
}

std::string YamlMap::where(const std::string& key) const {
  return source_ + ": " + (path_.empty() ? key : path_ + "." + key);
}

bool YamlMap::has(const std::string& key) const {
  return node_.IsMap() && node_[key].IsDefined() && !node_[key].IsNull();
}

YAML::Node YamlMap::scalar(const std::string& key, const char* expected) {
  read_.insert(key);
  YAML::Node v = node_.IsMap() ? node_[key] : YAML::Node();
  if (v.IsDefined() && !v.IsNull() && !v.IsScalar()) {
    throw InputError(where(key) + ": expected " + expected);
  }
  return v;
}

double YamlMap::number(const std::string& key, double fallback) {
  YAML::Node v = scalar(key, "a number");
  if (!v.IsDefined() || v.IsNull()) return fallback;
  try {
    double d = v.as<double>();
    if (!std::isfinite(d)) throw YAML::BadConversion(v.Mark());
    return d;
  } catch (const YAML::BadConversion&) {
    throw InputError(where(key) + ": expected a number, got '" + v.Scalar() + "'");
  }
}

int YamlMap::integer(const std::string& key, int fallback) {
  YAML::Node v = scalar(key, "an integer");
  if (!v.IsDefined() || v.IsNull()) return fallback;
  try {
    return v.as<int>();
  } catch (const YAML::BadConversion&) {
    throw InputError(where(key) + ": expected an integer, got '" + v.Scalar() + "'");
  }
}

bool YamlMap::boolean(const std::string& key, bool fallback) {
  YAML::Node v = scalar(key, "true or false");
  if (!v.IsDefined() || v.IsNull()) return fallback;
  try {
    return v.as<bool>();
  } catch (const YAML::BadConversion&) {
    throw InputError(where(key) + ": expected true or false, got '" + v.Scalar() + "'");
  }
}

std::string YamlMap::text(const std::string& key, const std::string& fallback) {
  YAML::Node v = scalar(key, "a text value");
  if (!v.IsDefined() || v.IsNull()) return fallback;
  return v.Scalar();
}

std::string YamlMap::required_text(const std::string& key) {
  if (!has(key)) throw InputError(where(key) + ": required key is missing");
  return text(key, "");
}

std::vector<int> YamlMap::integers(const std::string& key, const std::vector<int>& fallback) {
  read_.insert(key);
  YAML::Node v = node_.IsMap() ? node_[key] : YAML::Node();
  if (!v.IsDefined() || v.IsNull()) return fallback;
  std::vector<int> out;
  auto convert = [&](const YAML::Node& item) {
    try {
      out.push_back(item.as<int>());
    } catch (const YAML::Exception&) {
      throw InputError(where(key) + ": expected integers, got '" +
                       (item.IsScalar() ? item.Scalar() : std::string("a nested value")) + "'");
    }
  };
  if (v.IsScalar()) {
    convert(v);
  } else if (v.IsSequence()) {
    for (const auto& item : v) convert(item);
  } else {
    throw InputError(where(key) + ": expected an integer or a list of integers");
  }
  return out;
}

YamlMap YamlMap::map(const std::string& key) {
  read_.insert(key);
  YAML::Node v = node_.IsMap() ? node_[key] : YAML::Node();
  return YamlMap(v, path_.empty() ? key : path_ + "." + key, source_);
}

Eigen::Vector3d YamlMap::vector3(const std::string& key, const Eigen::Vector3d& fallback) {
  if (!has(key)) return fallback;
  YAML::Node node = raw(key);
  if (!node.IsSequence() || node.size() != 3) throw InputError(where(key) + ": expected a list of 3 numbers [x, y, z]");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    try {
      v[i] = node[i].as<double>();
    } catch (const YAML::Exception&) {
      throw InputError(where(key) + ": expected a list of 3 numbers, got '" + YAML::Dump(node) + "'");
    }
  }
  if (!v.allFinite()) throw InputError(where(key) + ": values must be finite");
  return v;
}

YAML::Node YamlMap::raw(const std::string& key) {
  read_.insert(key);
  return node_.IsMap() ? node_[key] : YAML::Node();
}

std::vector<std::string> YamlMap::keys() const {
  std::vector<std::string> out;
  if (!node_.IsMap()) return out;
  for (const auto& kv : node_) {
    if (!kv.first.IsScalar()) throw InputError(here() + "a key must be a name, not a list or a mapping");
    out.push_back(kv.first.Scalar());
  }
  return out;
}

void YamlMap::finish() const {
  std::vector<std::string> unknown;
  for (const auto& k : keys())
    if (!read_.count(k)) unknown.push_back(k);
  if (unknown.empty()) return;
  std::ostringstream msg;
  msg << where(unknown.front()) << ": unknown key";
  if (unknown.size() > 1) {
    msg << " (also unknown:";
    for (std::size_t i = 1; i < unknown.size(); ++i) msg << " '" << unknown[i] << "'";
    msg << ")";
  }
  msg << "; known keys here:";
  for (const auto& k : read_) msg << " " << k;
  throw InputError(msg.str());
}

double YamlMap::positive(const std::string& key, double fallback) {
  double v = number(key, fallback);
  if (!(v > 0.0)) {
    std::ostringstream msg;
    msg << where(key) << ": must be positive, got " << v;
    throw InputError(msg.str());
  }
  return v;
}

double YamlMap::in_range(const std::string& key, double fallback, double lo, double hi) {
  double v = number(key, fallback);
  if (!(v >= lo && v <= hi)) {
    std::ostringstream msg;
    msg << where(key) << ": must lie in [" << lo << ", " << hi << "], got " << v;
    throw InputError(msg.str());
  }
  return v;
}

namespace {

// Real configs hold a few hundred nodes; far more means aliases that expand exponentially
// ("billion laughs"), which every later walk over the document would pay for.
constexpr std::size_t kMaxYamlNodes = 100000;

// Walks the document once: counts nodes (aliases counted each time they are used) and refuses a
// mapping that repeats a key, which yaml-cpp keeps silently (lookups see only the first value).
void check_document(const YAML::Node& node, const std::string& path, std::size_t& count) {
  if (++count > kMaxYamlNodes) {
    throw InputError(path + ": more than " + std::to_string(kMaxYamlNodes) +
                     " YAML nodes once aliases are expanded (nested anchors and aliases?); a " +
                     "config holds a few hundred");
  }
  if (node.IsMap()) {
    std::set<std::string> keys;
    for (const auto& entry : node) {
      if (!entry.first.IsScalar()) {
        std::ostringstream msg;
        msg << path << ": line " << entry.first.Mark().line + 1
            << ": a key must be a name, not a list, a mapping or empty";
        throw InputError(msg.str());
      }
      if (!keys.insert(entry.first.Scalar()).second) {
        std::ostringstream msg;
        msg << path << ": duplicate key '" << entry.first.Scalar() << "' at line "
            << entry.first.Mark().line + 1 << " (each key may appear once in a mapping)";
        throw InputError(msg.str());
      }
      check_document(entry.first, path, count);
      check_document(entry.second, path, count);
    }
  } else if (node.IsSequence()) {
    for (const auto& item : node) check_document(item, path, count);
  }
}

}  // namespace

YAML::Node load_yaml_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError(path + (std::filesystem::exists(path, ec) ? ": is not a regular file"
                                                               : ": cannot open config file"));
  }
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open config file");
  YAML::Node root;
  try {
    root = YAML::Load(in);
  } catch (const YAML::ParserException& e) {
    std::ostringstream msg;
    msg << path << ": invalid YAML at line " << e.mark.line + 1 << ", column "
        << e.mark.column + 1 << ": " << e.msg;
    throw InputError(msg.str());
  } catch (const YAML::Exception& e) {
    throw InputError(path + ": invalid YAML: " + e.what());
  }
  if (!root.IsMap()) throw InputError(path + ": the config must be a mapping of keys");
  std::size_t count = 0;
  check_document(root, path, count);
  return root;
}

}  // namespace tissuemesh
