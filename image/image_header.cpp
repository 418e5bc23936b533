// Why: VTK 9.1's readers drop or guess parts of the geometry (vtkNrrdReader keeps only the lengths
// of `space directions`, treats a fast axis of <= 9 voxels as vector components and flips rows for
// LAS space; vtkMetaImageReader ignores TransformMatrix), so the headers are parsed here; VTK
// reads the NIfTI and NRRD voxel bytes, and the MetaImage ones are read by read_voxel_bytes
// (image/voxel_bytes.h) from what this parser found.
#include "image/image_header.h"

#include "core/errors.h"
#include "core/memory_budget.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <sstream>
#include <type_traits>
#include <vector>

namespace tissuemesh {
namespace {

// Real headers are a few hundred bytes; the cap keeps a mistaken multi-gigabyte file from being
// read whole while looking for a header end that is not there.
constexpr std::size_t kMaxHeaderBytes = 1 << 20;

std::string trim(const std::string& s) {
  const auto space = [](unsigned char c) { return std::isspace(c) != 0; };
  auto begin = std::find_if_not(s.begin(), s.end(), space);
  auto end = std::find_if_not(s.rbegin(), s.rend(), space).base();
  return begin < end ? std::string(begin, end) : std::string();
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::vector<std::string> split_ws(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> tokens;
  for (std::string t; in >> t;) tokens.push_back(t);
  return tokens;
}

// The fields of one header by name, and typed parsing whose errors name the file and the field.
// Names are matched in lower case without spaces, so NRRD's "data file" and "datafile", or
// MetaIO's "NDims" and "ndims", are the same field.
class Fields {
 public:
  explicit Fields(const std::string& path) : path_(path) {}
  const std::string& path() const { return path_; }

  [[noreturn]] void fail(const std::string& what) const { throw InputError(path_ + ": " + what); }

  void set(const std::string& name, const std::string& value) { values_[key(name)] = trim(value); }
  /// As set, but a field given before (in any spelling that matches) is an error naming the
  /// `format`: NRRD forbids it, and other readers (VTK's, MetaIO) take the first where this parser
  /// would keep the last.
  void set_once(const char* format, const std::string& name, const std::string& value) {
    if (values_.count(key(name))) {
      fail(std::string(format) + " field '" + trim(name) + "' is given more than once");
    }
    set(name, value);
  }

  /// The value of the first of `names` present, or nullptr.
  const std::string* find(std::initializer_list<const char*> names) const {
    for (const char* name : names) {
      auto it = values_.find(key(name));
      if (it != values_.end()) return &it->second;
    }
    return nullptr;
  }

  const std::string& require(const char* name) const {
    const std::string* value = find({name});
    if (value == nullptr) fail(std::string("header lacks the required field '") + name + "'");
    return *value;
  }

  template <typename T>
  T number(const std::string& token, const char* field) const {
    T value{};
    const char* end = token.data() + token.size();
    const auto [stop, error] = std::from_chars(token.data(), end, value);
    if (token.empty() || error != std::errc() || stop != end ||
        !std::isfinite(static_cast<double>(value))) {
      fail(std::string("field '") + field + "': '" + token + "' is not " +
           (std::is_integral_v<T> ? "an integer" : "a finite number"));
    }
    return value;
  }

  /// `value` split at whitespace into exactly `count` tokens.
  std::vector<std::string> tokens(const std::string& value, std::size_t count,
                                  const char* field) const {
    std::vector<std::string> t = split_ws(value);
    if (t.size() != count) {
      fail(std::string("field '") + field + "' has " + std::to_string(t.size()) +
           " values, expected " + std::to_string(count));
    }
    return t;
  }

  /// `count` numbers separated by whitespace.
  std::vector<double> numbers(const std::string& value, std::size_t count,
                              const char* field) const {
    std::vector<double> v;
    for (const std::string& token : tokens(value, count, field)) {
      v.push_back(number<double>(token, field));
    }
    return v;
  }

  Eigen::Vector3d vector3(const std::string& value, const char* field) const {
    return Eigen::Vector3d(numbers(value, 3, field).data());
  }

  std::array<int, 3> dims(const std::vector<std::string>& tokens, const char* field) const {
    std::array<int, 3> dims{};
    for (int a = 0; a < 3; ++a) {
      dims[a] = number<int>(tokens[a], field);
      if (dims[a] <= 0) fail(std::string("field '") + field + "': sizes must be positive");
    }
    return dims;
  }

  bool boolean(const std::string& value, const char* field) const {
    const std::string v = lower(value);
    if (v != "true" && v != "false" && v != "1" && v != "0") {
      fail(std::string("field '") + field + "': '" + value + "' is not True or False");
    }
    return v == "true" || v == "1";
  }

  /// A data file name from the header; relative names are relative to the header's folder (NRRD
  /// and MetaIO agree). Lists and patterns of files are refused.
  std::string data_file(const std::string& name) const {
    if (split_ws(name).size() != 1 || name.find('%') != std::string::npos) {
      fail("data file '" + name + "' lists several files; only a single data file is supported");
    }
    std::filesystem::path file(name);
    return file.is_absolute() ? name : (std::filesystem::path(path_).parent_path() / file).string();
  }

 private:
  static std::string key(const std::string& name) {
    std::string k = lower(name);
    k.erase(std::remove(k.begin(), k.end(), ' '), k.end());
    return k;
  }
  const std::string& path_;
  std::map<std::string, std::string> values_;
};

// The leading bytes of a file (at most kMaxHeaderBytes), split into lines ("\n" or "\r\n").
// `offset()` is the byte position just after the last line returned: where attached data starts.
class LineReader {
 public:
  explicit LineReader(const Fields& fields) : fields_(fields) {
    std::ifstream in(fields.path(), std::ios::binary);
    if (!in) fields.fail("cannot open file");
    text_.resize(kMaxHeaderBytes);
    in.read(text_.data(), static_cast<std::streamsize>(text_.size()));
    text_.resize(static_cast<std::size_t>(in.gcount()));
  }
  bool starts_with(const char* magic) const { return text_.rfind(magic, 0) == 0; }
  bool next(std::string& line) {
    if (pos_ >= text_.size()) return false;
    const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
    line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (std::any_of(line.begin(), line.end(),
                    [](unsigned char c) { return c < 0x20 && c != '\t'; })) {
      fields_.fail("header holds binary bytes where text was expected (corrupt or not a header)");
    }
    return true;
  }
  std::int64_t offset() const { return static_cast<std::int64_t>(std::min(pos_, text_.size())); }

 private:
  const Fields& fields_;
  std::string text_;
  std::size_t pos_ = 0;
};

// ---------------------------------------------------------------------------------------- NRRD

VoxelType nrrd_type(const std::string& name, const Fields& f) {
  static const std::pair<VoxelType, std::vector<std::string>> kNames[] = {
      {VoxelType::kInt8, {"signed char", "int8", "int8_t"}},
      {VoxelType::kUInt8, {"uchar", "unsigned char", "uint8", "uint8_t"}},
      {VoxelType::kInt16,
       {"short", "short int", "signed short", "signed short int", "int16", "int16_t"}},
      {VoxelType::kUInt16,
       {"ushort", "unsigned short", "unsigned short int", "uint16", "uint16_t"}},
      {VoxelType::kInt32, {"int", "signed int", "int32", "int32_t"}},
      {VoxelType::kUInt32, {"uint", "unsigned int", "uint32", "uint32_t"}},
      {VoxelType::kInt64,
       {"longlong", "long long", "long long int", "signed long long", "signed long long int",
        "int64", "int64_t"}},
      {VoxelType::kUInt64,
       {"ulonglong", "unsigned long long", "unsigned long long int", "uint64", "uint64_t"}},
      {VoxelType::kFloat32, {"float"}},
      {VoxelType::kFloat64, {"double"}}};
  for (const auto& [type, names] : kNames) {
    if (std::find(names.begin(), names.end(), name) != names.end()) return type;
  }
  f.fail("NRRD type '" + name + "' is not a known voxel type");
}

// LPS-from-space matrix of the anatomical NRRD spaces; other spaces have no patient frame.
Eigen::Matrix3d nrrd_space_to_lps(const std::string& space, const Fields& f) {
  const std::string s = lower(space);
  if (s == "left-posterior-superior" || s == "lps") return Eigen::Matrix3d::Identity();
  if (s == "right-anterior-superior" || s == "ras") return ras_lps_flip();
  if (s == "left-anterior-superior" || s == "las") return Eigen::Vector3d(1, -1, 1).asDiagonal();
  f.fail("NRRD space '" + space + "' is not supported (supported: left-posterior-superior, " +
         "right-anterior-superior, left-anterior-superior), so patient orientation is unknown");
}

// "(a,b,c) none (d,e,f) ..." -> the vectors without their parentheses, and "none" (a non-spatial
// axis). Vectors may hold spaces after commas, so they are cut at parentheses, not whitespace.
std::vector<std::string> nrrd_vectors(const std::string& value, const Fields& f,
                                      const char* field) {
  std::vector<std::string> tokens;
  for (std::size_t pos = value.find_first_not_of(" \t"); pos != std::string::npos;
       pos = value.find_first_not_of(" \t", pos)) {
    if (value[pos] == '(') {
      const std::size_t close = value.find(')', pos);
      if (close == std::string::npos) f.fail(std::string("field '") + field + "': unclosed '('");
      tokens.push_back(value.substr(pos + 1, close - pos - 1));
      pos = close + 1;
    } else if (value.compare(pos, 4, "none") == 0) {
      tokens.emplace_back("none");
      pos += 4;
    } else {
      f.fail(std::string("field '") + field + "': unexpected text '" + value.substr(pos) + "'");
    }
  }
  return tokens;
}

// "x,y,z" (a vector without parentheses) -> 3 numbers.
Eigen::Vector3d nrrd_vector(std::string text, const Fields& f, const char* field) {
  std::replace(text.begin(), text.end(), ',', ' ');
  return f.vector3(text, field);
}

// The axis of a 4-D NRRD that holds components: marked "none" in `space directions`, else the
// first whose `kinds` is neither "domain" nor "space", else axis 0 (interleaved components).
std::size_t nrrd_component_axis(const Fields& f, const std::vector<std::string>& directions) {
  if (!directions.empty()) {
    const auto none = std::find(directions.begin(), directions.end(), "none");
    if (none == directions.end()) f.fail("NRRD file has 4 axes but none is a component axis");
    return static_cast<std::size_t>(none - directions.begin());
  }
  if (const std::string* kinds_field = f.find({"kinds"})) {
    const std::vector<std::string> kinds = f.tokens(lower(*kinds_field), 4, "kinds");
    for (std::size_t a = 0; a < 4; ++a) {
      if (kinds[a] != "domain" && kinds[a] != "space") return a;
    }
  }
  return 0;
}

}  // namespace

// -------------------------------------------------------------------------------- shared helpers

const char* voxel_type_name(VoxelType type) {
  static const char* const kNames[] = {"int8",   "uint8", "int16",  "uint16",  "int32",
                                       "uint32", "int64", "uint64", "float32", "float64"};
  return kNames[static_cast<int>(type)];
}

std::size_t voxel_type_bytes(VoxelType type) {
  static const std::size_t kBytes[] = {1, 1, 2, 2, 4, 4, 8, 8, 4, 8};
  return kBytes[static_cast<int>(type)];
}

Eigen::Matrix3d ras_lps_flip() { return Eigen::Vector3d(-1, -1, 1).asDiagonal(); }

std::uint64_t checked_data_bytes(const std::array<int, 3>& dims, std::uint64_t components,
                                 std::uint64_t value_bytes, const std::string& path) {
  const std::string what = path + ": header sizes " + std::to_string(dims[0]) + " x " +
                           std::to_string(dims[1]) + " x " + std::to_string(dims[2]) +
                           " voxels x " + std::to_string(components) + " component(s) x " +
                           std::to_string(value_bytes) + " bytes";
  std::uint64_t bytes = value_bytes;
  for (std::uint64_t factor : {static_cast<std::uint64_t>(dims[0]),
                               static_cast<std::uint64_t>(dims[1]),
                               static_cast<std::uint64_t>(dims[2]), components}) {
    bytes = checked_multiply(bytes, factor, what);
  }
  return bytes;
}

void set_axis_steps(LabelImage& geometry, const Eigen::Matrix3d& axis_steps,
                    const std::string& what) {
  for (int c = 0; c < 3; ++c) {
    const double length = axis_steps.col(c).norm();
    if (!std::isfinite(length) || length == 0.0) {
      throw InputError(what + ": the step along voxel axis " + std::to_string(c) +
                       " is zero or not finite, so the voxel spacing is undefined");
    }
    geometry.spacing[c] = length;
    geometry.direction.col(c) = axis_steps.col(c) / length;
  }
}

// ---------------------------------------------------------------------------------------- NRRD

ImageHeader read_nrrd_header(const std::string& path) {
  Fields f(path);
  LineReader lines(f);
  if (!lines.starts_with("NRRD")) f.fail("not a NRRD file (no 'NRRD' magic at its start)");
  std::string line;
  lines.next(line);    // magic
  bool ended = false;  // by the blank line after which attached data starts
  while (!ended && lines.next(line)) {
    ended = line.empty();
    const std::size_t colon = line.find(": "), key_value = line.find(":=");
    if (ended || line[0] == '#' || key_value < colon) continue;  // comment or "key:=value"
    if (colon == std::string::npos) f.fail("NRRD header line '" + line + "' is not 'field: value'");
    f.set_once("NRRD", line.substr(0, colon), line.substr(colon + 2));
  }

  ImageHeader h;
  const auto n_axes = f.number<std::size_t>(f.require("dimension"), "dimension");
  if (n_axes != 3 && n_axes != 4) {
    f.fail("NRRD dimension " + std::to_string(n_axes) +
           " is not supported (3 spatial axes, optionally one component axis)");
  }
  h.type = nrrd_type(f.require("type"), f);
  const std::string encoding = lower(f.require("encoding"));
  h.compressed = encoding == "gzip" || encoding == "gz";
  if (!h.compressed && encoding != "raw") {
    f.fail("NRRD encoding '" + encoding + "' is not supported (supported: raw, gzip)");
  }
  if (voxel_type_bytes(h.type) > 1) {
    const std::string endian = lower(f.require("endian"));
    if (endian != "little" && endian != "big") f.fail("NRRD endian '" + endian + "' is unknown");
    h.big_endian = endian == "big";
  }
  for (const char* skip : {"byte skip", "line skip"}) {
    const std::string* value = f.find({skip});
    if (value && f.number<long long>(*value, skip) != 0) {
      f.fail(std::string("NRRD '") + skip + "' other than 0 is not supported");
    }
  }
  if (const std::string* units = f.find({"space units"})) {
    for (const std::string& unit : split_ws(*units)) {
      if (unit != "\"mm\"" && unit != "mm") f.fail("NRRD space units " + *units + " are not mm");
    }
  }

  // Axes: the spatial ones, and the component axis of a 4-D file.
  const std::vector<std::string> sizes = f.tokens(f.require("sizes"), n_axes, "sizes");
  std::vector<std::string> directions;
  if (const std::string* value = f.find({"space directions"})) {
    directions = nrrd_vectors(*value, f, "space directions");
    if (directions.size() != n_axes) {
      f.fail("field 'space directions' has " + std::to_string(directions.size()) +
             " entries, expected " + std::to_string(n_axes));
    }
  }
  const std::size_t component_axis = n_axes == 4 ? nrrd_component_axis(f, directions) : 3;
  if (n_axes == 4) {
    h.components = f.number<int>(sizes[component_axis], "sizes");
    if (h.components <= 0) f.fail("field 'sizes': the component axis size must be positive");
  }
  std::vector<std::size_t> spatial;
  for (std::size_t a = 0; a < n_axes; ++a) {
    if (a != component_axis) spatial.push_back(a);
  }
  h.geometry.dims = f.dims({sizes[spatial[0]], sizes[spatial[1]], sizes[spatial[2]]}, "sizes");

  // Geometry, from the declared space to LPS.
  const std::string* space = f.find({"space"});
  if (space == nullptr &&
      (f.find({"space dimension"}) || !directions.empty() || f.find({"space origin"}))) {
    f.fail(
        "NRRD header places the image in space but names no anatomical 'space', so patient "
        "orientation is unknown");
  }
  // VTK's reader sizes its axis lists by this number as it goes: only 3 is a 3-D patient space.
  if (const std::string* dimension = f.find({"space dimension"})) {
    if (f.number<long long>(*dimension, "space dimension") != 3)
      f.fail("NRRD 'space dimension' " + *dimension + " is not 3");
  }
  const Eigen::Matrix3d to_lps = space ? nrrd_space_to_lps(*space, f) : Eigen::Matrix3d::Identity();
  // Without directions the axes are those of the space, `spacings` (default 1 mm) apart.
  Eigen::Matrix3d steps = Eigen::Matrix3d::Identity();
  const std::string* spacings = f.find({"spacings"});
  for (int c = 0; c < 3; ++c) {
    if (!directions.empty()) {
      const std::string& token = directions[spatial[c]];
      if (token == "none") f.fail("field 'space directions': a spatial axis has 'none'");
      steps.col(c) = nrrd_vector(token, f, "space directions");
    } else if (spacings != nullptr) {
      steps(c, c) =
          f.number<double>(f.tokens(*spacings, n_axes, "spacings")[spatial[c]], "spacings");
    }
  }
  set_axis_steps(h.geometry, to_lps * steps, path);
  if (const std::string* origin = f.find({"space origin"})) {
    const std::vector<std::string> vector = nrrd_vectors(*origin, f, "space origin");
    if (vector.size() != 1 || vector[0] == "none") f.fail("field 'space origin' is not '(x,y,z)'");
    h.geometry.origin = to_lps * nrrd_vector(vector[0], f, "space origin");
  }

  // Data: one detached file, or the bytes after the blank line that ends the header.
  if (const std::string* data_file = f.find({"data file"})) {
    h.data_file = f.data_file(*data_file);
  } else if (ended) {
    h.data_file = path;
    h.data_offset = lines.offset();
  } else {
    f.fail(
        "NRRD header is not ended by a blank line and names no 'data file', so it holds no "
        "voxel data (truncated or corrupt)");
  }
  checked_data_bytes(h.geometry.dims, h.components, voxel_type_bytes(h.type), path);
  return h;
}

// ----------------------------------------------------------------------------------- MetaImage

// MetaIO, the format's reference reader (ITK, VTK, 3D Slicer), copies a field's name and text
// values such as Name, Comment and ObjectSubType into 255-byte buffers without a bound, so a
// longer one overruns them; such a file is refused rather than passed on in a mesh's provenance.
// Real headers stay far below: nine full-precision numbers of a TransformMatrix take about 190
// characters. ElementDataFile is held in a string and may be longer (a deep path).
constexpr std::size_t kMetaioMaxText = 254;

void require_metaio_field_size(const Fields& f, const std::string& name, const std::string& value) {
  const std::string key = trim(name);
  const std::size_t start = value.find_first_not_of(" \t");
  const std::size_t size = start == std::string::npos ? 0 : value.size() - start;
  const auto too_long = [&](const std::string& what, std::size_t length) {
    f.fail("MetaImage field " + what + " is " + std::to_string(length) +
           " characters long; MetaIO-based tools (ITK, VTK, 3D Slicer) read at most " +
           std::to_string(kMetaioMaxText));
  };
  if (key.size() > kMetaioMaxText) too_long("name '" + key.substr(0, 40) + "...'", key.size());
  if (size > kMetaioMaxText && lower(key) != "elementdatafile") too_long("'" + key + "'", size);
}

ImageHeader read_metaimage_header(const std::string& path) {
  Fields f(path);
  LineReader lines(f);
  std::string line;
  bool data_file_found = false;  // ElementDataFile is by MetaIO's rule the last field
  while (!data_file_found && lines.next(line)) {
    if (trim(line).empty()) continue;
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos)
      f.fail("MetaImage header line '" + line + "' is not 'Key = Value'");
    require_metaio_field_size(f, line.substr(0, eq), line.substr(eq + 1));
    f.set_once("MetaImage", line.substr(0, eq), line.substr(eq + 1));
    data_file_found = f.find({"ElementDataFile"}) != nullptr;
  }
  if (!data_file_found) f.fail("MetaImage header has no ElementDataFile (truncated or corrupt)");

