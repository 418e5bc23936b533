#include "support/test_helpers.h"

#include "core/errors.h"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>

namespace tissuemesh::test {

std::string read_file(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

void expect_no_nan_text(const std::string& text) {
  static const std::regex kBad(R"((^|[^A-Za-z_])(nan|inf|infinity)([^A-Za-z_]|$))", std::regex::icase);
  EXPECT_FALSE(std::regex_search(text, kBad)) << text.substr(0, 400);
}

std::string input_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

LabelImage nested_spheres(double inner_mm, double outer_mm) {
  LabelImage img;
  img.dims = {40, 40, 27};
  img.spacing = {1.0, 1.0, 1.5};
  img.labels.resize(img.voxel_count());
  for (int k = 0; k < img.dims[2]; ++k)
    for (int j = 0; j < img.dims[1]; ++j)
      for (int i = 0; i < img.dims[0]; ++i) {
        const double r = Eigen::Vector3d(i - 19.5, j - 19.5, 1.5 * (k - 13)).norm();
        img.labels[img.index(i, j, k)] = r < inner_mm ? 2 : (r < outer_mm ? 1 : 0);
      }
  return img;
}

}  // namespace tissuemesh::test
