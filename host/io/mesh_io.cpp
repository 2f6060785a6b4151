#include "io/mesh_io.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <filesystem>

#include "core/errors.h"
#include "io/file_utils.h"

namespace mcquad {
namespace {

//! OpenMesh's writers log chatter ("write file") to stdout; mcquad reports itself.
void silence_openmesh() {
  omlog().disable();
  omout().disable();
}

bool supported_mesh_extension(const std::string& ext) {
  return ext == "obj" || ext == "off" || ext == "ply" || ext == "om";
}

}  // namespace

void write_mesh(const std::string& path, const QuadMesh& mesh) {
  std::string ext = file_extension(path);
  if (!supported_mesh_extension(ext))
    throw OutputError(path + ": unknown mesh extension '." + ext + "' (expected .obj, .off, .ply or .om)");
  silence_openmesh();
  write_atomically(path, [&](const std::string& temporary) {
    OpenMesh::IO::Options options;
    if (ext == "ply" || ext == "om") options += OpenMesh::IO::Options::Binary;
    if (!OpenMesh::IO::write_mesh(mesh, temporary, options, 10))
      throw OutputError(path + ": cannot write mesh");
  });
}

QuadMesh read_mesh(const std::string& path) {
  std::string ext = file_extension(path);
  if (!supported_mesh_extension(ext))
    throw InputError(path + ": unknown mesh extension '." + ext + "' (expected .obj, .off, .ply or .om)");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path + ": cannot open: no such file");
  silence_openmesh();
  QuadMesh mesh;
  OpenMesh::IO::Options options;
  if (!OpenMesh::IO::read_mesh(mesh, path, options)) throw InputError(path + ": cannot read mesh");
  if (mesh.n_faces() == 0) throw InputError(path + ": the mesh has no faces");
  return mesh;
}

}  // namespace mcquad
