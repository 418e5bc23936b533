#include "image/voxel_bytes.h"

#include "core/errors.h"

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <utility>
#include <vector>

namespace tissuemesh {
namespace {

// The leading bytes of a NIfTI file must be a single-file NIfTI-1 or NIfTI-2 header with a known
// datatype, its bitpix, and 1-7 dimensions of at least one voxel each, checked before VTK sees the
// file: vtkNIFTIImageReader reads anything else as an Analyze 7.5 header (or a .hdr/.img pair),
// and crashes on some of those and on unknown datatypes. zlib reads plain and gzip files alike.
class NiftiHeaderBytes {
 public:
  explicit NiftiHeaderBytes(const std::string& path) {
    gzFile file = gzopen(path.c_str(), "rb");
    if (file == nullptr) throw InputError(path + ": cannot open file");
    got_ = std::max(gzread(file, bytes_, sizeof bytes_), 0);
    compressed_ = gzdirect(file) == 0;
    int code = Z_OK;
    const char* message = gzerror(file, &code);
    if (code != Z_OK && code != Z_STREAM_END && message != nullptr) zlib_error_ = message;
    gzclose(file);
    swapped_ = get<std::int32_t>(0) != 348 && get<std::int32_t>(0) != 540;
  }
  int got() const { return got_; }
  bool compressed() const { return compressed_; }
  /// zlib's complaint about a compressed file's first bytes ("" when none).
  const std::string& zlib_error() const { return zlib_error_; }
  template <typename T>
  T get(int offset) const {
    unsigned char b[sizeof(T)];
    std::memcpy(b, bytes_ + offset, sizeof(T));
    if (swapped_) std::reverse(b, b + sizeof(T));
    T value;
    std::memcpy(&value, b, sizeof(T));
    return value;
  }
  bool text_at(int offset, const char* text, std::size_t n) const {
    return std::memcmp(bytes_ + offset, text, n) == 0;
  }

 private:
  unsigned char bytes_[544] = {};
  int got_ = 0;
  bool swapped_ = false;
  bool compressed_ = false;
  std::string zlib_error_;
};

}  // namespace

std::uintmax_t data_file_size(const std::string& file, const std::string& path) {
  std::error_code ec;
  std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (ec) throw InputError(path + ": voxel data file " + file + " cannot be read: " + ec.message());
  return size;
}

namespace {

// Inflates the zlib or gzip stream held in `length` bytes at `offset` of `file`, handing each
// inflated piece to `sink(bytes, n)`, and returns the total count when the stream ends cleanly
// (checksum verified), -1 when it is corrupt or cut short.
template <typename Sink>
std::int64_t inflate_stream(const std::string& file, std::uintmax_t offset, std::uintmax_t length,
                            Sink&& sink) {
  std::ifstream in(file, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(offset));
  z_stream zs{};
  if (!in || inflateInit2(&zs, 15 + 32) != Z_OK) return -1;  // 15+32: zlib or gzip wrapper
  std::vector<unsigned char> input(1 << 16), output(1 << 16);
  int rc = Z_OK;
  while (rc != Z_STREAM_END) {
    if (zs.avail_in == 0) {
      in.read(reinterpret_cast<char*>(input.data()),
              static_cast<std::streamsize>(std::min<std::uintmax_t>(input.size(), length)));
      if (in.gcount() <= 0) break;  // input exhausted before the end of the stream
      zs.next_in = input.data();
      zs.avail_in = static_cast<uInt>(in.gcount());
      length -= zs.avail_in;
    }
    zs.next_out = output.data();
    zs.avail_out = static_cast<uInt>(output.size());
    rc = inflate(&zs, Z_NO_FLUSH);
    if (rc != Z_OK && rc != Z_STREAM_END && rc != Z_BUF_ERROR) break;  // corrupt stream
    sink(output.data(), output.size() - zs.avail_out);
  }
  const std::int64_t total = rc == Z_STREAM_END ? static_cast<std::int64_t>(zs.total_out) : -1;
  inflateEnd(&zs);
  return total;
}

// Where a header's voxel bytes lie in its data file: from `start`, `length` bytes (raw data, or
// MetaImage's CompressedDataSize), or, for a compressed stream of unknown length, to the end of
// the file. Requires the data file to exist and to hold them (InputError otherwise); a compressed
// stream's contents are checked by whoever inflates it.
struct DataSpan {
  std::uintmax_t start = 0;
  std::uintmax_t length = 0;  ///< bytes from start: the declared length, or the rest of the file
};

DataSpan present_data_span(const ImageHeader& h, const std::string& path) {
  std::error_code ec;  // a name the file system refuses (too long, a loop) is a missing file
  if (!std::filesystem::exists(h.data_file, ec)) {
    throw InputError(path + ": voxel data file " + h.data_file + " does not exist" +
                     (ec ? " (" + ec.message() + ")" : ""));
  }
  const std::uintmax_t size = data_file_size(h.data_file, path);
  const bool length_known = !h.compressed || h.compressed_size >= 0;
  const std::uintmax_t length =
      h.compressed ? static_cast<std::uintmax_t>(std::max<std::int64_t>(h.compressed_size, 0))
                   : h.data_bytes();
  DataSpan span;
  if (h.data_offset >= 0) {
    span.start = static_cast<std::uintmax_t>(h.data_offset);
  } else if (length_known) {
    span.start = size - std::min(size, length);  // HeaderSize = -1: the data are the last bytes
  } else {
    throw InputError(path + ": HeaderSize = -1 needs CompressedDataSize for compressed data");
  }
  const std::uintmax_t available = size - std::min(size, span.start);
  if (length_known && available < length) {
    throw InputError(path + ": voxel data is truncated: " + h.data_file + " holds " +
                     std::to_string(available) + " bytes of voxel data, " + std::to_string(length) +
                     " expected");
  }
  span.length = length_known ? length : available;
  return span;
}

InputError corrupt_stream(const ImageHeader& h, const std::string& path) {
  return InputError(path + ": compressed voxel data is truncated or corrupt (it does not " +
                    "inflate to the " + std::to_string(h.data_bytes()) + " bytes expected)");
}

}  // namespace

bool stream_delivers(const std::string& file, std::uintmax_t offset, std::uintmax_t length,
                     std::size_t expected) {
  const std::int64_t total =
      inflate_stream(file, offset, length, [](const unsigned char*, std::size_t) {});
  return total >= 0 && static_cast<std::uint64_t>(total) >= expected;
}

// The header parsers have settled where the bytes are, and present_data_span that they are there;
// what is left is copying them, so MetaIO (vtkMetaImageReader), whose own header
// parser reads some headers differently from this one and overruns fixed buffers on others, is
// not in the path (docs/reliability.md).
std::vector<unsigned char> read_voxel_bytes(const ImageHeader& h, const std::string& path) {
  const DataSpan span = present_data_span(h, path);
  const std::size_t expected = h.data_bytes();
  std::vector<unsigned char> bytes;
  if (h.compressed) {
    bytes.reserve(expected);
    const std::int64_t total =
        inflate_stream(h.data_file, span.start, span.length, [&](const unsigned char* data, std::size_t n) {
          bytes.insert(bytes.end(), data, data + std::min(n, expected - bytes.size()));
        });
    if (total < 0 || bytes.size() != expected) throw corrupt_stream(h, path);
  } else {
    std::ifstream in(h.data_file, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(span.start));
    bytes.resize(expected);
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(expected));
    if (!in || static_cast<std::size_t>(in.gcount()) != expected) {
      throw InputError(path + ": voxel data file " + h.data_file + " could not be read to its end");
    }
  }
  const std::size_t value = voxel_type_bytes(h.type);
  const bool host_big_endian = [] {
    const std::uint16_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    return first == 0;
  }();
  if (value > 1 && h.big_endian != host_big_endian) {
    for (std::size_t i = 0; i + value <= bytes.size(); i += value) {
      std::reverse(bytes.begin() + static_cast<std::ptrdiff_t>(i),
                   bytes.begin() + static_cast<std::ptrdiff_t>(i + value));
    }
  }
  return bytes;
}

