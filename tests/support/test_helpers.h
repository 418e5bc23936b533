// Small helpers shared by the test suites.
#pragma once

#include "core/label_image.h"

#include <filesystem>
#include <functional>
#include <string>

namespace tissuemesh::test {

/// Whole content of a file ("" if missing).
std::string read_file(const std::filesystem::path& path);

/// Expects no NaN or infinity spelled out in a JSON text (nlohmann writes them as null, a printf
/// as nan/inf); a word that merely contains the letters, e.g. in a path, is not one.
void expect_no_nan_text(const std::string& text);

/// The message of the InputError `f` throws, or "no error".
std::string input_error_of(const std::function<void()>& f);

/// Two nested spheres on a 40 x 40 x 27 grid of 1 x 1 x 1.5 mm voxels, centred at voxel
/// (19.5, 19.5, 13): label 2 inside radius `inner_mm`, label 1 out to `outer_mm`, 0 outside.
LabelImage nested_spheres(double inner_mm = 9.0, double outer_mm = 16.0);

}  // namespace tissuemesh::test
