#include "io/mesh_io.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <filesystem>

#include "core/errors.h"
#include "io/file_utils.h"
#include "io/openmesh_messages.h"

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

bool stl_extension(const std::string& ext) { return ext == "stl" || ext == "stla"; }

//! The mesh with every quad split in two triangles along its shorter
//! diagonal (the split that keeps the triangles fuller), other polygons as fans.
QuadMesh triangulated(const QuadMesh& mesh) {
  QuadMesh out;
  for (auto v : mesh.vertices()) out.add_vertex(mesh.point(v));
  std::vector<QuadMesh::VertexHandle> c;
  for (auto f : mesh.faces()) {
    c.assign(mesh.fv_range(f).begin(), mesh.fv_range(f).end());
    auto corner = [&](size_t i) { return out.vertex_handle(unsigned(c[i].idx())); };
    if (c.size() == 4 &&
        (mesh.point(c[1]) - mesh.point(c[3])).sqrnorm() < (mesh.point(c[0]) - mesh.point(c[2])).sqrnorm()) {
      out.add_face(corner(0), corner(1), corner(3));
      out.add_face(corner(1), corner(2), corner(3));
      continue;
    }
    for (size_t i = 1; i + 1 < c.size(); ++i) out.add_face(corner(0), corner(i), corner(i + 1));
  }
  return out;
}

}  // namespace

const char* const kMeshOutputExtensions = ".obj, .off, .ply, .om, .stl (binary triangles) or .stla (ASCII triangles)";

void write_mesh(const std::string& path, const QuadMesh& mesh) {
  std::string ext = file_extension(path);
  if (!supported_mesh_extension(ext) && !stl_extension(ext))
    throw OutputError(path + ": unknown mesh extension '." + ext + "' (expected " + kMeshOutputExtensions + ")");
  silence_openmesh();
  write_atomically(path, [&](const std::string& temporary) {
    OpenMesh::IO::Options options;
    if (ext == "ply" || ext == "om" || ext == "stl") options += OpenMesh::IO::Options::Binary;
    bool written = stl_extension(ext) ? OpenMesh::IO::write_mesh(triangulated(mesh), temporary, options, 10)
                                      : OpenMesh::IO::write_mesh(mesh, temporary, options, 10);
    if (!written) throw OutputError(path + ": cannot write mesh");
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
  // A face OpenMesh cannot hold is dropped or given copies of its corners,
  // with a message and nothing else: measured as it is read, a mesh whose
  // edge three faces share would pass for a manifold one. Refused instead.
  size_t complex_edges = 0, complex_vertices = 0, invalid_faces = 0;
  {
    OpenMeshMessages messages;
    if (!OpenMesh::IO::read_mesh(mesh, path, options)) throw InputError(path + ": cannot read mesh");
    complex_edges = messages.count("add_face: complex edge");
    complex_vertices = messages.count("add_face: complex vertex");
    invalid_faces = messages.count("invalid vertex index") + messages.count("invalid faces");
  }
  if (const size_t n = complex_edges + complex_vertices; n > 0)
    throw InputError(path + ": not a manifold mesh: " + std::to_string(n) + (n == 1 ? " face meets" : " faces meet") +
                     " an edge two faces already share, or a corner between two separate fans of faces, which "
                     "mcquad's mesh structure cannot hold");
  if (invalid_faces > 0)
    throw InputError(path + ": " + std::to_string(invalid_faces) +
                     (invalid_faces == 1 ? " face names a vertex" : " faces name vertices") +
                     " that the file does not have");
  if (mesh.n_faces() == 0) throw InputError(path + ": the mesh has no faces");
  return mesh;
}

}  // namespace mcquad