// VTK cannot be trusted to notice missing voxel bytes in every case: vtkImageReader (NRRD raw)
// only warns through the global output window, and MetaIO prints to std::cerr and leaves the
// missing voxels zero. So completeness is established here, before the voxels are read (by VTK
// for NRRD, by read_voxel_bytes for MetaImage).
void require_data_present(const ImageHeader& h, const std::string& path) {
  const DataSpan span = present_data_span(h, path);
  if (h.compressed && !stream_delivers(h.data_file, span.start, span.length, h.data_bytes())) {
    throw corrupt_stream(h, path);
  }
}

void require_nifti_header(const std::string& path) {
  const NiftiHeaderBytes h(path);
  const std::int32_t size = h.get<std::int32_t>(0);
  const bool nifti1 = h.got() >= 348 && size == 348 && h.text_at(344, "n+1", 4);
  const bool nifti2 = h.got() >= 540 && size == 540 && h.text_at(4, "n+2\0\r\n\032\n", 8);
  if (h.compressed() && (h.got() < 348 || !h.zlib_error().empty())) {
    throw InputError(path + ": gzip stream is truncated or corrupt (" +
                     (h.zlib_error().empty() ? "it ends after " + std::to_string(h.got()) + " bytes"
                                             : "zlib: " + h.zlib_error()) +
                     ", before the end of the NIfTI header)");
  }
  if (!nifti1 && !nifti2) {
    throw InputError(path + ": not a single-file NIfTI-1 or NIfTI-2 image (no n+1/n+2 header at " +
                     "its start" + (h.got() < 348 ? ", only " + std::to_string(h.got()) +
                     " readable bytes" : std::string()) + "); .hdr/.img pairs and Analyze files " +
                     "are not supported");
  }
  const int datatype = h.get<std::int16_t>(nifti1 ? 70 : 12);
  const int bitpix = h.get<std::int16_t>(nifti1 ? 72 : 14);
  static const std::pair<int, int> kTypes[] = {{2, 8},     {4, 16},    {8, 32},   {16, 32},
                                               {64, 64},   {256, 8},   {512, 16}, {768, 32},
                                               {1024, 64}, {1280, 64}};
  const auto known = std::find_if(std::begin(kTypes), std::end(kTypes),
                                  [&](const auto& t) { return t.first == datatype; });
  if (known == std::end(kTypes) || known->second != bitpix) {
    throw InputError(path + ": NIfTI datatype " + std::to_string(datatype) + " with bitpix " +
                     std::to_string(bitpix) + " is not a supported scalar voxel type");
  }
  const std::int64_t ndim = nifti1 ? h.get<std::int16_t>(40) : h.get<std::int64_t>(16);
  if (ndim < 1 || ndim > 7) {
    throw InputError(path + ": NIfTI dim[0] = " + std::to_string(ndim) + " is not 1 to 7 dimensions");
  }
  for (int a = 1; a <= ndim; ++a) {
    const std::int64_t n = nifti1 ? h.get<std::int16_t>(40 + 2 * a) : h.get<std::int64_t>(16 + 8 * a);
    if (n < 1) {
      throw InputError(path + ": NIfTI dim[" + std::to_string(a) + "] = " + std::to_string(n) +
                       " is not a voxel count of at least 1");
    }
  }
}

}  // namespace tissuemesh
