#include "solver_check/calculix_dat.h"

#include "core/errors.h"

#include <cctype>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

namespace tissuemesh {

namespace {

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

/// A Fortran real as printed by ccx: "1.234E+01", "1.234D+01", and for 3-digit exponents the
/// E-less form "1.234+100" / "1.234-100". False when `text` is not a number.
bool fortran_real(std::string text, double& value) {
  for (char& c : text)
    if (c == 'D' || c == 'd') c = 'E';
  if (text.find_first_of("Ee") == std::string::npos) {
    const std::size_t sign = text.find_last_of("+-");
    if (sign != std::string::npos && sign > 0 && std::isdigit(static_cast<unsigned char>(text[sign - 1])))
      text.insert(sign, "E");
  }
  const char* begin = text.c_str();
  char* end = nullptr;
  value = std::strtod(begin, &end);
  return end != begin && *end == '\0';
}

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> w;
  for (std::string s; in >> s;) w.push_back(s);
  return w;
}

}  // namespace

std::vector<DatBlock> read_calculix_dat(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot read CalculiX results '" + path + "'");
  // As ccx 2.20 prints it: ' displacements (vx,vy,vz) for set NALL and time  0.1000000E+01',
  // then node rows (i10, 3(1x,e13.6)) [' L' for local axes]; TOTALS=YES adds ' total force
  // (fx,fy,fz) for set S and time t' followed by one row of three values without a node number.
  static const std::regex kHeader(R"(^\s*(\S.*?)\s*\(([^)]*)\)\s*for set\s+(\S+)\s+and time\s+(\S+)\s*$)");
  enum class Mode { None, Rows, Total, Skip } mode = Mode::None;
  std::vector<DatBlock> blocks;
  DatBlock* total_of = nullptr;
  std::string line;
  int line_no = 0;
  auto malformed = [&](const std::string& why) {
    return InputError("CalculiX results '" + path + "' line " + std::to_string(line_no) + ": " + why);
  };
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::smatch m;
    if (std::regex_match(line, m, kHeader)) {
      double time = 0.0;
      if (!fortran_real(m[4].str(), time)) throw malformed("bad time '" + m[4].str() + "'");
      const std::string quantity = m[1].str(), set = upper(m[3].str());
      const bool vector = words(std::regex_replace(m[2].str(), std::regex(","), " ")).size() == 3;
      if (quantity.rfind("total", 0) == 0) {
        // The summary of the block just printed for the same set and time.
        total_of = nullptr;
        for (auto it = blocks.rbegin(); it != blocks.rend(); ++it)
          if (it->set == set && it->time == time) {
            total_of = &*it;
            break;
          }
        if (!total_of) throw malformed("'" + quantity + "' for set " + set + " without its block");
        mode = vector ? Mode::Total : Mode::Skip;
      } else if (vector) {
        DatBlock b;
        b.quantity = quantity;
        b.set = set;
        b.time = time;
        blocks.push_back(b);
        mode = Mode::Rows;
      } else {
        mode = Mode::Skip;  // stresses, strains, ...: not 3-component node values
      }
      continue;
    }
    std::vector<std::string> w = words(line);
    if (w.empty()) continue;
    if (mode == Mode::Rows) {
      if (w.size() == 5 && w[4] == "L") w.pop_back();  // local axes marker
      char* end = nullptr;
      const long id = std::strtol(w[0].c_str(), &end, 10);
      if (w.size() == 4 && *end == '\0' && id > 0) {
        Eigen::Vector3d v;
        for (int k = 0; k < 3; ++k)
          if (!fortran_real(w[k + 1], v[k])) throw malformed("bad number '" + w[k + 1] + "'");
        blocks.back().values[static_cast<int>(id)] = v;
        continue;
      }
      if (blocks.back().values.empty()) throw malformed("block without node rows");
      mode = Mode::None;  // anything else (a banner of newer ccx versions) ends the block
    } else if (mode == Mode::Total) {
      if (w.size() != 3) throw malformed("total line needs 3 values");
      for (int k = 0; k < 3; ++k)
        if (!fortran_real(w[k], total_of->total[k])) throw malformed("bad number '" + w[k] + "'");
      total_of->has_total = true;
      mode = Mode::None;
    }
  }
  if (in.bad()) throw InputError("reading CalculiX results '" + path + "' failed");
  if (mode == Mode::Rows && blocks.back().values.empty())
    throw InputError("CalculiX results '" + path + "': the last block has no node rows (truncated file?)");
  if (mode == Mode::Total) throw InputError("CalculiX results '" + path + "': total line missing (truncated file?)");
  return blocks;
}

const DatBlock& last_block(const std::vector<DatBlock>& blocks, const std::string& quantity, const std::string& set) {
  const DatBlock* best = nullptr;
  const std::string wanted = upper(set);
  for (const DatBlock& b : blocks)
    if (b.quantity == quantity && b.set == wanted && (!best || b.time >= best->time)) best = &b;
  if (!best) throw InputError("CalculiX results: no '" + quantity + "' block for set " + wanted);
  return *best;
}

std::vector<Eigen::Vector3d> values_by_node(const DatBlock& block, std::size_t num_nodes) {
  const std::string what = "CalculiX results: '" + block.quantity + "' for set " + block.set + ": ";
  std::vector<Eigen::Vector3d> values(num_nodes, Eigen::Vector3d::Zero());
  for (const auto& [id, v] : block.values) {
    if (id < 1 || static_cast<std::size_t>(id) > num_nodes)
      throw InputError(what + "node " + std::to_string(id) + " is not one of the model's " +
                       std::to_string(num_nodes) + " nodes");
    values[id - 1] = v;
  }
  if (block.values.size() != num_nodes) {
    std::size_t missing = 1;
    while (block.values.count(static_cast<int>(missing))) ++missing;
    throw InputError(what + std::to_string(block.values.size()) + " of " + std::to_string(num_nodes) +
                     " nodes printed (node " + std::to_string(missing) + " missing)");
  }
  return values;
}

}  // namespace tissuemesh
