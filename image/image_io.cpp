#include "image/image_io.h"

#include "core/errors.h"
#include "core/memory_budget.h"
#include "image/image_header.h"
#include "image/voxel_bytes.h"

#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkErrorCode.h>
#include <vtkExecutive.h>
#include <vtkImageData.h>
#include <vtkNIFTIImageHeader.h>
#include <vtkNIFTIImageReader.h>
#include <vtkNew.h>
#include <vtkNrrdReader.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkType.h>
#include <zlib.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <type_traits>
#include <vector>

namespace tissuemesh {
namespace {

// ------------------------------------------------------------------------------------ dispatch

// Whether the file name of `path` ends in `extension`, ignoring case (and is more than that).
bool has_extension(const std::string& path, const char* extension) {
  std::string name = std::filesystem::path(path).filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  const std::size_t n = std::strlen(extension);
  return name.size() > n && name.compare(name.size() - n, n, extension) == 0;
}

enum class Format { kNifti, kNrrd, kMetaImage };

Format format_of(const std::string& path) {
  static const std::pair<const char*, Format> kExtensions[] = {
      {".nii.gz", Format::kNifti}, {".nii", Format::kNifti},     {".nrrd", Format::kNrrd},
      {".nhdr", Format::kNrrd},    {".mha", Format::kMetaImage}, {".mhd", Format::kMetaImage}};
  for (const auto& [extension, format] : kExtensions) {
    if (has_extension(path, extension)) return format;
  }
  throw InputError(path +
                   ": unsupported label image format; supported extensions: .nii, .nii.gz, "
                   ".nrrd, .nhdr, .mha, .mhd");
}

// ------------------------------------------------------------------------------ VTK error capture

// VTK objects hand an error or warning to their observers instead of printing it to the global
// output window when an observer for that event exists (vtkErrorWithObjectMacro), so observing the
// reader and its executive (which reports the failed request separately) keeps the library silent
// and yields the text for the exception.
class ErrorObserver : public vtkCommand {
 public:
  static ErrorObserver* New() { return new ErrorObserver; }
  void Execute(vtkObject*, unsigned long event, void* data) override {
    if (event != vtkCommand::ErrorEvent || data == nullptr || !first_error_.empty()) return;
    // "ERROR: In <source>, line N\n<class> (<address>): <message>\n\n" -> "<message>"
    std::string text(static_cast<const char*>(data));
    std::size_t start = text.find("): ");
    start = start == std::string::npos ? 0 : start + 3;
    first_error_ = text.substr(start, text.find('\n', start) - start);
  }
  const std::string& first_error() const { return first_error_; }

 private:
  std::string first_error_;
};

// Runs a VTK reader's pipeline steps and turns any reported failure into an InputError.
class ReaderRun {
 public:
  ReaderRun(vtkAlgorithm* reader, const std::string& path, const char* format)
      : reader_(reader), path_(path), format_(format) {
    for (vtkObject* source :
         {static_cast<vtkObject*>(reader), static_cast<vtkObject*>(reader->GetExecutive())}) {
      source->AddObserver(vtkCommand::ErrorEvent, observer_.Get());
      source->AddObserver(vtkCommand::WarningEvent, observer_.Get());
    }
  }
  void information() {
    reader_->UpdateInformation();
    check("header");
  }
  // Headers are checked before this step, so a failure here is a short read or a corrupt stream.
  void data() {
    reader_->Update();
    check("voxel data (the file is truncated or corrupt)");
  }

