#include "core/vtk_xml_guard.h"

#include "core/errors.h"

#include <algorithm>
#include <fstream>
#include <iterator>

namespace tissuemesh {
namespace {

// The array types VTK's XML writers write and its readers make (vtkXMLDataElement's type names).
bool known_array_type(const std::string& type) {
  static const char* const kTypes[] = {"Int8",  "UInt8",  "Int16",   "UInt16",  "Int32",  "UInt32",
                                       "Int64", "UInt64", "Float32", "Float64", "String"};
  return std::find(std::begin(kTypes), std::end(kTypes), type) != std::end(kTypes);
}

// The value of attribute `name` in the start tag `tag`, or "" (also for an attribute only ending
// in `name`, such as "Scalars" for "type").
std::string attribute(const std::string& tag, const std::string& name) {
  for (std::size_t at = tag.find(name + "=\""); at != std::string::npos;
       at = tag.find(name + "=\"", at + 1)) {
    if (at > 0 && tag[at - 1] != ' ' && tag[at - 1] != '\t' && tag[at - 1] != '\n' &&
        tag[at - 1] != '\r') {
      continue;
    }
    const std::size_t begin = at + name.size() + 2;
    const std::size_t end = tag.find('"', begin);
    return end == std::string::npos ? std::string() : tag.substr(begin, end - begin);
  }
  return "";
}

void check_array_types(const std::string& xml, const std::string& path) {
  for (const char* element : {"<DataArray", "<Array"}) {
    for (std::size_t at = xml.find(element); at != std::string::npos; at = xml.find(element, at + 1)) {
      const std::size_t end = xml.find('>', at);
      const std::string tag = xml.substr(at, end == std::string::npos ? std::string::npos : end - at);
      const std::string type = attribute(tag, "type");
      if (!known_array_type(type)) {
        throw InputError(path + ": a " + std::string(element + 1) + " has " +
                         (type.empty() ? "no type" : "the unknown type '" + type + "'") +
                         " (corrupt or not written by VTK)");
      }
    }
  }
}

}  // namespace

std::string vtk_xml_text_to_read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open file");
  // The XML part: everything before appended binary data.
  std::string text, chunk(1 << 16, '\0');
  std::size_t appended = std::string::npos;
  while (appended == std::string::npos) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    if (in.gcount() <= 0) break;
    const std::size_t from = text.size() > 13 ? text.size() - 13 : 0;
    text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    appended = text.find("<AppendedData", from);
  }
  const std::string xml = text.substr(0, appended);
  check_array_types(xml, path);

  const std::size_t cell_data = xml.find("<CellData");
  if (cell_data == std::string::npos || xml.rfind("<PointData", cell_data) != std::string::npos) return "";
  text.append(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  const std::string empty = "<PointData></PointData>";
  for (std::size_t at = text.find("<CellData"); at != std::string::npos && at < appended;
       at = text.find("<CellData", at + empty.size() + 1)) {
    text.insert(at, empty);
    if (appended != std::string::npos) appended += empty.size();
  }
  return text;
}

}  // namespace tissuemesh
