#include "arrays.h"

#include <algorithm>

#include "core/errors.h"
#include "io/openmesh_messages.h"

namespace py = pybind11;

namespace mcquad {
namespace {

std::string shape_text(const py::array& a) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) text += (i ? ", " : "") + std::to_string(a.shape(i));
  return text + (a.ndim() == 1 ? ",)" : ")");
}

//! Rows of an (N, columns) array; an empty (0,) array counts as no rows.
size_t rows_of(const py::array& a, py::ssize_t columns, const std::string& name, const char* what) {
  if (a.ndim() == 1 && a.shape(0) == 0) return 0;
  if (a.ndim() != 2 || a.shape(1) != columns)
    throw InputError(name + ": " + what + " must have shape (N, " + std::to_string(columns) + "), not " +
                     shape_text(a));
  return size_t(a.shape(0));
}

template <typename T>
py::array_t<T> make_array(size_t rows, size_t columns) {
  return py::array_t<T>({py::ssize_t(rows), py::ssize_t(columns)});
}

}  // namespace

PointCloud cloud_from_array(const FloatArray& points, const std::string& name, const py::object& normals) {
  size_t n = rows_of(points, 3, name, "points");
  PointCloud cloud;
  cloud.points.resize(n);
  std::copy_n(points.data(), 3 * n, reinterpret_cast<float*>(cloud.points.data()));
  if (!normals.is_none()) {
    FloatArray given = normals.cast<FloatArray>();
    if (rows_of(given, 3, name, "normals") != n)
      throw InputError(name + ": " + std::to_string(given.shape(0)) + " normals for " + std::to_string(n) + " points");
    cloud.normals.resize(n);
    std::copy_n(given.data(), 3 * n, reinterpret_cast<float*>(cloud.normals.data()));
  }
  check_point_cloud(cloud, name);
  return cloud;
}

SkeletonData skeleton_from_arrays(const DoubleArray& nodes, const IndexArray& edges, const std::string& name) {
  size_t n = rows_of(nodes, 3, name, "skeleton nodes"), e = rows_of(edges, 2, name, "skeleton edges");
  SkeletonData skeleton;
  auto node = nodes.unchecked<2>();
  for (size_t i = 0; i < n; ++i) skeleton.nodes.emplace_back(node(i, 0), node(i, 1), node(i, 2));
  auto edge = edges.unchecked<2>();
  for (size_t i = 0; i < e; ++i) {
    for (int k = 0; k < 2; ++k)
      if (edge(i, k) < 0 || size_t(edge(i, k)) >= n)
        throw InputError(name + ": edge " + std::to_string(i) + " names node " + std::to_string(edge(i, k)) +
                         ", but there are " + std::to_string(n) + " nodes (indices are 0-based)");
    skeleton.edges.push_back({int(edge(i, 0)), int(edge(i, 1))});
  }
  return skeleton;
}

QuadMesh mesh_from_arrays(const DoubleArray& vertices, const IndexArray& faces, const std::string& name) {
  size_t n = rows_of(vertices, 3, name, "vertices");
  if (faces.ndim() != 2 || faces.shape(1) < 3)
    throw InputError(name + ": faces must have shape (F, k) with k >= 3, not " + shape_text(faces));
  QuadMesh mesh;
  auto v = vertices.unchecked<2>();
  for (size_t i = 0; i < n; ++i) {
    QuadMesh::Point p(v(i, 0), v(i, 1), v(i, 2));
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw InputError(name + ": vertex " + std::to_string(i) + " has a NaN or infinite coordinate");
    mesh.add_vertex(p);
  }
  auto f = faces.unchecked<2>();
  std::vector<QuadMesh::VertexHandle> corners;
  OpenMeshMessages quiet;  // a face OpenMesh refuses is named below, in one line
  for (py::ssize_t i = 0; i < faces.shape(0); ++i) {
    corners.clear();
    for (py::ssize_t k = 0; k < faces.shape(1); ++k) {
      int64_t index = f(i, k);
      if (index == -1) break;
      if (index < 0 || size_t(index) >= n)
        throw InputError(name + ": face " + std::to_string(i) + " names vertex " + std::to_string(index) + " of " +
                         std::to_string(n));
      corners.push_back(mesh.vertex_handle(unsigned(index)));
    }
    if (corners.size() < 3) throw InputError(name + ": face " + std::to_string(i) + " has fewer than 3 corners");
    if (!mesh.add_face(corners).is_valid())
      throw InputError(name + ": face " + std::to_string(i) +
                       " makes the mesh non-manifold or turns against its neighbours");
  }
  return mesh;
}

FloatArray points_of(const PointCloud& cloud) {
  auto out = make_array<float>(cloud.size(), 3);
  std::copy_n(cloud.data(), 3 * cloud.size(), out.mutable_data());
  return out;
}

DoubleArray nodes_of(const SkeletonData& skeleton) {
  auto out = make_array<double>(skeleton.nodes.size(), 3);
  auto o = out.mutable_unchecked<2>();
  for (size_t i = 0; i < skeleton.nodes.size(); ++i)
    for (int k = 0; k < 3; ++k) o(i, k) = skeleton.nodes[i][k];
  return out;
}

IndexArray edges_of(const SkeletonData& skeleton) {
  auto out = make_array<int64_t>(skeleton.edges.size(), 2);
  auto o = out.mutable_unchecked<2>();
  for (size_t i = 0; i < skeleton.edges.size(); ++i) o(i, 0) = skeleton.edges[i][0], o(i, 1) = skeleton.edges[i][1];
  return out;
}

DoubleArray vertices_of(const QuadMesh& mesh) {
  auto out = make_array<double>(mesh.n_vertices(), 3);
  auto o = out.mutable_unchecked<2>();
  for (auto v : mesh.vertices())
    for (int k = 0; k < 3; ++k) o(v.idx(), k) = mesh.point(v)[k];
  return out;
}

IndexArray faces_of(const QuadMesh& mesh) {
  size_t corners = 0;
  for (auto f : mesh.faces()) corners = std::max<size_t>(corners, mesh.valence(f));
  auto out = make_array<int64_t>(mesh.n_faces(), corners);
  auto o = out.mutable_unchecked<2>();
  for (auto f : mesh.faces()) {
    size_t k = 0;
    for (auto v : mesh.fv_range(f)) o(f.idx(), k++) = v.idx();
    for (; k < corners; ++k) o(f.idx(), k) = -1;
  }
  return out;
}

}  // namespace mcquad
