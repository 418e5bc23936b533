// VTU round trip through our writer and an independent reading with VTK itself.
#include "core/errors.h"
#include "core/vtu_io.h"
#include "support/test_paths.h"

#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <fstream>

using namespace tissuemesh;

namespace {
TetMesh two_tets() {
  TetMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  m.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
  m.tissue_ids = {1, 2};
  m.tissue_names = {"fat", "tumor"};
  return m;
}
}  // namespace

TEST(VtuIo, RoundTripKeepsEverything) {
  const auto path = (test::scratch_dir() / "m.vtu").string();
  TetMesh m = two_tets();
  write_vtu(m, path);
  TetMesh back = read_vtu(path);
  EXPECT_EQ(back.points, m.points);
  EXPECT_EQ(back.tets, m.tets);
  EXPECT_EQ(back.tissue_ids, m.tissue_ids);
  EXPECT_EQ(back.tissue_names, m.tissue_names);
}

TEST(VtuIo, PlainVtkReaderSeesTissueIdsAndNames) {
  const auto path = (test::scratch_dir() / "m.vtu").string();
  write_vtu(two_tets(), path, {{"quality", {0.5, 0.25}}});
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkUnstructuredGrid* g = reader->GetOutput();
  ASSERT_EQ(g->GetNumberOfCells(), 2);
  EXPECT_EQ(g->GetCellType(1), 10);  // VTK_TETRA
  EXPECT_EQ(g->GetCellData()->GetArray("tissue_id")->GetTuple1(1), 2.0);
  EXPECT_EQ(g->GetCellData()->GetArray("quality")->GetTuple1(0), 0.5);
  // Text as component names of Int32 arrays, and meshio's per-tissue [tag, dimension] arrays.
  vtkDataArray* names = g->GetFieldData()->GetArray("tissue_names");
  ASSERT_NE(names, nullptr);
  ASSERT_EQ(names->GetNumberOfComponents(), 2);
  EXPECT_STREQ(names->GetComponentName(1), "tumor");
  EXPECT_EQ(names->GetComponent(0, 1), 2.0);
  vtkDataArray* tumor = g->GetFieldData()->GetArray("tumor");
  ASSERT_NE(tumor, nullptr);
  EXPECT_EQ(tumor->GetTuple1(0), 2.0);
  EXPECT_EQ(tumor->GetTuple1(1), 3.0);
  vtkDataArray* frame = g->GetFieldData()->GetArray("coordinate_system");
  ASSERT_NE(frame, nullptr);
  EXPECT_STREQ(frame->GetComponentName(0), "LPS");
}

TEST(VtuIo, WritingIsDeterministic) {
  const auto dir = test::scratch_dir();
  write_vtu(two_tets(), (dir / "a.vtu").string());
  write_vtu(two_tets(), (dir / "b.vtu").string());
  std::ifstream a(dir / "a.vtu", std::ios::binary), b(dir / "b.vtu", std::ios::binary);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}), std::string(std::istreambuf_iterator<char>(b), {}));
}

TEST(VtuIo, BadFilesAreInputErrorsNamingThePath) {
  const auto dir = test::scratch_dir();
  try {
    read_vtu((dir / "missing.vtu").string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.vtu"), std::string::npos);
  }
  std::ofstream(dir / "junk.vtu") << "not xml at all";
  EXPECT_THROW(read_vtu((dir / "junk.vtu").string()), InputError);
  // Truncated: the first half of a valid file.
  write_vtu(two_tets(), (dir / "full.vtu").string());
  std::ifstream full(dir / "full.vtu", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(full)), {});
  std::ofstream(dir / "half.vtu", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  EXPECT_THROW(read_vtu((dir / "half.vtu").string()), InputError);
}

TEST(VtuIo, InvalidMeshIsRefusedBeforeWriting) {
  const auto path = test::scratch_dir() / "bad.vtu";
  TetMesh m = two_tets();
  m.tissue_ids[1] = 3;  // no such tissue
  EXPECT_THROW(write_vtu(m, path.string()), InputError);
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(VtuIo, TissueNamedLikeAFieldArrayIsRefusedBeforeWriting) {
  const auto path = test::scratch_dir() / "clash.vtu";
  TetMesh m = two_tets();
  m.tissue_names[1] = "length_unit";
  try {
    write_vtu(m, path.string());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'length_unit'"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(VtuIo, ReadsTissueNamesOfOlderFilesWrittenAsStringArrays) {
  // Files written before the meshio-readable form carry tissue_names as a VTK string array.
  const auto path = (test::scratch_dir() / "old.vtu").string();
  write_vtu(two_tets(), path);
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkUnstructuredGrid* g = reader->GetOutput();
  g->GetFieldData()->RemoveArray("tissue_names");
  vtkNew<vtkStringArray> names;
  names->SetName("tissue_names");
  names->InsertNextValue("fat");
  names->InsertNextValue("lesion");
  g->GetFieldData()->AddArray(names);
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(g);
  ASSERT_EQ(writer->Write(), 1);
  EXPECT_EQ(read_vtu(path).tissue_names, (std::vector<std::string>{"fat", "lesion"}));
}