  ImageHeader h;
  if (const std::string* object = f.find({"ObjectType"}); object && lower(*object) != "image") {
    f.fail("MetaImage ObjectType '" + *object + "' is not Image");
  }
  if (f.number<int>(f.require("NDims"), "NDims") != 3) {
    f.fail("MetaImage NDims " + f.require("NDims") + " is not supported; a label image has 3");
  }
  h.geometry.dims = f.dims(f.tokens(f.require("DimSize"), 3, "DimSize"), "DimSize");
  static const std::map<std::string, VoxelType> kTypes = {
      {"met_char", VoxelType::kInt8},       {"met_uchar", VoxelType::kUInt8},
      {"met_short", VoxelType::kInt16},     {"met_ushort", VoxelType::kUInt16},
      {"met_int", VoxelType::kInt32},       {"met_uint", VoxelType::kUInt32},
      {"met_long", VoxelType::kInt32},      {"met_ulong", VoxelType::kUInt32},  // 4 bytes in MetaIO
      {"met_long_long", VoxelType::kInt64}, {"met_ulong_long", VoxelType::kUInt64},
      {"met_float", VoxelType::kFloat32},   {"met_double", VoxelType::kFloat64}};
  const std::string& type = f.require("ElementType");
  const auto known = kTypes.find(lower(type));
  if (known == kTypes.end()) f.fail("MetaImage ElementType '" + type + "' is not a known type");
  h.type = known->second;

