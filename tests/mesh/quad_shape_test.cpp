#include <gtest/gtest.h>

#include <cmath>

#include "mesh/quad_shape.h"

namespace mcquad {
namespace {

QuadMesh one_quad(std::initializer_list<std::array<double, 2>> corners) {
  QuadMesh mesh;
  std::vector<QuadMesh::VertexHandle> v;
  for (const auto& c : corners) v.push_back(mesh.add_vertex(QuadMesh::Point(c[0], c[1], 0)));
  mesh.add_face(v);
  return mesh;
}

TEST(QuadShape, SquareRhombusRectangleAndConcaveQuads) {
  QuadShape square = measure_quad_shape(one_quad({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  EXPECT_NEAR(square.min_scaled_jacobian, 1, 1e-12);
  EXPECT_NEAR(square.max_edge_ratio, 1, 1e-12);
  EXPECT_NEAR(square.min_angle, 90, 1e-9);
  EXPECT_NEAR(square.max_angle, 90, 1e-9);
  EXPECT_EQ(square.faces_below_half, 0u);

  double c = std::cos(M_PI / 3), s = std::sin(M_PI / 3);  // a rhombus of 60 and 120 degrees
  QuadShape rhombus = measure_quad_shape(one_quad({{0, 0}, {1, 0}, {1 + c, s}, {c, s}}));
  EXPECT_NEAR(rhombus.min_scaled_jacobian, s, 1e-12);
  EXPECT_NEAR(rhombus.min_angle, 60, 1e-9);
  EXPECT_NEAR(rhombus.max_angle, 120, 1e-9);

  QuadShape rectangle = measure_quad_shape(one_quad({{0, 0}, {3, 0}, {3, 1}, {0, 1}}));
  EXPECT_NEAR(rectangle.max_edge_ratio, 3, 1e-12);
  EXPECT_NEAR(rectangle.min_scaled_jacobian, 1, 1e-12);

  // A dart: the corner at (0.5, 0.5) is reflex, so its scaled Jacobian is negative.
  QuadShape dart = measure_quad_shape(one_quad({{0, 0}, {2, 0}, {0.5, 0.5}, {0, 2}}));
  EXPECT_LT(dart.min_scaled_jacobian, 0);
  EXPECT_EQ(dart.faces_below_half, 1u);
}

}  // namespace
}  // namespace mcquad
