#include <gtest/gtest.h>

#include "mesh/crossing_guard.h"
#include "mesh/mesh_arrays.h"

namespace mcquad {
namespace {

//! Two unit squares, A at z = 0 and B at z = 1 over A's far half, both
//! facing +z: vertices 0-3 are A's, 4-7 B's.
MeshArrays two_squares() {
  QuadMesh mesh;
  std::vector<QuadMesh::VertexHandle> v;
  for (double z : {0.0, 1.0})
    for (auto [x, y] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}})
      v.push_back(mesh.add_vertex(QuadMesh::Point(x + 0.5 * z, y, z)));
  mesh.add_face(v[0], v[1], v[2], v[3]);
  mesh.add_face(v[4], v[5], v[6], v[7]);
  return flatten_mesh(mesh);
}

float z_of(const std::vector<float>& p, int v) { return p[3 * size_t(v) + 2]; }

TEST(CrossingGuard, AStepThroughAnotherFaceIsShortenedUntilItNoLongerCrosses) {
  MeshArrays mesh = two_squares();
  CrossingGuard guard(mesh);
  std::vector<float> before = mesh.positions, after = before;
  after[3 * 2 + 2] = 1.8f;   // A's corner under B rises through B ...
  after[3 * 0 + 0] = -0.1f;  // ... while another corner of A moves in its plane
  after[3 * 5 + 2] = 1.1f;   // and B rises a little, crossing nothing
  ASSERT_FALSE(guard.defects(after).empty());
  EXPECT_EQ(guard.apply(before, after), (std::vector<uint32_t>{0, 2})) << "the corners of A that moved, not B's";
  EXPECT_TRUE(guard.defects(after).empty());
  // A moved further than B, so A gives way: its corners take half their
  // steps, enough here (0.9 < 1); B keeps its whole step.
  EXPECT_FLOAT_EQ(z_of(after, 2), 0.9f);
  EXPECT_FLOAT_EQ(after[0], -0.05f);
  EXPECT_FLOAT_EQ(z_of(after, 5), 1.1f);
}

TEST(CrossingGuard, AFaceTurnedOverItsStartIsHeldBack) {
  MeshArrays mesh = two_squares();
  CrossingGuard guard(mesh);
  std::vector<float> before = mesh.positions, after = before;
  // B's corner 6 swings far across the diagonal from 5 to 7: B turns over.
  after[3 * 6 + 0] = -2.0f;
  after[3 * 6 + 1] = -2.0f;
  ASSERT_FALSE(guard.defects(after).empty());
  guard.apply(before, after);
  EXPECT_TRUE(guard.defects(after).empty());
  EXPECT_GT(after[3 * 6 + 0], -2.0f);
}

TEST(CrossingGuard, DefectsAlreadyThereAreLeftAlone) {
  MeshArrays mesh = two_squares();
  mesh.positions[3 * 2 + 2] = 1.8f;  // A pierces B from the start
  CrossingGuard guard(mesh);
  std::vector<float> before = mesh.positions, after = before;
  after[3 * 2 + 2] = 1.9f;
  EXPECT_TRUE(guard.apply(before, after).empty());
  EXPECT_FLOAT_EQ(z_of(after, 2), 1.9f);
}

//! What a device's test of a step reads (GuardArrays) holds every vertex's
//! reference and the close pairs, also right after the gap has widened
//! (the list is made again at once: an empty one would let a device pass
//! crossings it never tested).
TEST(CrossingGuard, DeviceArraysStayWholeWhenTheGapWidens) {
  MeshArrays mesh = two_squares();
  CrossingGuard guard(mesh);
  auto check = [&](const char* when) {
    GuardArrays arrays = guard.device_arrays();
    EXPECT_EQ(arrays.references.size(), mesh.positions.size()) << when;
    EXPECT_EQ(arrays.references, mesh.positions) << when;
    EXPECT_EQ(arrays.triangle_corners.size(), 3 * 2 * mesh.face_count()) << when;
    EXPECT_EQ(arrays.jacobian_floors.size(), mesh.face_count()) << when;
    EXPECT_GT(arrays.move_limit, 0.0) << when;
    return arrays;
  };
  GuardArrays first = check("at the start");
  const size_t version = guard.close_pairs_version();
  for (int k = 0; k < CrossingGuard::kMostWidenings; ++k) ASSERT_TRUE(guard.widen_close_pairs());
  EXPECT_FALSE(guard.widen_close_pairs()) << "at most kMostWidenings times";
  EXPECT_NE(guard.close_pairs_version(), version);
  GuardArrays widened = check("widened");
  // The squares' triangles lie 1 apart in z: within 4 times the first gap
  // (half the mean edge, about 0.57), not within the first gap itself.
  EXPECT_TRUE(first.close_pairs.empty());
  EXPECT_FALSE(widened.close_pairs.empty());
  EXPECT_GT(widened.move_limit, first.move_limit);
}

TEST(CrossingGuard, NothingToDoWithoutDefects) {
  MeshArrays mesh = two_squares();
  CrossingGuard guard(mesh);
  std::vector<float> before = mesh.positions, after = before;
  for (float& x : after) x += 0.25f;
  std::vector<float> expected = after;
  EXPECT_TRUE(guard.apply(before, after).empty());
  EXPECT_EQ(after, expected);
}

}  // namespace
}  // namespace mcquad
