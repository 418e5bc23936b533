// Reading CalculiX results from the .dat file written by *NODE PRINT (CalculiX CrunchiX User's
// Manual 2.20, *NODE PRINT).
#pragma once

#include <Eigen/Core>

#include <map>
#include <string>
#include <vector>

namespace tissuemesh {

/// One printed block: "<quantity> (...) for set <SET> and time <t>" followed by node rows.
struct DatBlock {
  std::string quantity;   ///< "displacements", "forces", ...
  std::string set;        ///< upper-case set name
  double time = 0.0;
  std::map<int, Eigen::Vector3d> values;  ///< node id (1-based) -> 3 components
  bool has_total = false;                 ///< "total force" summary (TOTALS=YES)
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
};

/// Every block in a .dat file, in file order. Throws InputError naming the file when it cannot be
/// read or a block is malformed.
std::vector<DatBlock> read_calculix_dat(const std::string& path);

/// The block of `quantity` for `set` with the largest time; throws InputError if there is none.
const DatBlock& last_block(const std::vector<DatBlock>& blocks, const std::string& quantity,
                           const std::string& set);

/// The block's values as one vector per node, index = CalculiX node id - 1 (tissuemesh writes
/// node i as id i + 1). Throws InputError when the block does not hold exactly the ids
/// 1..num_nodes (naming the first one missing or out of range).
std::vector<Eigen::Vector3d> values_by_node(const DatBlock& block, std::size_t num_nodes);

}  // namespace tissuemesh
