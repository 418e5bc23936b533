// vtu_points: the point arithmetic bench/bench_prone2supine.sh needs on VTU files.
//
//   vtu_points deform MESH.vtu SOLUTION.vtu OUT.vtu
//       MESH (a mesh of `tissuemesh mesh`) with every point moved by SOLUTION's point data
//       `displacement` (mm; SOLUTION must have MESH's points in MESH's order: model.node_order
//       mesh, tet4) -> OUT, a mesh every tissuemesh command reads.
//   vtu_points distance A.vtu[:ARRAY] B.vtu[:ARRAY]
//       prints the largest distance (mm) between point i of A and point i of B, each moved by its
//       point-data vector ARRAY when given.
// Exit 2 with a message on bad arguments or files.
#include "core/vtu_io.h"

#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <Eigen/Core>

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

std::vector<Eigen::Vector3d> positions(const std::string& spec) {
  const auto colon = spec.rfind(':');
  const std::string path = colon == std::string::npos ? spec : spec.substr(0, colon);
  const std::string array = colon == std::string::npos ? "" : spec.substr(colon + 1);
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  if (!grid || grid->GetNumberOfPoints() == 0) throw std::runtime_error(path + ": no points");
  std::vector<Eigen::Vector3d> p(static_cast<std::size_t>(grid->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i) grid->GetPoint(i, p[i].data());
  if (!array.empty()) {
    vtkDataArray* a = grid->GetPointData()->GetArray(array.c_str());
    if (!a || a->GetNumberOfComponents() != 3) throw std::runtime_error(path + ": no 3-component point array " + array);
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i) {
      double u[3];
      a->GetTuple(i, u);
      p[i] += Eigen::Vector3d(u[0], u[1], u[2]);
    }
  }
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "deform" && argc == 5) {
      tissuemesh::TetMesh mesh = tissuemesh::read_vtu(argv[2]);
      const std::vector<Eigen::Vector3d> moved = positions(std::string(argv[3]) + ":displacement");
      if (moved.size() != mesh.points.size()) throw std::runtime_error("the solution has other points than the mesh");
      mesh.points = moved;
      tissuemesh::write_vtu(mesh, argv[4]);
      return 0;
    }
    if (mode == "distance" && argc == 4) {
      const std::vector<Eigen::Vector3d> a = positions(argv[2]), b = positions(argv[3]);
      if (a.size() != b.size()) throw std::runtime_error("the two files have different point counts");
      double d = 0.0;
      for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i] - b[i]).norm());
      std::printf("%.6g\n", d);
      return 0;
    }
    std::fprintf(stderr, "usage: vtu_points deform MESH SOLUTION OUT | vtu_points distance A[:ARRAY] B[:ARRAY]\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vtu_points: %s\n", e.what());
  }
  return 2;
}