 private:
  void check(const char* stage) const {
    unsigned long code = reader_->GetErrorCode();
    if (observer_->first_error().empty() && code == vtkErrorCode::NoError) return;
    std::string reason = observer_->first_error().empty() ? "VTK error code " + std::to_string(code)
                                                          : observer_->first_error();
    throw InputError(path_ + ": cannot read " + format_ + " " + stage + ": " + reason);
  }
  vtkAlgorithm* reader_;
  const std::string& path_;
  const char* format_;
  vtkNew<ErrorObserver> observer_;
};

// ------------------------------------------------------------------------------- voxel values

VoxelType voxel_type_of_vtk(int vtk_type, const std::string& path) {
  switch (vtk_type) {
    case VTK_CHAR: return std::is_signed_v<char> ? VoxelType::kInt8 : VoxelType::kUInt8;
    case VTK_SIGNED_CHAR: return VoxelType::kInt8;
    case VTK_UNSIGNED_CHAR: return VoxelType::kUInt8;
    case VTK_SHORT: return VoxelType::kInt16;
    case VTK_UNSIGNED_SHORT: return VoxelType::kUInt16;
    case VTK_INT: return VoxelType::kInt32;
    case VTK_UNSIGNED_INT: return VoxelType::kUInt32;
    case VTK_LONG: return sizeof(long) == 8 ? VoxelType::kInt64 : VoxelType::kInt32;
    case VTK_UNSIGNED_LONG: return sizeof(long) == 8 ? VoxelType::kUInt64 : VoxelType::kUInt32;
    case VTK_LONG_LONG: return VoxelType::kInt64;
    case VTK_UNSIGNED_LONG_LONG: return VoxelType::kUInt64;
    case VTK_FLOAT: return VoxelType::kFloat32;
    case VTK_DOUBLE: return VoxelType::kFloat64;
    default:
      throw InputError(path + ": voxel type " + vtkImageScalarTypeNameMacro(vtk_type) +
                       " is not supported");
  }
}

void require_label_voxels(VoxelType type, int components, const std::string& path) {
  if (components != 1) {
    throw InputError(path + ": voxels hold " + std::to_string(components) +
                     " components; a label image must hold one value per voxel");
  }
  if (type == VoxelType::kFloat32 || type == VoxelType::kFloat64) {
    throw InputError(path + ": voxel type " + voxel_type_name(type) +
                     " is not an integer label type; a label image must hold integers");
  }
}

// Reading holds the file's voxel values (VTK's buffer) and the int32 labels copied from them at
// the same time; refused before either is allocated when that cannot fit.
void require_read_memory(const std::array<int, 3>& dims, std::uint64_t value_bytes,
                         const std::string& path) {
  const std::uint64_t voxels = checked_data_bytes(dims, 1, 1, path);
  const std::uint64_t bytes = checked_data_bytes(dims, 1, value_bytes + sizeof(std::int32_t), path);
  require_memory(bytes, path + ": reading this label image",
                 std::to_string(voxels) + " voxels of " + std::to_string(value_bytes) +
                     " byte(s) each, plus 4-byte labels");
}

template <typename T>
bool fits_int32(T v) {
  if constexpr (std::is_floating_point_v<T>) {
    return false;  // floating-point images are refused before their data is read
  } else if constexpr (std::is_signed_v<T>) {
    return v >= std::numeric_limits<std::int32_t>::min() &&
           v <= std::numeric_limits<std::int32_t>::max();
  } else {
    return static_cast<std::uint64_t>(v) <=
           static_cast<std::uint64_t>(std::numeric_limits<std::int32_t>::max());
  }
}

// Copies VTK's voxel values into image.labels. `reverse_k`: VTK stored the slices in reverse
// order (vtkNIFTIImageReader does so when qfac = -1 or the sform is left-handed; see its
// GetQFac()), so slice k of the file is VTK slice nz-1-k.
template <typename T>
void copy_labels(const T* values, bool reverse_k, LabelImage& image, const std::string& path) {
  const std::size_t slice = static_cast<std::size_t>(image.dims[0]) * image.dims[1];
  image.labels.resize(image.voxel_count());
  for (int k = 0; k < image.dims[2]; ++k) {
    const T* src = values + slice * static_cast<std::size_t>(reverse_k ? image.dims[2] - 1 - k : k);
    std::int32_t* dst = image.labels.data() + slice * static_cast<std::size_t>(k);
    for (std::size_t n = 0; n < slice; ++n) {
      if (!fits_int32(src[n])) {
        std::ostringstream msg;
        msg << path << ": label value " << +src[n] << " at voxel (" << n % image.dims[0] << ","
            << n / image.dims[0] << "," << k << ") does not fit in a 32-bit signed integer";
        throw InputError(msg.str());
      }
      dst[n] = static_cast<std::int32_t>(src[n]);
    }
  }
}

void labels_from_vtk(vtkImageData* data, bool reverse_k, LabelImage& image,
                     const std::string& path) {
  int dims[3] = {0, 0, 0};
  data->GetDimensions(dims);
  vtkDataArray* scalars = data->GetPointData()->GetScalars();
  if (dims[0] != image.dims[0] || dims[1] != image.dims[1] || dims[2] != image.dims[2] ||
      scalars == nullptr || scalars->GetNumberOfComponents() != 1) {
    throw InputError(path + ": the voxel data read does not match the header's dimensions");
  }
  switch (scalars->GetDataType()) {
    vtkTemplateMacro(copy_labels(static_cast<const VTK_TT*>(scalars->GetVoidPointer(0)), reverse_k,
                                 image, path));
    default: throw InputError(path + ": unsupported voxel type " + scalars->GetDataTypeAsString());
  }
}

// The header's spatial sizes, refused unless each fits an int (NIfTI-2 stores 64-bit sizes).
std::array<int, 3> nifti_dims(vtkNIFTIImageHeader& h, const std::string& path) {
  std::array<int, 3> dims{1, 1, 1};
  for (int a = 0; a < 3 && a < h.GetDim(0); ++a) {
    const vtkTypeInt64 n = h.GetDim(a + 1);
    if (n <= 0 || n > std::numeric_limits<int>::max()) {
      throw InputError(path + ": NIfTI dim[" + std::to_string(a + 1) + "] = " + std::to_string(n) +
                       " is not a voxel count between 1 and " +
                       std::to_string(std::numeric_limits<int>::max()));
    }
    dims[a] = static_cast<int>(n);
  }
  return dims;
}

// Geometry from the raw NIfTI header fields, following nifti1.h: sform (method 3) when
// sform_code > 0, else qform (method 2), else pixdim (method 1). Computed here rather than taken
// from vtkNIFTIImageReader's matrices, which are re-expressed for VTK's reversed slice order.
LabelImage nifti_geometry(vtkNIFTIImageHeader& h, const std::string& path) {
  LabelImage g;
  g.dims = nifti_dims(h, path);
  const Eigen::Vector3d pixdim(h.GetPixDim(1), h.GetPixDim(2), h.GetPixDim(3));
  const int space_units = h.GetXYZTUnits() & 7;  // NIFTI_UNITS_METER 1, MM 2, MICRON 3
  const double mm = space_units == 1 ? 1000.0 : space_units == 3 ? 1e-3 : 1.0;

  Eigen::Matrix3d steps_ras;
  Eigen::Vector3d origin_ras = Eigen::Vector3d::Zero();
  if (h.GetSFormCode() > 0) {
    double rows[3][4];
    h.GetSRowX(rows[0]);
    h.GetSRowY(rows[1]);
    h.GetSRowZ(rows[2]);
    for (int r = 0; r < 3; ++r) {
      steps_ras.row(r) << rows[r][0], rows[r][1], rows[r][2];
      origin_ras[r] = rows[r][3];
    }
  } else {
    if (!(pixdim.array() > 0.0).all()) {
      throw InputError(path + ": NIfTI pixdim (" + std::to_string(pixdim[0]) + ", " +
                       std::to_string(pixdim[1]) + ", " + std::to_string(pixdim[2]) +
                       ") must be positive");
    }
    steps_ras = pixdim.asDiagonal();
    if (h.GetQFormCode() > 0) {
      // nifti1_io's nifti_quatern_to_mat44: a from the unit-norm constraint, qfac in pixdim[0].
      double b = h.GetQuaternB(), c = h.GetQuaternC(), d = h.GetQuaternD();
      double a = 1.0 - (b * b + c * c + d * d);
      if (a < 1e-7) {
        double s = 1.0 / std::sqrt(b * b + c * c + d * d);
        b *= s, c *= s, d *= s, a = 0.0;
      } else {
        a = std::sqrt(a);
      }
      Eigen::Matrix3d rotation;
      rotation << a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c),
          2 * (b * c + a * d), a * a + c * c - b * b - d * d, 2 * (c * d - a * b),
          2 * (b * d - a * c), 2 * (c * d + a * b), a * a + d * d - c * c - b * b;
      const double qfac = h.GetPixDim(0) < 0 ? -1.0 : 1.0;
      steps_ras = rotation * Eigen::Vector3d(pixdim[0], pixdim[1], qfac * pixdim[2]).asDiagonal();
      origin_ras << h.GetQOffsetX(), h.GetQOffsetY(), h.GetQOffsetZ();
    }
  }
  set_axis_steps(g, mm * ras_lps_flip() * steps_ras, path);
  g.origin = mm * ras_lps_flip() * origin_ras;
  return g;
}

// The voxel bytes the header promises, checked before VTK allocates for them: present in a .nii,
// and in a .nii.gz a stream that inflates to at least header + data with a valid checksum.
void require_nifti_data(vtkNIFTIImageHeader& h, const std::array<int, 3>& dims,
                        const std::string& path) {
  const std::uint64_t value_bytes = static_cast<std::uint64_t>(std::max(h.GetBitPix(), 8) / 8);
  require_read_memory(dims, value_bytes, path);
  const vtkTypeInt64 offset = h.GetVoxOffset();
  if (offset < 0) {
    throw InputError(path + ": NIfTI vox_offset " + std::to_string(offset) + " is negative");
  }
  const std::uint64_t end = static_cast<std::uint64_t>(offset) +
                            checked_data_bytes(dims, 1, value_bytes, path);
  const std::uintmax_t size = data_file_size(path, path);
  if (has_extension(path, ".gz")) {
    if (!stream_delivers(path, 0, size, end)) {
      throw InputError(path + ": gzip stream is truncated or corrupt (it does not inflate to the " +
                       std::to_string(end) + " bytes of header and voxel data expected)");
    }
  } else if (size < end) {
    throw InputError(path + ": voxel data is truncated: the file holds " + std::to_string(size) +
                     " bytes, header and voxel data need " + std::to_string(end));
  }
}

LabelImage read_nifti(const std::string& path) {
  require_nifti_header(path);
  vtkNew<vtkNIFTIImageReader> reader;
  reader->SetFileName(path.c_str());
  reader->TimeAsVectorOn();  // time points become components, which are then refused
  ReaderRun run(reader, path, "NIfTI");
  run.information();

  vtkNIFTIImageHeader* header = reader->GetNIFTIHeader();
  const std::string magic = header->GetMagic();
  if (magic != "n+1" && magic != "n+2") {
    throw InputError(path + ": not a single-file NIfTI image (magic '" + magic +
                     "'); .hdr/.img pairs and Analyze files are not supported");
  }
  require_label_voxels(voxel_type_of_vtk(reader->GetDataScalarType(), path),
                       reader->GetNumberOfScalarComponents(), path);
  const double slope = header->GetSclSlope(), intercept = header->GetSclInter();
  if ((slope != 0.0 && slope != 1.0) || intercept != 0.0) {
    throw InputError(path + ": NIfTI intensity scaling (scl_slope " + std::to_string(slope) +
                     ", scl_inter " + std::to_string(intercept) +
                     ") is set, so the stored values are not the labels");
  }
  require_nifti_data(*header, nifti_dims(*header, path), path);
  LabelImage image = nifti_geometry(*header, path);
  run.data();
  labels_from_vtk(reader->GetOutput(), reader->GetQFac() < 0, image, path);
  return image;
}

// --------------------------------------------------------------------------------------- NRRD

// vtkNrrdReader with the layout taken from our header parser. VTK 9.1's own interpretation
// guesses that a first axis of <= 9 voxels holds vector components and reads LAS-space files
// bottom-up (FileLowerLeft off); either would scramble a label volume. So after VTK has parsed
// what it is trusted with (encoding, data file, byte order, header size), the layout is reset.
class LayoutNrrdReader : public vtkNrrdReader {
 public:
  static LayoutNrrdReader* New();
  vtkTypeMacro(LayoutNrrdReader, vtkNrrdReader);
  void set_dims(const std::array<int, 3>& dims) { dims_ = dims; }

