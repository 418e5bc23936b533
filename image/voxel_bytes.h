// Checks on a label image file's own bytes, made before its voxels are read: VTK 9.1's readers
// allocate what a header claims, read past short files, leave missing voxels zero with only a
// warning, and crash on some NIfTI headers they take for Analyze 7.5. What is checked here is what
// the toolkit's readers (image/image_io.h) rely on; and the MetaImage voxel read that relies on
// those checks.
//
// Every function throws InputError naming the file (`path`, as the user gave it) and what is
// wrong; nothing is printed. No function reads more than the stream it checks or reads.
#pragma once

#include "image/image_header.h"

#include <cstdint>
#include <string>
#include <vector>

namespace tissuemesh {

/// Size in bytes of `file` (the voxel data file of the image `path`). Throws InputError when it
/// cannot be read.
std::uintmax_t data_file_size(const std::string& file, const std::string& path);

/// Whether the zlib or gzip stream held in `length` bytes at byte `offset` of `file` inflates
/// cleanly to its end (checksum verified) and to at least `expected` bytes. The output is
/// discarded; memory use is constant.
bool stream_delivers(const std::string& file, std::uintmax_t offset, std::uintmax_t length,
                     std::size_t expected);

/// The `header.data_bytes()` voxel bytes of a MetaImage or NRRD header, read raw or inflated (zlib
/// or gzip, in one pass) from `header.data_file` at its offset, multi-byte values put in this
/// machine's byte order. Makes require_data_present's checks on the way, with its messages, so it
/// is called instead of it; throws InputError naming `path`.
std::vector<unsigned char> read_voxel_bytes(const ImageHeader& header, const std::string& path);

/// Requires the voxel bytes an NRRD or MetaImage header (image/image_header.h) promises: the data
/// file exists, holds the declared raw bytes after the header or offset, and a compressed stream
/// inflates to the declared size. Throws InputError otherwise.
void require_data_present(const ImageHeader& header, const std::string& path);

/// Requires that the first bytes of `path` (plain or gzip) are a single-file NIfTI-1 (n+1) or
/// NIfTI-2 (n+2) header (NIfTI-1.1 and NIfTI-2 format definitions, nifti.nimh.nih.gov) with a
/// known scalar datatype and its bitpix, and dim[0] of 1-7 dimensions of at least one voxel each.
/// Throws InputError naming the field, or the gzip stream's fault.
void require_nifti_header(const std::string& path);

}  // namespace tissuemesh
