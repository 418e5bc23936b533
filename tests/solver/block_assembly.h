// BlockAssembly: the block model of tests/support/model_fixture.h (three tissues, fixed posterior
// face, sliding top with tilted normals, so that the top nodes' bases are not coordinate axes) with
// its element geometry, laws, dof map and two reduced assemblies: the standard tet4 (one thread)
// and the average-nodal-pressure tet4 (two threads). Shared by the assembly tests.
#pragma once

#include "materials/make_law.h"
#include "materials/volumetric_split.h"
#include "solver_check/dof_map.h"
#include "solver_check/nodal_pressure.h"
#include "solver_check/reduced_assembly.h"
#include "solver_check/static_solver.h"
#include "support/model_fixture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

namespace tissuemesh::test {

/// The block model (three tissues, fixed posterior face, sliding top with tilted normals) and both
/// assemblies of it.
struct BlockAssembly {
  Model model;
  std::vector<std::unique_ptr<HyperelasticLaw>> laws, shear;
  std::vector<const HyperelasticLaw*> full, rest;
  std::vector<int> tissue;
  std::vector<ElementGeometry> geometry;
  std::unique_ptr<DofMap> dofs;
  std::unique_ptr<NodalPressure> nodal;
  std::unique_ptr<ReducedAssembly> standard, with_nodal;

  /// cells_per_2mm > 1: the refined block (block_mesh), e.g. 2 for 12,000 tets, more than one
  /// assembly chunk.
  explicit BlockAssembly(int cells_per_2mm = 1) {
    BlockModelOptions options;
    options.sliding_top = true;
    options.cells_per_2mm = cells_per_2mm;
    model = block_model(options);  // mm-t-s: laws in MPa, lengths in mm
    // Tilt the sliding normals, so that the top nodes' bases are not coordinate axes.
    for (NodeSet& set : model.node_sets)
      for (Eigen::Vector3d& n : set.normals) n = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
    for (const MaterialSpec& spec : model.materials) {
      laws.push_back(make_law(spec, model.units));
      shear.push_back(make_shear_part(*laws.back()));
    }
    geometry.resize(model.elements.size());
    for (std::size_t e = 0; e < model.elements.size(); ++e) {
      ElementNodes X(4, 3);
      for (int a = 0; a < 4; ++a) X.row(a) = model.nodes[model.elements[e][a]].transpose();
      EXPECT_EQ(element_geometry(ElementOrder::Linear, X, geometry[e]), ElementStatus::Ok);
      tissue.push_back(model.tissue_ids[e] - 1);
      full.push_back(laws[tissue.back()].get());
      rest.push_back(shear[tissue.back()].get());
    }
    dofs = std::make_unique<DofMap>(model, std::vector<PrescribedDisplacement>{});
    nodal = std::make_unique<NodalPressure>(model.elements, geometry, tissue, full);
    standard = std::make_unique<ReducedAssembly>(ElementOrder::Linear, model.elements, geometry, full, *dofs, 1);
    with_nodal =
        std::make_unique<ReducedAssembly>(ElementOrder::Linear, model.elements, geometry, rest, *dofs, 2, nodal.get());
  }

  /// A smooth displacement (mm) with shear and a few percent of volume change, on the free dofs.
  Eigen::VectorXd smooth_q(double amplitude) const {
    Eigen::VectorXd u(3 * model.nodes.size());
    for (std::size_t v = 0; v < model.nodes.size(); ++v) {
      const Eigen::Vector3d& X = model.nodes[v];
      u.segment<3>(3 * v) << std::sin(0.3 * X.x() + 0.2 * X.z()), std::cos(0.25 * X.y() - 0.1 * X.x()),
          std::sin(0.2 * X.z() + 0.3 * X.y());
    }
    return amplitude * dofs->reduce(u);
  }
};

}  // namespace tissuemesh::test