 protected:
  using vtkNrrdReader::ReadHeader;
  int ReadHeader(vtkCharArray* header) override {
    if (!this->Superclass::ReadHeader(header)) return 0;
    this->NumberOfScalarComponents = 1;  // multi-component files are refused before reading
    this->FileDimensionality = 3;
    this->FileLowerLeft = 1;
    for (int a = 0; a < 3; ++a) {
      this->DataExtent[2 * a] = 0;
      this->DataExtent[2 * a + 1] = dims_[a] - 1;
      this->DataSpacing[a] = 1.0;
      this->DataOrigin[a] = 0.0;
    }
    return 1;
  }

 private:
  std::array<int, 3> dims_{1, 1, 1};
};
vtkStandardNewMacro(LayoutNrrdReader);

LabelImage read_nrrd(const std::string& path) {
  ImageHeader h = read_nrrd_header(path);
  require_label_voxels(h.type, h.components, path);
  require_read_memory(h.geometry.dims, voxel_type_bytes(h.type), path);
  require_data_present(h, path);
  vtkNew<LayoutNrrdReader> reader;
  reader->set_dims(h.geometry.dims);
  reader->SetFileName(path.c_str());
  ReaderRun(reader, path, "NRRD").data();
  labels_from_vtk(reader->GetOutput(), false, h.geometry, path);
  return h.geometry;
}

// ---------------------------------------------------------------------------------- MetaImage

// The voxel bytes are read by the toolkit from what its header parser found, not by
// vtkMetaImageReader (see read_voxel_bytes).
LabelImage read_metaimage(const std::string& path) {
  ImageHeader h = read_metaimage_header(path);
  require_label_voxels(h.type, h.components, path);
  require_read_memory(h.geometry.dims, voxel_type_bytes(h.type), path);
  const std::vector<unsigned char> bytes = read_voxel_bytes(h, path);  // with the presence checks
  const auto labels = [&](auto type_tag) {
    using T = decltype(type_tag);
    copy_labels(reinterpret_cast<const T*>(bytes.data()), false, h.geometry, path);
  };
  switch (h.type) {
    case VoxelType::kInt8: labels(std::int8_t{}); break;
    case VoxelType::kUInt8: labels(std::uint8_t{}); break;
    case VoxelType::kInt16: labels(std::int16_t{}); break;
    case VoxelType::kUInt16: labels(std::uint16_t{}); break;
    case VoxelType::kInt32: labels(std::int32_t{}); break;
    case VoxelType::kUInt32: labels(std::uint32_t{}); break;
    case VoxelType::kInt64: labels(std::int64_t{}); break;
    case VoxelType::kUInt64: labels(std::uint64_t{}); break;
    default: throw InputError(path + ": voxel type " + voxel_type_name(h.type) + " is not a label type");
  }
  return h.geometry;
}

// ------------------------------------------------------------------------------- NIfTI writing

// Little-endian byte encoding, independent of the host's byte order.
void put_le(std::string& bytes, std::size_t offset, std::uint64_t bits, int size) {
  for (int b = 0; b < size; ++b) bytes[offset + b] = static_cast<char>((bits >> (8 * b)) & 0xff);
}

void put_f32(std::string& bytes, std::size_t offset, double value) {
  float f = static_cast<float>(value);
  std::uint32_t bits = 0;
  std::memcpy(&bits, &f, sizeof bits);
  put_le(bytes, offset, bits, 4);
}

// The nifti_1_header fields at their byte offsets (nifti1.h), plus the 4-byte empty extension
// flag: 352 bytes, the voxel data follows.
std::string nifti_header(const LabelImage& image, int datatype, int bitpix) {
  std::string h(352, '\0');
  put_le(h, 0, 348, 4);  // sizeof_hdr
  h[38] = 'r';           // "regular", expected by Analyze-era readers
  const std::int64_t dim[8] = {3, image.dims[0], image.dims[1], image.dims[2], 1, 1, 1, 1};
  for (int a = 0; a < 8; ++a) put_le(h, 40 + 2 * a, static_cast<std::uint64_t>(dim[a]), 2);
  put_le(h, 68, 1002, 2);  // intent_code NIFTI_INTENT_LABEL
  put_le(h, 70, static_cast<std::uint64_t>(datatype), 2);
  put_le(h, 72, static_cast<std::uint64_t>(bitpix), 2);

  // Both forms describe the same RAS affine. The qform needs a proper rotation: a left-handed
  // grid is expressed by qfac = -1 (pixdim[0]), which negates the k column.
  const Eigen::Matrix3d steps_ras = ras_lps_flip() * image.index_to_physical();
  const Eigen::Vector3d origin_ras = ras_lps_flip() * image.origin;
  Eigen::Matrix3d rotation = ras_lps_flip() * image.direction;
  const double qfac = rotation.determinant() < 0 ? -1.0 : 1.0;
  rotation.col(2) *= qfac;
  Eigen::Quaterniond q(rotation);
  if (q.w() < 0) q.coeffs() *= -1.0;  // NIfTI stores b, c, d and derives a >= 0

  const double pixdim[8] = {qfac, image.spacing[0], image.spacing[1], image.spacing[2], 1, 1, 1, 1};
  for (int a = 0; a < 8; ++a) put_f32(h, 76 + 4 * a, pixdim[a]);
  put_f32(h, 108, 352.0);  // vox_offset
  put_f32(h, 112, 1.0);    // scl_slope: stored values are the labels
  h[123] = 2;              // xyzt_units NIFTI_UNITS_MM
  static const char kDescrip[] = "tissuemesh label image";  // no version or date: determinism
  std::memcpy(&h[148], kDescrip, sizeof kDescrip);
  // Code 1 "scanner anatomical": the coordinates are those of the acquisition the labels were
  // segmented from, passed through unchanged, not the result of a registration (code 2). ITK
  // writes the same codes, so ITK-based tools read the orientation identically.
  put_le(h, 252, 1, 2);  // qform_code
  put_le(h, 254, 1, 2);  // sform_code
  put_f32(h, 256, q.x());
  put_f32(h, 260, q.y());
  put_f32(h, 264, q.z());
  for (int r = 0; r < 3; ++r) {
    put_f32(h, 268 + 4 * r, origin_ras[r]);                                         // qoffset
    for (int c = 0; c < 3; ++c) put_f32(h, 280 + 16 * r + 4 * c, steps_ras(r, c));  // srow
    put_f32(h, 280 + 16 * r + 12, origin_ras[r]);
  }
  std::memcpy(&h[344], "n+1", 4);  // magic, with its NUL
  return h;
}

// A gzip member with zlib's default header: modification time 0, no file name, so the bytes
// depend on the content only.
std::string gzip(const std::string& raw, const std::string& path) {
  z_stream zs{};
  if (deflateInit2(&zs, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) !=
      Z_OK) {
    throw OutputError(path + ": cannot initialise gzip compression");
  }
  std::string out;
  std::vector<Bytef> buffer(1 << 18);
  std::size_t consumed = 0;
  int flush = Z_NO_FLUSH;
  int rc = Z_OK;
  while (flush != Z_FINISH && rc != Z_STREAM_ERROR) {
    // zlib counts in 32-bit uInt, so the input is fed in chunks (zlib's zpipe.c loop).
    const std::size_t chunk = std::min<std::size_t>(raw.size() - consumed, 1u << 30);
    zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(raw.data() + consumed));
    zs.avail_in = static_cast<uInt>(chunk);
    consumed += chunk;
    flush = consumed == raw.size() ? Z_FINISH : Z_NO_FLUSH;
    do {
      zs.next_out = buffer.data();
      zs.avail_out = static_cast<uInt>(buffer.size());
      rc = deflate(&zs, flush);
      out.append(reinterpret_cast<const char*>(buffer.data()), buffer.size() - zs.avail_out);
    } while (zs.avail_out == 0 && rc != Z_STREAM_ERROR);
  }
  deflateEnd(&zs);
  if (rc != Z_STREAM_END) throw OutputError(path + ": gzip compression failed");
  return out;
}

}  // namespace

