// Text-header parsers for the NRRD (.nrrd, .nhdr) and MetaImage (.mha, .mhd) label-image formats:
// the authority for geometry, voxel type and data layout (image/image_io.cpp reads only the voxel
// bytes through VTK).
//
// Everything is converted to the toolkit's convention (core/label_image.h): millimetres, patient
// LPS, `origin` = centre of voxel (0,0,0), `direction` columns = unit LPS vectors of the i, j, k
// axes, i fastest.
//
// NRRD (http://teem.sourceforge.net/nrrd/format.html): fields `dimension` (3, or 4 with one
// non-spatial axis, reported as components), `type`, `sizes`, `endian`, `encoding` (raw, gzip;
// anything else is refused), `space` (left-posterior-superior/LPS, right-anterior-superior/RAS,
// left-anterior-superior/LAS; any other space is refused because the patient frame would be
// unknown), `space directions` (one vector per spatial axis, length = spacing), `space origin`,
// `space units` (mm only), `spacings` (used only without `space directions`: the axes are those
// of the space), `kinds`, `data file` (one detached file, relative to the header's folder),
// `byte skip`/`line skip` (0 only), `space dimension` (3 only). A field given twice is refused.
// Comments (#) and key/value pairs (key:=value) are skipped.
//
// MetaImage (ITK's MetaIO): NDims (3), DimSize, ElementType (MET_CHAR ... MET_DOUBLE),
// ElementNumberOfChannels, ElementSpacing, Offset (a.k.a. Position, Origin), TransformMatrix
// (a.k.a. Rotation, Orientation), BinaryDataByteOrderMSB (a.k.a. ElementByteOrderMSB),
// CompressedData, CompressedDataSize, HeaderSize, ElementDataFile (LOCAL or one file name; must be
// the last field); a field given twice is refused. BinaryData = False (ASCII voxels) is refused.
// MetaImage physical space is LPS (ITK's convention); AnatomicalOrientation is informational
// only and ignored, as ITK does.
//
// Every function throws InputError naming the file and the field at fault for a missing, garbled or
// unsupported header. Nothing is printed.
#pragma once

#include "core/label_image.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace tissuemesh {

/// Storage type of one voxel value on disk.
enum class VoxelType {
  kInt8,
  kUInt8,
  kInt16,
  kUInt16,
  kInt32,
  kUInt32,
  kInt64,
  kUInt64,
  kFloat32,
  kFloat64
};

/// "int8", "uint16", "float32", ... (the names used in error messages).
const char* voxel_type_name(VoxelType type);

/// Bytes per value: 1, 2, 4 or 8.
std::size_t voxel_type_bytes(VoxelType type);

/// Geometry and on-disk layout of a NRRD or MetaImage file, as declared by its header.
struct ImageHeader {
  LabelImage geometry;  ///< dims, spacing (mm), origin and direction (LPS); labels empty
  int components = 1;   ///< values per voxel
  VoxelType type = VoxelType::kUInt8;
  bool big_endian = false;       ///< byte order of multi-byte values
  bool compressed = false;       ///< data is a gzip (NRRD) or zlib (MetaImage) stream
  std::string data_file;         ///< file holding the voxel bytes (the header file when attached)
  std::int64_t data_offset = 0;  ///< byte offset of the data in data_file; -1: its last bytes
  std::int64_t compressed_size = -1;  ///< MetaImage CompressedDataSize, -1 when not given

  /// Uncompressed size of the voxel data in bytes. The parsers below have checked that it fits
  /// in 64 bits.
  std::size_t data_bytes() const {
    return geometry.voxel_count() * static_cast<std::size_t>(components) * voxel_type_bytes(type);
  }
};

/// dims[0] x dims[1] x dims[2] x components x bytes per value, or InputError naming `path` and
/// the header's sizes when the product overflows 64 bits.
std::uint64_t checked_data_bytes(const std::array<int, 3>& dims, std::uint64_t components,
                                 std::uint64_t value_bytes, const std::string& path);

/// Parses the header of a .nrrd (attached data) or .nhdr (detached data) file.
ImageHeader read_nrrd_header(const std::string& path);

/// Parses the header of a .mha (attached data) or .mhd (detached data) file.
ImageHeader read_metaimage_header(const std::string& path);

/// diag(-1, -1, 1): maps RAS coordinates to LPS and LPS to RAS (it is its own inverse).
Eigen::Matrix3d ras_lps_flip();

/// Sets geometry.spacing to the column lengths of `axis_steps` (mm per index step along i, j, k, in
/// LPS) and geometry.direction to its normalised columns. Throws InputError naming `what` when a
/// column is zero or not finite. Orthonormality is left to LabelImage::validate.
void set_axis_steps(LabelImage& geometry, const Eigen::Matrix3d& axis_steps,
                    const std::string& what);

}  // namespace tissuemesh
