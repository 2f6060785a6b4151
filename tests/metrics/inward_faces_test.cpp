// Which faces face inward, told by the scan's own normals: none on a mesh
// that faces out, all on one turned inside out, and exactly the faces whose
// nearby normals say so, by their share of the area.
#include <gtest/gtest.h>

#include "metrics/mesh_metrics.h"

namespace mcquad {
namespace {

//! The cube [-1, 1]^3 as six quads; `outward` picks the orientation.
QuadMesh cube(bool outward) {
  QuadMesh mesh;
  std::vector<QuadMesh::VertexHandle> v;
  for (int i = 0; i < 8; ++i)
    v.push_back(mesh.add_vertex(QuadMesh::Point(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1)));
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    std::vector<QuadMesh::VertexHandle> corners{v[size_t(f[0])], v[size_t(f[1])], v[size_t(f[2])], v[size_t(f[3])]};
    if (!outward) std::reverse(corners.begin(), corners.end());
    mesh.add_face(corners);
  }
  return mesh;
}

//! Points on the cube's faces with their outward normals, a grid per face;
//! the normals of the face `flipped` (-1: none) point in.
OrientedSample cube_scan(int flipped) {
  OrientedSample scan;
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {-1, 1}) {
      int face = 2 * axis + (side > 0);
      for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) {
          Eigen::Vector3f p, n = Eigen::Vector3f::Zero();
          p[axis] = float(side);
          p[(axis + 1) % 3] = -0.8f + 0.4f * float(i);
          p[(axis + 2) % 3] = -0.8f + 0.4f * float(j);
          n[axis] = float(face == flipped ? -side : side);
          scan.points.push_back(p);
          scan.normals.push_back(n);
        }
    }
  return scan;
}

TEST(InwardFaces, NoneOnAnOutwardMeshAllOnOneInsideOut) {
  EXPECT_TRUE(faces_against_normals(cube(true), cube_scan(-1)).empty());
  QuadMesh inverted = cube(false);
  std::vector<int> inward = faces_against_normals(inverted, cube_scan(-1));
  EXPECT_EQ(inward.size(), 6u);
  EXPECT_DOUBLE_EQ(area_fraction(inverted, inward), 1.0);
}

TEST(InwardFaces, TheFacesTheNormalsDisagreeWithByTheirArea) {
  QuadMesh mesh = cube(true);
  std::vector<int> inward = faces_against_normals(mesh, cube_scan(3));  // +y's normals point in
  ASSERT_EQ(inward.size(), 1u);
  EXPECT_GT(face_centroid(mesh, inward[0]).y(), 0.9);
  EXPECT_NEAR(area_fraction(mesh, inward), 1.0 / 6.0, 1e-12);
}

TEST(InwardFaces, ScanNormalsDecideOverTheSkeletonInTheMetrics) {
  QuadMesh mesh = cube(true);
  PointCloud cloud;
  OrientedSample scan = cube_scan(3);
  cloud.points = scan.points;
  CellTree cells = build_cell_tree(cloud, 6);
  ScanOrientation orientation(scan);
  QualityMetrics by_normals = measure_quality(mesh, cloud, cells, nullptr, &orientation);
  EXPECT_EQ(by_normals.inward_reference, "scan normals");
  EXPECT_EQ(by_normals.inward_faces, 1);
  EXPECT_NEAR(by_normals.inward_area_fraction, 1.0 / 6.0, 1e-12);
  ASSERT_EQ(by_normals.inward_sites.size(), 1u);
  QualityMetrics unmeasured = measure_quality(mesh, cloud, cells, nullptr, nullptr);
  EXPECT_EQ(unmeasured.inward_faces, -1);
  EXPECT_LT(unmeasured.inward_area_fraction, 0.0);
}

TEST(OrientedSample, KeepsOnlyUsableNormalsAndAtMostTheAskedNumber) {
  PointCloud cloud;
  for (int i = 0; i < 100; ++i) {
    cloud.points.emplace_back(float(i), 0, 0);
    cloud.normals.emplace_back(i % 10 == 0 ? Eigen::Vector3f::Zero() : Eigen::Vector3f(0, 0, 2));
  }
  OrientedSample all = oriented_sample(cloud, 1000);
  EXPECT_EQ(all.points.size(), 90u);  // the zero normals (generated outliers) left out
  for (const auto& n : all.normals) EXPECT_FLOAT_EQ(n.norm(), 1.0f);
  EXPECT_LE(oriented_sample(cloud, 25).points.size(), 25u);
  cloud.normals.clear();
  EXPECT_TRUE(oriented_sample(cloud).empty());
}

//! A quad bent like a roof along its 0-2 diagonal, over a scan whose
//! normal at the raised triangle (corners 0 2 3, as a viewer draws it)
//! points across it, and up elsewhere, nearest the quad's centre too: that
//! triangle is turned, the quad's mean normal is not. Judged by triangles
//! the quad faces inward, by exactly that triangle's area; judged whole it
//! does not.
TEST(InwardFaces, ABentQuadIsTurnedWhereOneOfItsTrianglesIs) {
  QuadMesh mesh;
  std::vector<QuadMesh::VertexHandle> v{
      mesh.add_vertex(QuadMesh::Point(0, 0, 0)), mesh.add_vertex(QuadMesh::Point(2, 0, 0)),
      mesh.add_vertex(QuadMesh::Point(2, 2, 0)), mesh.add_vertex(QuadMesh::Point(0, 2, 2))};
  mesh.add_face(v);
  OrientedSample scan;
  scan.points = {{4.0f / 3, 2.0f / 3, 0}, {2.0f / 3, 4.0f / 3, 2.0f / 3}, {1, 1, 0.45f}};
  scan.normals = {{0, 0, 1}, {0, 1, 0}, {0, 0, 1}};
  ScanOrientation orientation(scan);
  EXPECT_TRUE(orientation.faces_inward(mesh, 0, ScanOrientation::FaceTest::kTriangles));
  EXPECT_FALSE(orientation.faces_inward(mesh, 0, ScanOrientation::FaceTest::kWhole));
  const double flat = 2.0, raised = 0.5 * Eigen::Vector3d(4, -4, 4).norm();  // triangles 0 1 2 and 0 2 3
  EXPECT_NEAR(orientation.inward_area(mesh, 0), raised, 1e-6);
  EXPECT_NEAR(orientation.inward_area_fraction(mesh, {0}), raised / (flat + raised), 1e-6);
}

}  // namespace
}  // namespace mcquad