  if (const std::string* channels = f.find({"ElementNumberOfChannels"})) {
    h.components = f.number<int>(*channels, "ElementNumberOfChannels");
    if (h.components <= 0) f.fail("MetaImage ElementNumberOfChannels must be positive");
  }
  if (const std::string* binary = f.find({"BinaryData"});
      binary && !f.boolean(*binary, "BinaryData")) {
    f.fail("MetaImage BinaryData = False (ASCII voxel values) is not supported");
  }
  if (const std::string* msb = f.find({"BinaryDataByteOrderMSB", "ElementByteOrderMSB"})) {
    h.big_endian = f.boolean(*msb, "BinaryDataByteOrderMSB");
  }
  if (const std::string* compressed = f.find({"CompressedData"})) {
    h.compressed = f.boolean(*compressed, "CompressedData");
  }
  if (const std::string* size = f.find({"CompressedDataSize"})) {
    h.compressed_size = f.number<std::int64_t>(*size, "CompressedDataSize");
    // MetaIO allocates this many bytes as given: a negative size becomes 2^64 - n.
    if (h.compressed_size < 0) f.fail("MetaImage CompressedDataSize must be at least 0");
  }

  // Geometry, already LPS. TransformMatrix follows ITK's MetaImageIO, which writes
  // matrix[3*a + r] = GetDirection(a)[r] (itkMetaImageIO.cxx, WriteImageInformation): the first
  // three numbers are the unit LPS vector of the i axis, the next three that of j, then k.
  if (const std::string* spacing = f.find({"ElementSpacing"})) {
    h.geometry.spacing = f.vector3(*spacing, "ElementSpacing");
  }
  if (const std::string* offset = f.find({"Offset", "Position", "Origin"})) {
    h.geometry.origin = f.vector3(*offset, "Offset");
  }
  if (const std::string* matrix = f.find({"TransformMatrix", "Rotation", "Orientation"})) {
    const std::vector<double> m = f.numbers(*matrix, 9, "TransformMatrix");
    h.geometry.direction = Eigen::Map<const Eigen::Matrix3d>(m.data());  // column-major
  }

  const std::string& data_file = f.require("ElementDataFile");
  // MetaIO's own spellings of "the data follow the header", and only these: any other spelling
  // (e.g. "LoCAL") is a file name to MetaIO, so it must be one here too.
  if (data_file == "LOCAL" || data_file == "Local" || data_file == "local") {
    h.data_file = path;
    h.data_offset = lines.offset();
  } else {
    h.data_file = f.data_file(data_file);
    if (const std::string* header_size = f.find({"HeaderSize"})) {
      h.data_offset = f.number<std::int64_t>(*header_size, "HeaderSize");
      if (h.data_offset < -1) f.fail("MetaImage HeaderSize must be -1 or at least 0");
    }
  }
  checked_data_bytes(h.geometry.dims, h.components, voxel_type_bytes(h.type), path);
  return h;
}

}  // namespace tissuemesh
