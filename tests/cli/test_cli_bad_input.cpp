// Bad input through the program: exit code 2, a message naming the culprit, no partial output.
#include "cli/cli_runner.h"
#include "image/image_io.h"
#include "support/test_paths.h"

#include <gtest/gtest.h>

#include <vtkImageData.h>
#include <vtkNIFTIImageWriter.h>
#include <vtkNew.h>

#include <fstream>

using namespace tissuemesh;
using test::files_below;
using test::read_file;
using test::run_cli;

namespace {

LabelImage tiny_labels(std::int32_t extra_label) {
  LabelImage img;
  img.dims = {8, 8, 8};
  img.labels.assign(img.voxel_count(), 0);
  for (int k = 2; k < 6; ++k)
    for (int j = 2; j < 6; ++j)
      for (int i = 2; i < 6; ++i) img.labels[img.index(i, j, k)] = 1;
  img.labels[img.index(3, 3, 3)] = extra_label;
  return img;
}

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = test::scratch_dir();
    std::ofstream(dir / "ok.yaml") << "tissues: [{name: fat, labels: [1]}]\n";
    write_nifti(tiny_labels(1), (dir / "ok.nii.gz").string());
  }
  // Runs `args`, expects exit 2 with every `needles` in stderr, and no output folder.
  void expect_refused(const std::string& args, const std::vector<std::string>& needles) {
    const auto r = run_cli(args, dir);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    for (const auto& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << "'" << n << "' not in: " << r.err;
    EXPECT_TRUE(files_below(dir / "out").empty()) << args;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << args;
  }
  std::filesystem::path dir;
};

}  // namespace

TEST_F(BadInput, TruncatedNiftiGz) {
  const std::string bytes = read_file(dir / "ok.nii.gz");
  std::ofstream(dir / "cut.nii.gz", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  expect_refused("mesh cut.nii.gz -c ok.yaml -o out", {"cut.nii.gz"});
}

TEST_F(BadInput, FloatImage) {
  vtkNew<vtkImageData> img;
  img->SetDimensions(4, 4, 4);
  img->AllocateScalars(VTK_FLOAT, 1);
  vtkNew<vtkNIFTIImageWriter> w;
  w->SetInputData(img);
  w->SetFileName((dir / "float.nii").c_str());
  w->Write();
  expect_refused("mesh float.nii -c ok.yaml -o out", {"float.nii", "float", "integer"});
}

TEST_F(BadInput, UnmappedLabel) {
  write_nifti(tiny_labels(9), (dir / "nine.nii.gz").string());
  expect_refused("mesh nine.nii.gz -c ok.yaml -o out", {"nine.nii.gz", "label 9"});
}

TEST_F(BadInput, EmptyTissue) {
  std::ofstream(dir / "two.yaml") << "tissues: [{name: fat, labels: [1]}, {name: tumor, labels: [3]}]\n";
  expect_refused("mesh ok.nii.gz -c two.yaml -o out", {"tissue 'tumor'", "no voxels"});
}

TEST_F(BadInput, MissingFiles) {
  expect_refused("mesh nothere.nii.gz -c ok.yaml -o out", {"nothere.nii.gz"});
  expect_refused("mesh ok.nii.gz -c nothere.yaml -o out", {"nothere.yaml"});
  expect_refused("info nothere.vtu", {"nothere.vtu"});
}

TEST_F(BadInput, InvalidYamlAndUnknownKey) {
  std::ofstream(dir / "broken.yaml") << "tissues: [{name: fat, labels: [1]}\n";
  expect_refused("mesh ok.nii.gz -c broken.yaml -o out", {"broken.yaml", "line"});
  std::ofstream(dir / "typo.yaml") << "tissues: [{name: fat, labels: [1]}]\ndirect: {facet_sise_mm: 2}\n";
  expect_refused("mesh ok.nii.gz -c typo.yaml -o out", {"typo.yaml", "direct.facet_sise_mm", "unknown key"});
}

TEST_F(BadInput, NonPhysicalParameter) {
  std::ofstream(dir / "neg.yaml") << "tissues: [{name: fat, labels: [1]}]\ndirect: {cell_size_mm: -3}\n";
  expect_refused("mesh ok.nii.gz -c neg.yaml -o out", {"direct.cell_size_mm", "positive"});
}

TEST_F(BadInput, UnwritableOutputDirectory) {
  std::ofstream(dir / "file") << "x";  // a file where a folder should be: nobody, not even root, can write there
  const auto r = run_cli("mesh ok.nii.gz -c ok.yaml -o file/out", dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("file/out"), std::string::npos) << r.err;
  const auto p = run_cli("phantom --out /proc/tissuemesh-test/labels.nii.gz", dir);
  EXPECT_EQ(p.exit_code, 2) << p.err;
  EXPECT_NE(p.err.find("/proc/tissuemesh-test"), std::string::npos) << p.err;
}

TEST_F(BadInput, BadPhantomOption) {
  const auto r = run_cli("phantom --out x.nii.gz --tumor-diameter -4", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("tumor_diameter_mm"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.nii.gz"));
}
