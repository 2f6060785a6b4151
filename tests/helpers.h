#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "generate/shapes.h"

namespace mcquad::test {

//! A fresh directory under the system temp dir, removed at the end.
class TempDir {
 public:
  TempDir() {
    path_ = std::filesystem::temp_directory_path() /
            ("mcquad-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter()++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(file(name), std::ios::binary) << text;
    return file(name);
  }

 private:
  static int& counter() {
    static int c = 0;
    return c;
  }
  std::filesystem::path path_;
};

//! OpenCL tests may skip only outside CI: with CI=true or
//! MCQUAD_REQUIRE_OPENCL=1 a missing device is a failure.
inline bool opencl_required() {
  const char* ci = std::getenv("CI");
  const char* require = std::getenv("MCQUAD_REQUIRE_OPENCL");
  return (ci && std::string(ci) == "true") || (require && std::string(require) == "1");
}

inline GeneratedShape small_shape(const std::string& name, size_t points, ShapeOptions options = {}) {
  options.points = points;
  return generate_shape(name, options);
}

}  // namespace mcquad::test
