// Every input the fuzzers once failed on (fuzz/regressions/<target>/), and
// their seeds, read by the reader it was found in: read, or refused with
// InputError, nothing else.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "core/errors.h"
#include "helpers.h"
#include "io/file_utils.h"
#include "io/point_cloud_io.h"
#include "io/skeleton_io.h"

namespace mcquad {
namespace {

struct Reader {
  const char* extension;
  bool skeleton;
};

// As in fuzz/CMakeLists.txt.
const std::map<std::string, Reader> kTargets = {
    {"ply_cloud", {"ply", false}},     {"xyz_cloud", {"xyz", false}}, {"csv_cloud", {"csv", false}},
    {"obj_cloud", {"obj", false}},     {"off_cloud", {"off", false}}, {"obj_skeleton", {"obj", true}},
    {"cgal_skeleton", {"cgal", true}},
};

TEST(FuzzRegressions, EveryKeptInputIsReadOrRefusedWithInputError) {
  test::TempDir dir;
  size_t inputs = 0;
  for (const char* kind : {"seeds", "regressions"}) {
    for (const auto& [target, reader] : kTargets) {
      std::filesystem::path folder = std::filesystem::path(MCQUAD_FUZZ_DIR) / kind / target;
      if (!std::filesystem::is_directory(folder)) continue;
      for (const auto& entry : std::filesystem::directory_iterator(folder)) {
        std::string copy = dir.write(std::string("input.") + reader.extension, read_file(entry.path().string()));
        try {
          if (reader.skeleton)
            read_skeleton(copy);
          else
            read_point_cloud(copy, true);
        } catch (const InputError&) {
        } catch (const std::exception& e) {
          ADD_FAILURE() << entry.path() << ": " << e.what();
        }
        ++inputs;
      }
    }
  }
  EXPECT_GE(inputs, kTargets.size());  // at least the seeds
}

}  // namespace
}  // namespace mcquad
