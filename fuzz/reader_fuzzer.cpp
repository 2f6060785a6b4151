// libFuzzer target for one reader: the input bytes become a file with the
// reader's extension, and the reader must either read it or throw
// InputError. Anything else (another exception, a crash, a leak, a hang,
// an address or undefined-behaviour error) is a bug. Built once per reader
// with MCQUAD_FUZZ_READER (cloud, skeleton or mesh) and MCQUAD_FUZZ_EXTENSION.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "core/errors.h"
#include "io/mesh_io.h"
#include "io/point_cloud_io.h"
#include "io/skeleton_io.h"

namespace {

//! One scratch file per process, in memory where the system has a tmpfs.
const std::string& scratch_path() {
  static const std::string path = [] {
    std::string dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    return dir + "/mcquad-fuzz-" + std::to_string(getpid()) + "." MCQUAD_FUZZ_EXTENSION;
  }();
  return path;
}

void read_once(const std::string& path) {
  using namespace mcquad;
  const std::string reader = MCQUAD_FUZZ_READER;
  if (reader == "cloud")
    read_point_cloud(path, true);
  else if (reader == "skeleton")
    read_skeleton(path);
  else
    read_mesh(path);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string& path = scratch_path();
  FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) return 0;
  std::fwrite(data, 1, size, file);
  std::fclose(file);
  try {
    read_once(path);
  } catch (const mcquad::InputError&) {
    // The expected answer to a malformed file.
  }
  std::remove(path.c_str());
  return 0;
}