LabelImage read_label_image(const std::string& path) {
  const Format format = format_of(path);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError(
        path + (std::filesystem::exists(path, ec) ? ": is not a regular file" : ": no such file"));
  }
  LabelImage image = format == Format::kNifti  ? read_nifti(path)
                     : format == Format::kNrrd ? read_nrrd(path)
                                               : read_metaimage(path);
  image.validate(path);
  return image;
}

void write_nifti(const LabelImage& image, const std::string& path) {
  const bool gz = has_extension(path, ".nii.gz");
  if (!gz && !has_extension(path, ".nii")) {
    throw OutputError(path + ": a NIfTI file name must end in .nii or .nii.gz");
  }
  image.validate("label image to write to " + path);
  if (*std::max_element(image.dims.begin(), image.dims.end()) > 32767) {
    throw OutputError(path + ": image too large for NIfTI-1 (more than 32767 voxels on an axis)");
  }

  // The smallest NIfTI type holding every label: DT_UINT8 (2), DT_INT16 (4) or DT_INT32 (8).
  const auto [min_it, max_it] = std::minmax_element(image.labels.begin(), image.labels.end());
  const bool fits_uint8 = *min_it >= 0 && *max_it <= 255;
  const bool fits_int16 = *min_it >= -32768 && *max_it <= 32767;
  const int datatype = fits_uint8 ? 2 : fits_int16 ? 4 : 8;
  const int bytes = fits_uint8 ? 1 : fits_int16 ? 2 : 4;
  std::string file = nifti_header(image, datatype, 8 * bytes);
  const std::size_t start = file.size();
  file.resize(start + image.labels.size() * bytes);
  for (std::size_t n = 0; n < image.labels.size(); ++n) {
    put_le(file, start + n * bytes, static_cast<std::uint32_t>(image.labels[n]), bytes);
  }
  if (gz) file = gzip(file, path);

  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw OutputError(path + ": cannot open for writing: " + std::strerror(errno));
  out.write(file.data(), static_cast<std::streamsize>(file.size()));
  out.close();
  if (!out) {
    std::error_code ec;
    std::filesystem::remove(path, ec);  // no partial file left behind
    throw OutputError(path + ": writing failed (disk full or device error)");
  }
}

}  // namespace tissuemesh
