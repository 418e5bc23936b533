// Reading label images (NIfTI, NRRD, MetaImage) into a LabelImage, and writing them as NIfTI.
//
// Geometry is exact and in the toolkit's convention (core/label_image.h): millimetres, patient LPS,
// origin = centre of voxel (0,0,0), direction columns = unit LPS vectors of the i, j, k axes, with
// voxel (i,j,k) the (i,j,k)-th value of the file (i fastest) — the readers never reorder voxels
// to make the axes right-handed; a left-handed grid keeps det(direction) = -1.
//
//   NIfTI-1/2 (.nii, .nii.gz): the sform when sform_code > 0, else the qform (quaternion, qfac,
//     pixdim, qoffset) when qform_code > 0, else pixdim alone (NIfTI "method 1"); the RAS world of
//     NIfTI is converted to LPS; xyzt_units metre/micron are converted to mm (unknown = mm).
//     A header with intensity scaling (scl_slope not 0 or 1, or scl_inter not 0) is refused: the
//     stored values would not be the labels.
//   NRRD (.nrrd, .nhdr) and MetaImage (.mha, .mhd): see image/image_header.h for the fields used.
//     NRRD encodings raw and gzip; MetaImage raw and zlib-compressed; attached or one detached
//     file.
//
// Voxel values must be integers (int8, uint8, int16, uint16, int32, uint32, int64, uint64) that fit
// in int32, one value per voxel.
#pragma once

#include "core/label_image.h"

#include <string>

namespace tissuemesh {

/// Reads the label image at `path`, format chosen by extension (case-insensitive): .nii, .nii.gz,
/// .nrrd, .nhdr, .mha, .mhd. The result passes LabelImage::validate.
///
/// Throws InputError, its message starting with `path`, when: the file does not exist ("no such
/// file"); the extension is not one of the above (the message lists them); the header is garbled
/// or declares something unsupported; the voxel type is not an integer type (e.g. "voxel type
/// float32 is not an integer label type"); a voxel holds more than one component; a value does
/// not fit in int32; the voxel data is truncated or its compressed stream is corrupt.
/// Never prints: VTK's error output is captured into the exception message.
LabelImage read_label_image(const std::string& path);

/// Writes `image` as NIfTI-1 to `path` (.nii, or .nii.gz for gzip), little-endian, voxel type the
/// smallest of uint8 / int16 / int32 that holds every label, units mm, intent "label". The
/// orientation is stored twice, equivalently: as the sform (exact matrix) and as the qform
/// (quaternion + qfac), both with code 1 "scanner anatomical", in NIfTI's RAS world. The bytes
/// depend only on `image` (gzip header time stamp 0, no version or date in the header), so equal
/// images give equal files. read_label_image gives back the same labels and, within NIfTI's float32
/// storage, the same geometry.
///
/// Throws InputError if `image` fails LabelImage::validate; OutputError naming `path` if the
/// extension is not .nii/.nii.gz, the image is too large for NIfTI-1 (more than 32767 voxels along
/// an axis) or the file cannot be written (no partial file is left behind).
void write_nifti(const LabelImage& image, const std::string& path);

}  // namespace tissuemesh
