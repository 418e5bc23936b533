// build_model: TetMesh + ModelSettings + materials per tissue -> Model (core/model.h).
//
// Elements are grouped by tissue id. Nodes: with `node_order: rcm` (the default) the corners are
// renumbered by reverse Cuthill-McKee on the corner graph (core/node_ordering.h) and tet10
// midside nodes follow them, ordered by the (lower, higher) new index of their edge's ends; the
// elements of a tissue are then ordered by their lowest corner (nearby elements, nearby ids). With
// `node_order: mesh` corners and elements keep the mesh's order (within a tissue) and midside
// nodes follow in make_quadratic's order. Corners stay first either way (SOFA writes only them),
// and Model::mesh_node_of maps each corner back to the mesh. Renumbering happens last, so every
// selection below sees the mesh's numbering and selects the same points either way.
// Selections (core/model_settings.h) are evaluated on the linear mesh: `between` takes the
// triangles shared by a tet of side A and a tet of side B (a boundary triangle when a side is
// `outside`); `plane` the nodes within tolerance of the plane; `box` the nodes inside the box.
// For tet10, midside nodes whose edge has both ends in a node set join it, and face sets keep
// their (element, face) pairs. Sliding normals are the area-weighted normals of the selected
// triangles (pointing from side A to side B) or the plane normal; a box cannot slide.
// Throws InputError naming the set when it comes out empty or names an unknown tissue, and when a
// tissue of the mesh has no material.
#pragma once

#include "core/material_spec.h"
#include "core/model.h"
#include "core/model_settings.h"
#include "core/tet_mesh.h"

#include <map>
#include <string>

namespace tissuemesh {

/// `materials` maps tissue name -> spec; entries for tissues the mesh lacks are ignored.
/// `materials_source` names where they came from in the error for a missing one.
Model build_model(const TetMesh& mesh, const ModelSettings& settings,
                  const std::map<std::string, MaterialSpec>& materials,
                  const std::string& materials_source);

/// Adds the midside node of every edge (shared between neighbours, straight edges), numbered after
/// the corner nodes in order of first appearance (element by element, edge by edge): deterministic.
void make_quadratic(Model& model);

/// Triangles (element, local face) between two sides, in element order.
std::vector<std::array<int, 2>> interface_faces(const Model& model, const InterfaceSide& a,
                                                const InterfaceSide& b);

}  // namespace tissuemesh
