#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/shared_math.h"

namespace mcquad {
namespace {

using device::mcq_vec3;

// A closed ring of quads around the z axis, `round` quads round and `rows`
// high, as the flat arrays the kernels read; `inward` turns every face over.
struct QuadTube {
  std::vector<float> positions;
  std::vector<uint32_t> faces, vertex_face_offsets, vertex_faces;
  int round, rows;

  QuadTube(int round_, int rows_, double radius, double height, bool inward) : round(round_), rows(rows_) {
    for (int j = 0; j <= rows; ++j)
      for (int i = 0; i < round; ++i) {
        double angle = 2 * M_PI * i / round;
        positions.insert(positions.end(),
                         {float(radius * std::cos(angle)), float(radius * std::sin(angle)), float(height * j)});
      }
    std::vector<std::vector<uint32_t>> around(positions.size() / 3);
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < round; ++i) {
        uint32_t a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
        uint32_t face = uint32_t(faces.size() / 4);
        if (inward)
          faces.insert(faces.end(), {a, d, c, b});
        else
          faces.insert(faces.end(), {a, b, c, d});
        for (uint32_t v : {a, b, c, d}) around[v].push_back(face);
      }
    vertex_face_offsets.push_back(0);
    for (const auto& list : around) {
      vertex_faces.insert(vertex_faces.end(), list.begin(), list.end());
      vertex_face_offsets.push_back(uint32_t(vertex_faces.size()));
    }
  }
  uint32_t index(int i, int j) const { return uint32_t(j * round + (i % round + round) % round); }

  device::mcq_shape_operator shape_at(int i, int j, mcq_vec3 n) const {
    uint32_t v = index(i, j);
    return device::mcq_vertex_shape_operator(positions.data(), faces.data(), vertex_face_offsets.data(),
                                             vertex_faces.data(), v, device::mcq_load3(positions.data(), v), n);
  }
};

mcq_vec3 vec(double x, double y, double z) { return mcq_vec3{float(x), float(y), float(z)}; }

double quadratic(const device::mcq_shape_operator& k, mcq_vec3 x) { return device::mcq_shape_quadratic(k, x); }

TEST(ShapeOperator, CylinderIsCurvedAroundAndStraightAlong) {
  const double radius = 2.0;
  QuadTube tube(32, 4, radius, 0.4, false);
  for (int i : {0, 5, 11}) {
    double angle = 2 * M_PI * i / 32;
    mcq_vec3 outward = vec(std::cos(angle), std::sin(angle), 0);
    mcq_vec3 around = vec(-std::sin(angle), std::cos(angle), 0);
    auto k = tube.shape_at(i, 2, outward);
    EXPECT_NEAR(quadratic(k, around), 1 / radius, 0.03 / radius) << "vertex " << i;
    EXPECT_NEAR(quadratic(k, vec(0, 0, 1)), 0.0, 0.03 / radius);
    EXPECT_NEAR(quadratic(k, outward), 0.0, 1e-5) << "the operator lies in the tangent plane";
    // No twist: the diagonal tangent sees the mean of the two curvatures.
    mcq_vec3 diagonal = vec((around.x) / std::sqrt(2.0), (around.y) / std::sqrt(2.0), 1 / std::sqrt(2.0));
    EXPECT_NEAR(quadratic(k, diagonal), 0.5 / radius, 0.03 / radius);
  }
}

//! A vertex standing out of its ring (a bump) must not see the ring as more
//! convex, or the correction would push it further out.
TEST(ShapeOperator, TheVertexsOwnHeightDoesNotEnter) {
  const double radius = 2.0;
  QuadTube tube(32, 4, radius, 0.4, false);
  mcq_vec3 outward = vec(1, 0, 0);
  auto before = tube.shape_at(0, 2, outward);
  tube.positions[3 * tube.index(0, 2)] += 0.1f;  // out along its normal
  auto after = tube.shape_at(0, 2, outward);
  for (mcq_vec3 x : {vec(0, 1, 0), vec(0, 0, 1), vec(0, std::sqrt(0.5), std::sqrt(0.5))})
    EXPECT_NEAR(quadratic(after, x), quadratic(before, x), 1e-4);
}

TEST(ShapeOperator, ConcaveSideIsNegativeAndNotCapped) {
  const double radius = 2.0;
  QuadTube tube(32, 4, radius, 0.4, true);
  mcq_vec3 inward = vec(-1, 0, 0);
  auto k = tube.shape_at(0, 2, inward);
  EXPECT_NEAR(quadratic(k, vec(0, 1, 0)), -1 / radius, 0.03 / radius);
  EXPECT_NEAR(quadratic(k, vec(0, 0, 1)), 0.0, 0.03 / radius);
}

TEST(ShapeOperator, CurvatureSharperThanTwoAndAHalfEdgesIsCapped) {
  // Eight quads round: the true curvature 1/r is above the cap 0.4 / edge.
  const double radius = 1.0;
  QuadTube tube(8, 4, radius, 0.5, false);
  double edge_around = 2 * radius * std::sin(M_PI / 8), edge_along = 0.5;
  double cap = 0.4 * 4 / (2 * edge_around + 2 * edge_along);
  ASSERT_LT(cap, 1 / radius);
  auto k = tube.shape_at(0, 2, vec(1, 0, 0));
  EXPECT_NEAR(quadratic(k, vec(0, 1, 0)), cap, 1e-4);
}

TEST(ShapeOperator, IsZeroWithoutFaces) {
  QuadTube tube(16, 1, 1.0, 0.3, false);
  std::vector<uint32_t> no_faces(tube.vertex_face_offsets.size(), 0);
  auto k = device::mcq_vertex_shape_operator(tube.positions.data(), tube.faces.data(), no_faces.data(),
                                             tube.vertex_faces.data(), 0, device::mcq_load3(tube.positions.data(), 0),
                                             vec(1, 0, 0));
  EXPECT_EQ(quadratic(k, vec(0, 1, 0)), 0.0);
  EXPECT_EQ(quadratic(k, vec(0, 0, 1)), 0.0);
}

}  // namespace
}  // namespace mcquad
