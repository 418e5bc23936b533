#include "core/surface_vtp.h"

#include "core/vtk_grid_file.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>

#include <map>

namespace tissuemesh {
namespace {

void set_points(vtkPolyData& data, const TriSurface& s) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(s.points.size()));
  for (std::size_t v = 0; v < s.points.size(); ++v)
    points->SetPoint(static_cast<vtkIdType>(v), s.points[v][0], s.points[v][1], s.points[v][2]);
  data.SetPoints(points);
}

vtkNew<vtkIntArray> int_array(const char* name, vtkIdType n) {
  vtkNew<vtkIntArray> a;
  a->SetName(name);
  a->SetNumberOfValues(n);
  return a;
}

}  // namespace

void write_surface_vtp(const TriSurface& s, const std::string& path) {
  vtkNew<vtkPolyData> data;
  set_points(*data, s);
  const auto n = static_cast<vtkIdType>(s.triangles.size());
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(n, 3 * n);
  auto p = int_array("label_p", n), q = int_array("label_q", n), patch = int_array("patch", n);
  std::map<std::array<int, 2>, int> patches;
  for (const auto& pq : s.labels) patches.emplace(pq, 0);
  int next = 0;
  for (auto& [pq, index] : patches) index = next++;
  for (vtkIdType t = 0; t < n; ++t) {
    const auto& tri = s.triangles[static_cast<std::size_t>(t)];
    const vtkIdType ids[3] = {tri[0], tri[1], tri[2]};
    polys->InsertNextCell(3, ids);
    const auto& pq = s.labels[static_cast<std::size_t>(t)];
    p->SetValue(t, pq[0]);
    q->SetValue(t, pq[1]);
    patch->SetValue(t, patches.at(pq));
  }
  data->SetPolys(polys);
  data->GetCellData()->AddArray(p);
  data->GetCellData()->AddArray(q);
  data->GetCellData()->AddArray(patch);
  write_polydata_vtp(*data, s.tissue_names, path);
}

void write_junctions_vtp(const TriSurface& s, const std::string& path) {
  vtkNew<vtkPolyData> data;
  set_points(*data, s);
  const auto n = static_cast<vtkIdType>(s.junctions.size());
  vtkNew<vtkCellArray> lines;
  auto closed = int_array("closed", n), index = int_array("junction", n);
  for (vtkIdType j = 0; j < n; ++j) {
    const auto& line = s.junctions[static_cast<std::size_t>(j)];
    lines->InsertNextCell(static_cast<vtkIdType>(line.size()));
    for (int v : line) lines->InsertCellPoint(v);
    closed->SetValue(j, line.front() == line.back() ? 1 : 0);
    index->SetValue(j, static_cast<int>(j));
  }
  data->SetLines(lines);
  data->GetCellData()->AddArray(closed);
  data->GetCellData()->AddArray(index);
  write_polydata_vtp(*data, s.tissue_names, path);
}

}  // namespace tissuemesh
