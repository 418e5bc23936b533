// Label-image readers and the NIfTI writer: the same volume through every format, hand-checked
// orientation, NIfTI qform/sform variants written by VTK's independent NIfTI writer, refusals of
// bad input (with nothing printed), and write_nifti round trip and byte-determinism.
#include "image/image_io.h"

#include "core/errors.h"
#include "support/test_paths.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNIFTIImageHeader.h>
#include <vtkNIFTIImageReader.h>
#include <vtkNIFTIImageWriter.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <zlib.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace tissuemesh {
namespace {

namespace fs = std::filesystem;
using test::kHeaderCoordinateMm;

const Eigen::Matrix3d kRasLps = Eigen::Vector3d(-1, -1, 1).asDiagonal();

// 7 x 5 x 4 voxels, every voxel its own label, so any flip or transposition changes the labels.
LabelImage make_volume(const Eigen::Matrix3d& direction) {
  LabelImage image;
  image.dims = {7, 5, 4};
  image.spacing = {0.7, 0.8, 1.5};
  image.origin = {-12.5, 30.25, 7.75};
  image.direction = direction;
  image.labels.resize(image.voxel_count());
  for (std::size_t n = 0; n < image.labels.size(); ++n) image.labels[n] = static_cast<int>(n) + 1;
  return image;
}

// An oblique rotation (det +1) and an oblique reflection (det -1, a left-handed voxel grid).
struct Orientation {
  const char* name;
  Eigen::Matrix3d direction;
};
std::vector<Orientation> orientations() {
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  return {{"right-handed", rotation},
          {"left-handed", rotation * Eigen::Vector3d(1, 1, -1).asDiagonal()}};
}

void expect_same_image(const LabelImage& actual, const LabelImage& expected) {
  ASSERT_EQ(actual.dims, expected.dims);
  EXPECT_EQ(actual.labels, expected.labels);
  double worst = 0.0;  // largest voxel-centre distance, mm
  for (int k = 0; k < expected.dims[2]; ++k) {
    for (int j = 0; j < expected.dims[1]; ++j) {
      for (int i = 0; i < expected.dims[0]; ++i) {
        const Eigen::Vector3d ijk(i, j, k);
        worst = std::max(worst, (actual.to_physical(ijk) - expected.to_physical(ijk)).norm());
      }
    }
  }
  EXPECT_LE(worst, kHeaderCoordinateMm);
}

bool host_is_big_endian() {
  const std::uint16_t one = 1;
  unsigned char first = 0;
  std::memcpy(&first, &one, 1);
  return first == 0;
}

// Voxel bytes in host order, each label stored as T, repeated `components` times.
template <typename T>
std::string voxel_bytes(const LabelImage& image, int components = 1) {
  std::string bytes;
  for (std::int32_t label : image.labels) {
    const T value = static_cast<T>(label);
    for (int c = 0; c < components; ++c) {
      bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
    }
  }
  return bytes;
}

void write_file(const fs::path& path, const std::string& bytes, bool append = false) {
  std::ofstream out(path, std::ios::binary | (append ? std::ios::app : std::ios::trunc));
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << path;
}

// Appends a gzip member (what NRRD's "encoding: gzip" means) to `path`.
void append_gzip(const fs::path& path, const std::string& bytes) {
  gzFile file = gzopen(path.c_str(), "ab");
  ASSERT_NE(file, nullptr);
  ASSERT_EQ(gzwrite(file, bytes.data(), static_cast<unsigned>(bytes.size())),
            static_cast<int>(bytes.size()));
  ASSERT_EQ(gzclose(file), Z_OK);
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string numbers(const Eigen::Vector3d& v, const char* separator) {
  std::ostringstream out;
  out << std::setprecision(17) << v[0] << separator << v[1] << separator << v[2];
  return out.str();
}

// A NRRD written by hand. `space` is a NRRD space name; directions and origin are expressed in it.
// `data_name` empty: attached data; else the header goes to `path` and the data to that file.
struct Nrrd {
  std::string space = "left-posterior-superior";
  std::string type = "short";
  bool gzip = false;
  std::string data_name;
};
void write_nrrd(const LabelImage& image, const fs::path& path, const Nrrd& nrrd,
                const std::string& data) {
  Eigen::Matrix3d to_space = Eigen::Matrix3d::Identity();
  if (nrrd.space == "right-anterior-superior") to_space = kRasLps;
  if (nrrd.space == "left-anterior-superior") to_space = Eigen::Vector3d(1, -1, 1).asDiagonal();
  const Eigen::Matrix3d steps = to_space * image.index_to_physical();
  std::ostringstream h;
  h << "NRRD0004\n# hand-written by test_image_io\ntype: " << nrrd.type << "\ndimension: 3\n"
    << "space: " << nrrd.space << "\nsizes: " << image.dims[0] << " " << image.dims[1] << " "
    << image.dims[2] << "\nspace directions: (" << numbers(steps.col(0), ",") << ") ("
    << numbers(steps.col(1), ",") << ") (" << numbers(steps.col(2), ",") << ")\n"
    << "kinds: domain domain domain\nendian: " << (host_is_big_endian() ? "big" : "little")
    << "\nencoding: " << (nrrd.gzip ? "gzip" : "raw") << "\nspace origin: ("
    << numbers(to_space * image.origin, ",") << ")\n";
  if (!nrrd.data_name.empty()) h << "data file: " << nrrd.data_name << "\n";
  h << "\n";
  write_file(path, h.str());
  const fs::path data_path = nrrd.data_name.empty() ? path : path.parent_path() / nrrd.data_name;
  if (!nrrd.data_name.empty()) write_file(data_path, "");
  if (nrrd.gzip) {
    append_gzip(data_path, data);
  } else {
    write_file(data_path, data, true);
  }
}

// A MetaImage written by hand (ITK's field order). TransformMatrix lists the i, j, k axis
// vectors one after another (ITK's MetaImageIO convention).
struct Mha {
  std::string element_type = "MET_USHORT";
  int channels = 1;
  bool compress = false;  // zlib stream, as MetaIO writes it
  std::string data_name;  // empty: LOCAL
};
// `data` as one zlib stream, as MetaIO writes compressed voxels.
std::string zlib_stream(const std::string& data) {
  std::string packed(compressBound(data.size()), '\0');
  uLongf size = packed.size();
  const int rc = compress2(reinterpret_cast<Bytef*>(packed.data()), &size,
                           reinterpret_cast<const Bytef*>(data.data()), data.size(), 6);
  EXPECT_EQ(rc, Z_OK);
  return packed.substr(0, size);
}

void write_mha(const LabelImage& image, const fs::path& path, const Mha& mha, std::string data) {
  if (mha.compress) data = zlib_stream(data);
  const Eigen::Matrix3d& d = image.direction;
  std::ostringstream h;
  h << "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = "
    << (host_is_big_endian() ? "True" : "False")
    << "\nCompressedData = " << (mha.compress ? "True" : "False") << "\n";
  if (mha.compress) h << "CompressedDataSize = " << data.size() << "\n";
  h << "TransformMatrix = " << numbers(d.col(0), " ") << " " << numbers(d.col(1), " ") << " "
    << numbers(d.col(2), " ") << "\nOffset = " << numbers(image.origin, " ")
    << "\nCenterOfRotation = 0 0 0\nAnatomicalOrientation = " << orientation_code(image.direction)
    << "\nElementSpacing = " << numbers(image.spacing, " ") << "\nDimSize = " << image.dims[0]
    << " " << image.dims[1] << " " << image.dims[2]
    << "\nElementNumberOfChannels = " << mha.channels << "\nElementType = " << mha.element_type
    << "\nElementDataFile = " << (mha.data_name.empty() ? "LOCAL" : mha.data_name) << "\n";
  write_file(path, h.str());
  if (mha.data_name.empty()) {
    write_file(path, data, true);
  } else {
    write_file(path.parent_path() / mha.data_name, data);
  }
}

// `image` as VTK image data (origin 0, its spacing), slices reversed if asked: the layout that
// vtkNIFTIImageWriter expects when it is given QFac = -1.
vtkSmartPointer<vtkImageData> to_vtk(const LabelImage& image, int vtk_type = VTK_SHORT,
                                     int components = 1, bool reverse_k = false) {
  auto data = vtkSmartPointer<vtkImageData>::New();
  data->SetDimensions(image.dims[0], image.dims[1], image.dims[2]);
  data->SetSpacing(image.spacing.data());
  data->AllocateScalars(vtk_type, components);
  vtkDataArray* scalars = data->GetPointData()->GetScalars();
  for (int k = 0; k < image.dims[2]; ++k) {
    const int file_k = reverse_k ? image.dims[2] - 1 - k : k;
    for (int j = 0; j < image.dims[1]; ++j) {
      for (int i = 0; i < image.dims[0]; ++i) {
        for (int c = 0; c < components; ++c) {
          scalars->SetComponent(static_cast<vtkIdType>(image.index(i, j, k)), c,
                                image.at(i, j, file_k));
        }
      }
    }
  }
  return data;
}

// Writes `data` with VTK's own NIfTI writer (independent of write_nifti). The RAS orientation
// `linear` (unit columns) and `offset` go into the qform only (with `qfac`) or the sform only; VTK
// scales the columns by the data's spacing. The data's origin is 0, so VTK adds no other form.
enum class NiftiForm { kQformOnly, kSformOnly };
void write_vtk_nifti(vtkImageData* data, const fs::path& path, NiftiForm form,
                     const Eigen::Matrix3d& linear, const Eigen::Vector3d& offset,
                     double qfac = 1.0) {
  vtkNew<vtkMatrix4x4> matrix;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) matrix->SetElement(r, c, linear(r, c));
    matrix->SetElement(r, 3, offset[r]);
  }
  vtkNew<vtkNIFTIImageWriter> writer;
  if (form == NiftiForm::kQformOnly) {
    writer->SetQFac(qfac);
    writer->SetQFormMatrix(matrix);
  } else {
    writer->SetSFormMatrix(matrix);
  }
  writer->SetInputData(data);
  writer->SetFileName(path.c_str());
  writer->Write();
  ASSERT_EQ(writer->GetErrorCode(), 0u) << path;
}

