#include "fuzz_scratch.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace tissuemesh::fuzz {
namespace {

const std::filesystem::path& scratch_folder() {
  static const std::filesystem::path folder = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::filesystem::path p = std::filesystem::path(tmp && *tmp ? tmp : "/tmp") /
                              ("tissuemesh-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(p);
    return p;
  }();
  return folder;
}

}  // namespace

std::string write_scratch(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = scratch_folder() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) {
    std::fprintf(stderr, "fuzz setup: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path.string();
}

std::string write_image_input(const std::uint8_t* data, std::size_t size,
                              const std::string& attached_name, const std::string& header_name,
                              std::initializer_list<const char*> data_names) {
  static const std::string kSeparator = "\n@@detached@@\n";
  const std::string all(reinterpret_cast<const char*>(data), size);
  const std::size_t at = all.find(kSeparator);
  if (at == std::string::npos) {
    std::error_code ec;
    for (const char* name : data_names) std::filesystem::remove(scratch_folder() / name, ec);
    return write_scratch(attached_name, data, size);
  }
  const std::string header = all.substr(0, at) + "\n";
  const std::string voxels = all.substr(at + kSeparator.size());
  for (const char* name : data_names) {
    write_scratch(name, reinterpret_cast<const std::uint8_t*>(voxels.data()), voxels.size());
  }
  return write_scratch(header_name, reinterpret_cast<const std::uint8_t*>(header.data()),
                       header.size());
}

}  // namespace tissuemesh::fuzz
