// Scratch files for fuzz targets whose reader takes a path, not bytes.
//
// One folder per process (under $TMPDIR, else /tmp), created on first use and reused for every
// input: each call overwrites the named file, so a run of millions of inputs leaves a handful of
// files. The folder is not removed at exit (libFuzzer ends a run with _exit on a finding, and the
// last input is what one wants to look at then).
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>

namespace tissuemesh::fuzz {

/// Writes `size` bytes to `name` inside this process's scratch folder and returns the file's path.
/// Aborts (a fuzzing setup error, not a finding) when the file cannot be written.
std::string write_scratch(const std::string& name, const std::uint8_t* data, std::size_t size);

/// The input layout of the targets whose format has a text header that may name a data file
/// (NRRD, MetaImage): an input holding the line "@@detached@@" is a detached pair, the text before
/// it (plus a newline) written as `header_name` and the bytes after it as each of `data_names`
/// (the seeds' headers name one of them); any other input is written whole as `attached_name`,
/// and the data files of an earlier input are removed (a run stays reproducible input by input).
/// Returns the path of the file to read.
std::string write_image_input(const std::uint8_t* data, std::size_t size,
                              const std::string& attached_name, const std::string& header_name,
                              std::initializer_list<const char*> data_names);

}  // namespace tissuemesh::fuzz