// `image` through write_vtk_nifti. A left-handed grid in the qform needs qfac = -1; VTK then keeps
// its slices right-handed (its first slice is the file's last, and the matrix holds a proper
// rotation and that slice's position: vtkNIFTIImageReader.h, GetQFac).
void write_with_vtk(const LabelImage& image, const fs::path& path, NiftiForm form,
                    int vtk_type = VTK_SHORT, int components = 1) {
  Eigen::Matrix3d linear = kRasLps * image.direction;
  const bool reverse = form == NiftiForm::kQformOnly && linear.determinant() < 0;
  if (reverse) linear.col(2) *= -1.0;
  const Eigen::Vector3d offset =
      kRasLps * image.to_physical(Eigen::Vector3d(0, 0, reverse ? image.dims[2] - 1 : 0));
  write_vtk_nifti(to_vtk(image, vtk_type, components, reverse), path, form, linear, offset,
                  reverse ? -1.0 : 1.0);
}

// The header fields of a NIfTI file as VTK reads them.
vtkSmartPointer<vtkNIFTIImageHeader> nifti_fields(const fs::path& path) {
  vtkNew<vtkNIFTIImageReader> reader;
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  vtkSmartPointer<vtkNIFTIImageHeader> header = vtkSmartPointer<vtkNIFTIImageHeader>::New();
  header->DeepCopy(reader->GetNIFTIHeader());
  return header;
}

