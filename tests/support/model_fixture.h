// Small models for writer and solver tests, built through the library's own build_model.
//
// block_mesh(): a 20 x 10 x 10 mm box on a 2 mm grid (10 x 5 x 5 cubes, each split into 6
// positively oriented tets along its main diagonal, conforming): 1,500 tets, 396 nodes, three
// tissues by x: fat [0, 8), fgt [8, 14), tumor [14, 20]. Volumes 800, 600, 600 mm^3.
#pragma once

#include "core/model.h"
#include "core/model_settings.h"
#include "core/tet_mesh.h"

#include <map>
#include <string>

namespace tissuemesh::test {

/// The box [lo, hi] on an nx x ny x nz grid of cells, each split into 6 positively oriented tets
/// along its main diagonal (Kuhn split: conforming), cell by cell in x-fastest order; one tissue
/// "tissue".
TetMesh box_mesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int nx, int ny, int nz);

/// The block (see above); cells_per_2mm > 1 refines its grid, each 2 mm cell split into that many
/// per direction (tissue boundaries stay at x = 8 and 14).
TetMesh block_mesh(int cells_per_2mm = 1);

/// A plane selection through grid nodes: they lie on it exactly, so a 1e-6 mm tolerance takes
/// them all and nothing else.
SetSelection grid_plane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal);

struct BlockModelOptions {
  ElementOrder order = ElementOrder::Linear;
  bool ogden_tumor = false;        ///< tumor as 2-term Ogden instead of Mooney-Rivlin
  bool sliding_top = false;        ///< add a sliding set on the plane z = 10 (normal +z)
  int cells_per_2mm = 1;           ///< grid refinement (block_mesh)
  UnitSystem units = UnitSystem::MillimetreTonneSecond;
};

/// Materials: fat neo-Hookean (mu 150 Pa, K 50 kPa, 950 kg/m^3), fgt Mooney-Rivlin (C10 100 Pa,
/// C01 50 Pa, K 60 kPa, 1040 kg/m^3), tumor Mooney-Rivlin (C10 400 Pa, C01 50 Pa, K 100 kPa,
/// 1060 kg/m^3) or Ogden (mu 700/200 Pa, alpha 2/-2). Fixed set `chest_wall` = plane y = 10
/// (posterior face), face set `skin` = the boundary face y = 0 (anterior), prone gravity 9.81.
std::map<std::string, MaterialSpec> block_materials(bool ogden_tumor);
ModelSettings block_settings(const BlockModelOptions& options);
Model block_model(const BlockModelOptions& options = {});

/// Readable name of a (element order, unit system) test parameter: "tet4_mm_t_s", "tet10_SI", ...
std::string order_units_name(ElementOrder order, UnitSystem units);

}  // namespace tissuemesh::test
