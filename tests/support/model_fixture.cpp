#include "support/model_fixture.h"

#include "core/model_builder.h"

#include <algorithm>

namespace tissuemesh::test {

TetMesh box_mesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int nx, int ny, int nz) {
  TetMesh mesh;
  auto id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  const Eigen::Vector3d step = (hi - lo).cwiseQuotient(Eigen::Vector3d(nx, ny, nz));
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) mesh.points.push_back(lo + step.cwiseProduct(Eigen::Vector3d(i, j, k)));
  // Kuhn split: the 6 monotone paths from corner (0,0,0) to (1,1,1) through the cube.
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          std::array<int, 4> t;
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          const auto& P = mesh.points;
          if (signed_tet_volume(P[t[0]], P[t[1]], P[t[2]], P[t[3]]) < 0) std::swap(t[2], t[3]);
          mesh.tets.push_back(t);
          mesh.tissue_ids.push_back(1);
        }
  mesh.tissue_names = {"tissue"};
  return mesh;
}

TetMesh block_mesh(int cells_per_2mm) {
  const int r = cells_per_2mm;
  TetMesh mesh = box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(20, 10, 10), 10 * r, 5 * r, 5 * r);
  // Six tets per cell in cell order (x fastest): the tissue follows the cell's x position.
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const int i = static_cast<int>(t / 6) % (10 * r);  // x index of the cell; 2 mm = r cells
    mesh.tissue_ids[t] = i < 4 * r ? 1 : (i < 7 * r ? 2 : 3);
  }
  mesh.tissue_names = {"fat", "fgt", "tumor"};
  return mesh;
}

std::map<std::string, MaterialSpec> block_materials(bool ogden_tumor) {
  std::map<std::string, MaterialSpec> m;
  MaterialSpec fat;
  fat.law = MaterialLaw::NeoHookean;
  fat.mu_Pa = 150;
  fat.C10_Pa = 75;
  fat.K_Pa = 50e3;
  fat.density_kg_m3 = 950;
  fat.source = "test fixture";
  m["fat"] = fat;
  MaterialSpec fgt;
  fgt.law = MaterialLaw::MooneyRivlin;
  fgt.C10_Pa = 100;
  fgt.C01_Pa = 50;
  fgt.mu_Pa = 300;
  fgt.K_Pa = 60e3;
  fgt.density_kg_m3 = 1040;
  m["fgt"] = fgt;
  MaterialSpec tumor;
  if (ogden_tumor) {
    tumor.law = MaterialLaw::Ogden;
    tumor.ogden = {{700, 2.0}, {200, -2.0}};
    tumor.mu_Pa = 900;
  } else {
    tumor.law = MaterialLaw::MooneyRivlin;
    tumor.C10_Pa = 400;
    tumor.C01_Pa = 50;
    tumor.mu_Pa = 900;
  }
  tumor.K_Pa = 100e3;
  tumor.density_kg_m3 = 1060;
  m["tumor"] = tumor;
  return m;
}

SetSelection grid_plane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  SetSelection s;
  s.kind = SetSelection::Kind::Plane;
  s.plane_point_mm = point;
  s.plane_normal = normal;
  s.plane_tolerance_mm = 1e-6;
  return s;
}

ModelSettings block_settings(const BlockModelOptions& options) {
  ModelSettings s;
  s.units = options.units;
  s.element = options.order;
  NodeSetSettings wall{"chest_wall", grid_plane({0, 10, 0}, {0, 1, 0}), Constraint::Fixed};
  s.node_sets.push_back(wall);
  if (options.sliding_top) {
    NodeSetSettings top{"top", grid_plane({0, 0, 10}, {0, 0, 1}), Constraint::Sliding};
    s.node_sets.push_back(top);
  }
  FaceSetSettings skin{"skin", grid_plane({0, 0, 0}, {0, 1, 0})};
  s.face_sets.push_back(skin);
  s.gravity.direction = "prone";
  s.gravity.m_s2 = 9.81;
  return s;
}

Model block_model(const BlockModelOptions& options) {
  return build_model(block_mesh(options.cells_per_2mm), block_settings(options), block_materials(options.ogden_tumor),
                     "test fixture");
}

std::string order_units_name(ElementOrder order, UnitSystem units) {
  std::string name = std::string(order == ElementOrder::Linear ? "tet4" : "tet10") + "_" + unit_system_name(units);
  for (char& c : name)
    if (c == '-') c = '_';  // test names take [A-Za-z0-9_] only
  return name;
}

}  // namespace tissuemesh::test