// Expects read_label_image(path) to throw InputError whose message names the file and contains
// every one of `fragments`, and nothing to reach stderr on the way.
void expect_refused(const fs::path& path, const std::vector<std::string>& fragments) {
  SCOPED_TRACE(path.filename().string());
  testing::internal::CaptureStderr();
  std::string message;
  try {
    read_label_image(path.string());
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  ASSERT_FALSE(message.empty()) << "no InputError";
  EXPECT_NE(message.find(path.filename().string()), std::string::npos) << message;
  for (const auto& fragment : fragments) {
    EXPECT_NE(message.find(fragment), std::string::npos)
        << "'" << fragment << "' not in: " << message;
  }
}

// Pseudo-random bytes (Numerical Recipes LCG, top byte): reproducible noise.
std::uint8_t next_random_byte(std::uint32_t& state) {
  state = state * 1664525u + 1013904223u;
  return static_cast<std::uint8_t>(state >> 24);
}

// A larger volume of irregular labels: its compressed data is long enough to cut in half.
LabelImage make_noisy_volume() {
  LabelImage image = make_volume(Eigen::Matrix3d::Identity());
  image.dims = {48, 40, 32};
  image.labels.resize(image.voxel_count());
  std::uint32_t state = 12345;
  for (auto& label : image.labels) label = next_random_byte(state);
  return image;
}

void cut_to_half(const fs::path& path) { fs::resize_file(path, fs::file_size(path) / 2); }

// ----------------------------------------------------------------------------------------- tests

TEST(ImageIo, SameVolumeFromNiftiNrrdAndMetaImage) {
  const fs::path dir = test::scratch_dir();
  for (const Orientation& o : orientations()) {
    SCOPED_TRACE(o.name);
    const LabelImage volume = make_volume(o.direction);
    const std::string shorts = voxel_bytes<std::int16_t>(volume);
    const std::string ushorts = voxel_bytes<std::uint16_t>(volume);
    const std::string tag = o.name;
    std::vector<fs::path> files = {dir / (tag + ".nii.gz"),   dir / (tag + "_lps_gz.nrrd"),
                                   dir / (tag + "_ras.nrrd"), dir / (tag + "_las.nhdr"),
                                   dir / (tag + ".mha"),      dir / (tag + "_zlib.mhd")};
    write_nifti(volume, files[0].string());
    write_nrrd(volume, files[1], {"left-posterior-superior", "short", true, ""}, shorts);
    write_nrrd(volume, files[2], {"right-anterior-superior", "short", false, ""}, shorts);
    // Raw, because VTK's raw path is where LAS space would make it read rows bottom-up.
    write_nrrd(volume, files[3], {"left-anterior-superior", "short", false, tag + "_las.raw"},
               shorts);
    write_mha(volume, files[4], {}, ushorts);
    write_mha(volume, files[5], {"MET_USHORT", 1, true, tag + "_zlib.zraw"}, ushorts);
    for (const fs::path& file : files) {
      SCOPED_TRACE(file.filename().string());
      testing::internal::CaptureStderr();
      const LabelImage image = read_label_image(file.string());
      EXPECT_EQ(testing::internal::GetCapturedStderr(), "");  // readers never print
      expect_same_image(image, volume);
    }
  }
}

TEST(ImageIo, IdentityRasBecomesLpsFlip) {
  // Hand-checked: RAS axes (+x right, +y anterior) are LPS (-x, -y); z is shared.
  const fs::path dir = test::scratch_dir();
  const LabelImage ras_volume = make_volume(Eigen::Matrix3d::Identity());  // written as RAS
  const Eigen::Vector3d o = ras_volume.origin;
  LabelImage expected = ras_volume;
  expected.direction = Eigen::Vector3d(-1, -1, 1).asDiagonal();
  expected.origin = Eigen::Vector3d(-o[0], -o[1], o[2]);

  // sform = diag(spacing) with offset o, no qform.
  write_vtk_nifti(to_vtk(ras_volume), dir / "identity_sform.nii", NiftiForm::kSformOnly,
                  Eigen::Matrix3d::Identity(), o);
  EXPECT_EQ(nifti_fields(dir / "identity_sform.nii")->GetQFormCode(), 0);

  std::ostringstream ras;
  ras << "NRRD0004\ntype: short\ndimension: 3\nspace: right-anterior-superior\nsizes: 7 5 4\n"
      << "space directions: (0.7,0,0) (0,0.8,0) (0,0,1.5)\nendian: "
      << (host_is_big_endian() ? "big" : "little") << "\nencoding: raw\nspace origin: ("
      << numbers(o, ",") << ")\n\n";
  write_file(dir / "identity_ras.nrrd", ras.str() + voxel_bytes<std::int16_t>(ras_volume));

  for (const char* name : {"identity_sform.nii", "identity_ras.nrrd"}) {
    SCOPED_TRACE(name);
    const LabelImage image = read_label_image((dir / name).string());
    EXPECT_TRUE(image.direction.isApprox(expected.direction, 1e-12)) << image.direction;
    EXPECT_LE((image.origin - expected.origin).norm(), kHeaderCoordinateMm);
    EXPECT_EQ(orientation_code(image.direction), "RAS");
    expect_same_image(image, expected);
  }
}

TEST(ImageIo, NiftiQformOnlyAndSformOnlyGiveTheSameGeometry) {
  const fs::path dir = test::scratch_dir();
  for (const Orientation& o : orientations()) {
    SCOPED_TRACE(o.name);
    const LabelImage volume = make_volume(o.direction);
    const bool left_handed = o.direction.determinant() < 0;
    const fs::path qform = dir / (std::string(o.name) + "_qform.nii.gz");
    const fs::path sform = dir / (std::string(o.name) + "_sform.nii");
    write_with_vtk(volume, qform, NiftiForm::kQformOnly);
    write_with_vtk(volume, sform, NiftiForm::kSformOnly);

    // The files really are what this test claims: qform only (with qfac = -1 when the grid is
    // left-handed) and sform only (left-handed matrix, which VTK reads slice-reversed).
    auto q = nifti_fields(qform);
    EXPECT_EQ(q->GetSFormCode(), 0);
    EXPECT_GT(q->GetQFormCode(), 0);
    EXPECT_EQ(q->GetPixDim(0), left_handed ? -1.0 : 1.0);
    auto s = nifti_fields(sform);
    EXPECT_EQ(s->GetQFormCode(), 0);
    EXPECT_GT(s->GetSFormCode(), 0);

    expect_same_image(read_label_image(qform.string()), volume);
    expect_same_image(read_label_image(sform.string()), volume);
  }
}

TEST(ImageIo, RefusesBadInputNamingTheFile) {
  const fs::path dir = test::scratch_dir();
  const LabelImage volume = make_volume(orientations()[0].direction);

  write_nrrd(volume, dir / "float.nrrd", {"left-posterior-superior", "float", false, ""},
             voxel_bytes<float>(volume));
  expect_refused(dir / "float.nrrd", {"float32", "not an integer label type"});
  write_with_vtk(volume, dir / "double.nii", NiftiForm::kSformOnly, VTK_DOUBLE);
  expect_refused(dir / "double.nii", {"float64", "not an integer label type"});

  write_mha(volume, dir / "two_channels.mha", {"MET_USHORT", 2, false, ""},
            voxel_bytes<std::uint16_t>(volume, 2));
  expect_refused(dir / "two_channels.mha", {"2 components"});
  write_with_vtk(volume, dir / "two_components.nii.gz", NiftiForm::kSformOnly, VTK_SHORT, 2);
  expect_refused(dir / "two_components.nii.gz", {"2 components"});

  LabelImage big = volume;
  big.labels[3] = 0;
  std::string uints = voxel_bytes<std::uint32_t>(big);
  const std::uint32_t too_big = 3000000000u;
  std::memcpy(&uints[3 * sizeof too_big], &too_big, sizeof too_big);
  write_nrrd(big, dir / "huge_label.nrrd", {"left-posterior-superior", "uint", false, ""}, uints);
  expect_refused(dir / "huge_label.nrrd", {"3000000000", "does not fit"});

  // Truncated data in every container: the cut must be detected, never zero-filled.
  const LabelImage noisy = make_noisy_volume();
  write_nifti(noisy, (dir / "cut.nii.gz").string());
  write_nifti(noisy, (dir / "cut.nii").string());
  write_nrrd(noisy, dir / "cut_raw.nrrd", {}, voxel_bytes<std::int16_t>(noisy));
  write_nrrd(noisy, dir / "cut_gz.nrrd", {"left-posterior-superior", "short", true, ""},
             voxel_bytes<std::int16_t>(noisy));
  write_mha(noisy, dir / "cut_raw.mha", {}, voxel_bytes<std::uint16_t>(noisy));
  write_mha(noisy, dir / "cut_zlib.mha", {"MET_USHORT", 1, true, ""},
            voxel_bytes<std::uint16_t>(noisy));
  for (const char* name :
       {"cut.nii.gz", "cut.nii", "cut_raw.nrrd", "cut_gz.nrrd", "cut_raw.mha", "cut_zlib.mha"}) {
    ASSERT_NO_THROW(read_label_image((dir / name).string())) << name;
    fs::copy_file(dir / name, dir / (std::string("bad_") + name));
    cut_to_half(dir / name);
    expect_refused(dir / name, {"truncated"});
  }
  // Corrupt compressed streams of full length: the damage must be detected, too.
  for (const char* name : {"bad_cut.nii.gz", "bad_cut_gz.nrrd", "bad_cut_zlib.mha"}) {
    std::string bytes = read_bytes(dir / name);
    for (std::size_t n = bytes.size() / 2; n < bytes.size() / 2 + 64; ++n) bytes[n] ^= 0x5a;
    write_file(dir / name, bytes);
    expect_refused(dir / name, {"corrupt"});
  }

  write_file(dir / "garbage.nrrd", "NRRD0004\ntype: banana\ndimension: 3\nsizes: 7 5 4\n\n");
  expect_refused(dir / "garbage.nrrd", {"banana"});
  write_file(dir / "scanner.nrrd",
             "NRRD0004\ntype: uchar\ndimension: 3\nspace: scanner-xyz\nsizes: 7 5 4\n"
             "encoding: raw\n\n" +
                 voxel_bytes<std::uint8_t>(volume));
  expect_refused(dir / "scanner.nrrd", {"scanner-xyz"});
  // A field given twice (here in two spellings) would be read differently by VTK, which takes
  // them in order: a huge first 'dimension' sized its axis list before the second corrected it.
  const std::string valid = "type: uchar\nsizes: 7 5 4\nencoding: raw\n\n" + voxel_bytes<std::uint8_t>(volume);
  write_file(dir / "twice.nrrd", "NRRD0004\nDimension: 77777777777777\ndimension: 3\n" + valid);
  expect_refused(dir / "twice.nrrd", {"'dimension'", "more than once"});
  write_file(dir / "twice.mha", "ObjectType = Image\nNDims = 77777777777777 3\nNDims = 3\n"
                                "DimSize = 7 5 4\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n" +
                                    voxel_bytes<std::uint8_t>(volume));
  expect_refused(dir / "twice.mha", {"'NDims'", "more than once"});
  write_file(dir / "space_dimension.nrrd",
             "NRRD0004\ndimension: 3\nspace: left-posterior-superior\nspace dimension: 77777777\n" + valid);
  expect_refused(dir / "space_dimension.nrrd", {"space dimension", "not 3"});
  std::string noise(2000, '\0');
  std::uint32_t state = 99;
  for (char& c : noise) c = static_cast<char>(next_random_byte(state));
  for (const char* name : {"garbage.nii", "garbage.nii.gz", "garbage.mha", "garbage.nhdr"}) {
    write_file(dir / name, noise);
    expect_refused(dir / name, {});
  }

  expect_refused(dir / "missing.nii.gz", {"no such file"});
  write_file(dir / "labels.png", noise);
  expect_refused(dir / "labels.png", {".nii", ".nii.gz", ".nrrd", ".nhdr", ".mha", ".mhd"});
}

// The MetaImage voxel bytes are read by the toolkit: every integer type, either byte order, raw
// or zlib, attached, detached at an offset, and HeaderSize = -1 (the data are the file's last
// bytes) give the same labels.
TEST(ImageIo, MetaImageVoxelsInEveryLayout) {
  const fs::path dir = test::scratch_dir();
  const LabelImage volume = make_noisy_volume();
  const auto swapped = [](std::string bytes, std::size_t size) {
    for (std::size_t i = 0; i + size <= bytes.size(); i += size) {
      std::reverse(bytes.begin() + static_cast<std::ptrdiff_t>(i),
                   bytes.begin() + static_cast<std::ptrdiff_t>(i + size));
    }
    return bytes;
  };
  struct Case {
    const char* type;
    std::string bytes;
    std::size_t size;
  };
  const std::vector<Case> cases = {{"MET_UCHAR", voxel_bytes<std::uint8_t>(volume), 1},
                                   {"MET_SHORT", voxel_bytes<std::int16_t>(volume), 2},
                                   {"MET_UINT", voxel_bytes<std::uint32_t>(volume), 4},
                                   {"MET_LONG_LONG", voxel_bytes<std::int64_t>(volume), 8}};
  for (const Case& c : cases) {
    for (const bool other_order : {false, true}) {
      for (const bool compress : {false, true}) {
        const std::string name = std::string(c.type) + (other_order ? "_swapped" : "") +
                                 (compress ? "_zlib" : "");
        SCOPED_TRACE(name);
        std::string data = other_order ? swapped(c.bytes, c.size) : c.bytes;
        if (compress) data = zlib_stream(data);
        std::ostringstream h;
        h << "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = "
          << ((host_is_big_endian() != other_order) ? "True" : "False")
          << "\nCompressedData = " << (compress ? "True" : "False") << "\n";
        if (compress) h << "CompressedDataSize = " << data.size() << "\n";
        h << "ElementSpacing = " << numbers(volume.spacing, " ") << "\nOffset = "
          << numbers(volume.origin, " ") << "\nDimSize = " << volume.dims[0] << " "
          << volume.dims[1] << " " << volume.dims[2] << "\nElementType = " << c.type;
        write_file(dir / (name + ".mha"), h.str() + "\nElementDataFile = LOCAL\n" + data);
        // Detached, behind 37 bytes of another header; once at HeaderSize 37, once at -1.
        write_file(dir / (name + ".raw"), std::string(37, 'x') + data);
        write_file(dir / (name + ".mhd"),
                   h.str() + "\nHeaderSize = 37\nElementDataFile = " + name + ".raw\n");
        write_file(dir / (name + "_last.mhd"),
                   h.str() + "\nHeaderSize = -1\nElementDataFile = " + name + ".raw\n");
        for (const std::string& file : {name + ".mha", name + ".mhd", name + "_last.mhd"}) {
          SCOPED_TRACE(file);
          const LabelImage image = read_label_image((dir / file).string());
          EXPECT_EQ(image.labels, volume.labels);
          EXPECT_TRUE(image.spacing.isApprox(volume.spacing, 1e-12));
        }
      }
    }
  }
}

TEST(ImageIo, WriteNiftiRoundTripIsExactAndDeterministic) {
  const fs::path dir = test::scratch_dir();
  for (const Orientation& o : orientations()) {
    SCOPED_TRACE(o.name);
    const LabelImage volume = make_volume(o.direction);
    for (const char* ext : {".nii", ".nii.gz"}) {
      SCOPED_TRACE(ext);
      const fs::path first = dir / (std::string(o.name) + "_a" + ext);
      const fs::path second = dir / (std::string(o.name) + "_b" + ext);
      write_nifti(volume, first.string());
      write_nifti(volume, second.string());
      EXPECT_EQ(read_bytes(first), read_bytes(second));
      expect_same_image(read_label_image(first.string()), volume);

      auto fields = nifti_fields(first);
      EXPECT_EQ(fields->GetSFormCode(), 1);
      EXPECT_EQ(fields->GetQFormCode(), 1);
      EXPECT_EQ(fields->GetDataType(), 2);       // uint8 holds labels 1..140
      EXPECT_EQ(fields->GetXYZTUnits(), 2);      // mm
      EXPECT_EQ(fields->GetIntentCode(), 1002);  // NIFTI_INTENT_LABEL
    }
    // gzip member header: modification time (bytes 4-7) zero.
    const std::string gz = read_bytes(dir / (std::string(o.name) + "_a.nii.gz"));
    ASSERT_GT(gz.size(), 10u);
    EXPECT_EQ(gz.substr(4, 4), std::string(4, '\0'));
  }

  // The qform alone (sform ignored) must describe the same grid: blank the sform code and read.
  const LabelImage left = make_volume(orientations()[1].direction);
  write_nifti(left, (dir / "qform_check.nii").string());
  std::string bytes = read_bytes(dir / "qform_check.nii");
  bytes[254] = bytes[255] = '\0';  // sform_code = 0
  write_file(dir / "qform_check.nii", bytes);
  expect_same_image(read_label_image((dir / "qform_check.nii").string()), left);

  // Label ranges choose the storage type: int16 for negatives, int32 beyond 16 bits.
  for (const auto& [label, datatype] : {std::pair{-7, 4}, std::pair{100000, 8}}) {
    LabelImage image = left;
    image.labels[5] = label;
    const fs::path path = dir / ("range_" + std::to_string(datatype) + ".nii.gz");
    write_nifti(image, path.string());
    EXPECT_EQ(nifti_fields(path)->GetDataType(), datatype);
    expect_same_image(read_label_image(path.string()), image);
  }

  const std::string unwritable = (dir / "no_such_folder" / "labels.nii.gz").string();
  try {
    write_nifti(left, unwritable);
    ADD_FAILURE() << "no OutputError for " << unwritable;
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(unwritable), std::string::npos) << e.what();
  }
  EXPECT_THROW(write_nifti(left, (dir / "labels.png").string()), OutputError);
  EXPECT_FALSE(fs::exists(dir / "labels.png"));
}

}  // namespace
}  // namespace tissuemesh
