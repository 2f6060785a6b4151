#include <gtest/gtest.h>

#include "io/file_utils.h"

#include <cmath>
#include <filesystem>

#include "core/errors.h"
#include "evolution/evolve.h"
#include "evolution/serial_backend.h"
#include "helpers.h"
#include "mesh/initial_mesh.h"
#include "metrics/mesh_metrics.h"
#include "pipeline/prepare.h"
#include "skeleton/skeleton_graph.h"
#include "surfaces/cad_model.h"
#include "surfaces/surface_checks.h"
#include "surfaces/surface_model.h"

namespace mcquad {
namespace {

constexpr double kMajor = 3.0, kMinor = 1.0;

Eigen::Vector3d torus_point(double along, double around) {
  double ring = kMajor + kMinor * std::cos(around);
  return {ring * std::cos(along), ring * std::sin(along), kMinor * std::sin(around)};
}

//! A torus of `along` x `around` quads whose rings come back rotated by
//! `shift` steps when the loop closes (as a swept loop's rings may).
QuadMesh torus_grid(int along, int around, int shift) {
  QuadMesh mesh;
  std::vector<QuadMesh::VertexHandle> v;
  for (int i = 0; i < along; ++i)
    for (int j = 0; j < around; ++j) {
      // Twist the rings gradually so that ring `along` is ring 0 turned by `shift`.
      double a = 2 * M_PI * i / along, b = 2 * M_PI * (j + double(shift) * i / along) / around;
      Eigen::Vector3d p = torus_point(a, b);
      v.push_back(mesh.add_vertex(QuadMesh::Point(p.x(), p.y(), p.z())));
    }
  auto at = [&](int i, int j) {
    if (i == along) i = 0, j += shift;
    return v[size_t(i) * size_t(around) + size_t(((j % around) + around) % around)];
  };
  for (int i = 0; i < along; ++i)
    for (int j = 0; j < around; ++j) mesh.add_face(at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
  return mesh;
}

double torus_distance(const Eigen::Vector3d& p) {
  return std::abs(std::hypot(std::hypot(p.x(), p.y()) - kMajor, p.z()) - kMinor);
}

Eigen::Vector3d point_of(const QuadMesh& mesh, int v) {
  const auto& p = mesh.point(QuadMesh::VertexHandle(v));
  return {p[0], p[1], p[2]};
}

//! Every surface passes through its region's vertices at their parameters.
void expect_interpolates_vertices(const QuadMesh& mesh, const SurfaceModel& model, double tolerance) {
  for (size_t r = 0; r < model.surfaces.size(); ++r) {
    const PatchRegion& region = model.layout.regions[r];
    SurfaceEvaluator surface(model.surfaces[r]);
    for (int j = 0; j < region.rows; ++j)
      for (int i = 0; i < region.columns; ++i)
        ASSERT_LT((surface.point(i, j) - point_of(mesh, region.vertex(i, j))).norm(), tolerance)
            << "region " << r << " vertex (" << i << ", " << j << ")";
  }
}

//! Each face lies in exactly one region, and the region's grid holds its corners.
void expect_partition(const QuadMesh& mesh, const PatchLayout& layout) {
  std::vector<int> seen(mesh.n_faces(), 0);
  for (const PatchRegion& region : layout.regions)
    for (int f : region.faces) seen[size_t(f)] += 1;
  for (int count : seen) ASSERT_EQ(count, 1);
  EXPECT_EQ(layout.single_face_fallbacks, 0u);
}

TEST(PatchLayout, TorusIsOneDoublyPeriodicSurface) {
  QuadMesh mesh = torus_grid(24, 10, 0);
  SurfaceModel model = build_surface_model(mesh);
  ASSERT_EQ(model.layout.regions.size(), 1u);
  const PatchRegion& region = model.layout.regions[0];
  EXPECT_TRUE(region.periodic_u && region.periodic_v);
  EXPECT_EQ(region.columns * region.rows, 240);
  expect_interpolates_vertices(mesh, model, 1e-9);
  SurfaceChecks checks = check_surfaces(mesh, model.layout, model.surfaces, nullptr);
  EXPECT_EQ(checks.seam_edges, 0u);
  // At the middle of every face, the smooth surface lies far closer to the
  // true torus than the flat quad does.
  SurfaceEvaluator surface(model.surfaces[0]);
  double worst_spline = 0, worst_quad = 0;
  for (auto f : mesh.faces()) {
    const auto& corners = model.layout.face_corner_parameters[size_t(f.idx())];
    Eigen::Vector2d middle = (corners[0] + corners[1] + corners[2] + corners[3]) / 4;
    Eigen::Vector3d quad_middle = Eigen::Vector3d::Zero();
    for (auto v : mesh.fv_range(f)) quad_middle += point_of(mesh, v.idx()) / 4;
    worst_spline = std::max(worst_spline, torus_distance(surface.point(middle.x(), middle.y())));
    worst_quad = std::max(worst_quad, torus_distance(quad_middle));
  }
  EXPECT_LT(worst_spline, 0.05 * worst_quad);
}

TEST(PatchLayout, TorusClosingWithARotationHasOneSmoothSelfSeam) {
  QuadMesh mesh = torus_grid(24, 10, 3);
  SurfaceModel model = build_surface_model(mesh);
  ASSERT_EQ(model.layout.regions.size(), 1u);
  const PatchRegion& region = model.layout.regions[0];
  EXPECT_FALSE(region.periodic_u);
  EXPECT_TRUE(region.periodic_v);
  EXPECT_EQ(region.columns, 25);  // the first ring again, turned, closes the surface
  EXPECT_EQ(region.rows, 10);
  expect_interpolates_vertices(mesh, model, 1e-9);
  SurfaceChecks checks = check_surfaces(mesh, model.layout, model.surfaces, nullptr);
  EXPECT_EQ(checks.seam_edges, 10u);
  EXPECT_LT(checks.max_position_gap, 1e-9);
  // Every seam vertex is regular: central differences on both sides agree.
  EXPECT_LT(checks.max_normal_gap_degrees, 1e-6);
}

struct ShapeCase {
  const char* shape;
  size_t points;
};

class SurfacesOnShapes : public ::testing::TestWithParam<ShapeCase> {};

TEST_P(SurfacesOnShapes, RegionsAreGridsAndSurfacesMeetAlongTheirSeams) {
  GeneratedShape shape = test::small_shape(GetParam().shape, GetParam().points);
  SkeletonGraph graph = build_skeleton_graph(shape.skeleton, GetParam().shape);
  // The seams' tangent check needs a mesh that is smooth two edges from its
  // irregular vertices. The junctions' inflation leaves the fitted theta a
  // crease there (surfaces 4.3 degrees apart, 0.6 without it; the mesh's
  // own, docs/DESIGN.md), so this checks the surfaces on the uninflated fit,
  // its blocks at the tubes' start fraction (grown, 4.1 degrees).
  // The facing cells leave quads near the theta's junctions less square
  // (least scaled Jacobian 0.54 -> 0.33) and its surfaces 7.2 degrees apart
  // at a seam there (docs/DESIGN.md), so they are off here too.
  InitialMeshOptions smooth_start;
  smooth_start.junction_inflation = 0;
  smooth_start.block_fraction = smooth_start.start_fraction;
  EvolutionSetup setup = prepare_evolution(graph, shape.cloud, smooth_start, 6, GetParam().shape);
  EvolutionParameters parameters;
  parameters.epsilon = automatic_epsilon(setup.median_radius);
  parameters.facing_cells = false;
  SerialBackend backend;
  backend.load(setup.cells, setup.arrays, setup.regions);
  QuadMesh mesh = setup.initial.mesh;
  set_positions(mesh, evolve(backend, setup.arrays, parameters).positions);
  SurfaceModel model = build_surface_model(mesh);
  expect_partition(mesh, model.layout);
  const double scale = setup.median_radius;
  expect_interpolates_vertices(mesh, model, 1e-9 * scale);
  SurfaceChecks checks = check_surfaces(mesh, model.layout, model.surfaces, &shape.cloud);
  EXPECT_EQ(checks.seam_edges > 0, model.layout.irregular_vertices > 0);
  EXPECT_LT(checks.max_position_gap, 1e-9 * scale);  // both sides interpolate the same curve
  // Where the quad mesh is smooth, tangent planes agree across seams away
  // from irregular vertices (both sides take the same harmonic tangents);
  // the rest is reported, site by site, with the mesh's own crease there.
  EXPECT_LT(checks.max_normal_gap_away_from_irregular_degrees, 2.0);
  EXPECT_LE(checks.farthest_gap_from_irregular, 3);
  for (const NormalGapSite& site : checks.sites)
    EXPECT_FALSE(is_regular_vertex(mesh, QuadMesh::VertexHandle(site.vertex)));
  // The smooth surfaces stay within the quad mesh's own distance to the cloud.
  EXPECT_LE(checks.to_cloud.mean, checks.mesh_to_cloud.mean);
  EXPECT_LE(checks.to_cloud.p95, 1.02 * checks.mesh_to_cloud.p95);
  EXPECT_LT(checks.to_mesh.p95, 0.05 * scale);
}

INSTANTIATE_TEST_SUITE_P(Shapes, SurfacesOnShapes,
                         ::testing::Values(ShapeCase{"t-shape", 20000}, ShapeCase{"bent-tube", 20000},
                                           ShapeCase{"theta", 30000}, ShapeCase{"tube-frame", 40000}),
                         [](const auto& param_info) {
                           std::string name = param_info.param.shape;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

//! The paper's Fig. 7d: the torus knot's irregularity-free mesh becomes one
//! surface, periodic around the tube.
TEST(SurfacesOnTheKnot, OnePeriodicSurfaceWithinTheMeshsDistance) {
  GeneratedShape shape = test::small_shape("torus-knot", 80000);
  EvolutionSetup setup = prepare_evolution(build_skeleton_graph(shape.skeleton, "knot"), shape.cloud, {}, 6, "knot");
  EvolutionParameters parameters;
  parameters.epsilon = automatic_epsilon(setup.median_radius);
  parameters.iterations = 10;
  SerialBackend backend;
  backend.load(setup.cells, setup.arrays, setup.regions);
  QuadMesh mesh = setup.initial.mesh;
  set_positions(mesh, evolve(backend, setup.arrays, parameters).positions);
  SurfaceModel model = build_surface_model(mesh);
  ASSERT_EQ(model.surfaces.size(), 1u);
  EXPECT_TRUE(model.surfaces[0].periodic_v || model.surfaces[0].periodic_u);
  SurfaceChecks checks = check_surfaces(mesh, model.layout, model.surfaces, &shape.cloud);
  EXPECT_LE(checks.to_cloud.mean, checks.mesh_to_cloud.mean);
  EXPECT_LE(checks.to_cloud.p95, checks.mesh_to_cloud.p95);
  // Face by face: no surface bulges off on its own. Where one is farther
  // than allowed, the quad mesh itself is already off the cloud there
  // (beyond its own 95th percentile: 80,000 points leave a few faces half a
  // radius off), and such faces are rare.
  EXPECT_LE(checks.faces_off_cloud, mesh.n_faces() / 200);
  for (const OffCloudSurfaceSite& site : checks.off_cloud_sites)
    EXPECT_GT(site.allowed_distance, 1.1 * checks.off_cloud_tolerance + checks.off_cloud_slack + 1e-12);
  // A loop whose rings close rotated keeps one seam, tangent-continuous.
  EXPECT_LT(checks.max_normal_gap_degrees, 1e-6);
  EXPECT_LT(checks.max_position_gap, 1e-9 * setup.median_radius);
}

//! A cloud on the true torus, `along` x `around` points.
PointCloud torus_cloud(int along, int around) {
  PointCloud cloud;
  for (int i = 0; i < along; ++i)
    for (int j = 0; j < around; ++j)
      cloud.points.push_back(torus_point(2 * M_PI * (i + 0.5) / along, 2 * M_PI * (j + 0.5) / around).cast<float>());
  return cloud;
}

//! The surfaces' own check: no face's surface farther from the cloud than
//! the quad mesh. Surfaces of a mesh with one vertex pushed off the torus
//! bulge there while the true mesh stays on it: the check names those
//! faces, at the bump, and none for the surfaces of the true mesh.
TEST(SurfaceChecks, FacesWhoseSurfaceLeavesTheCloudAreNamed) {
  QuadMesh mesh = torus_grid(24, 10, 0);
  PointCloud cloud = torus_cloud(240, 100);
  SurfaceModel model = build_surface_model(mesh);
  SurfaceChecks clean = check_surfaces(mesh, model.layout, model.surfaces, &cloud);
  EXPECT_EQ(clean.faces_off_cloud, 0u);
  EXPECT_TRUE(clean.off_cloud_sites.empty());

  QuadMesh bumped = mesh;
  const QuadMesh::VertexHandle bump(5 * 10 + 3);
  Eigen::Vector3d p = point_of(mesh, bump.idx());
  Eigen::Vector3d ring(p.x(), p.y(), 0);
  Eigen::Vector3d outward = (p - kMajor * ring.normalized()).normalized();
  Eigen::Vector3d moved = p + 0.4 * kMinor * outward;
  bumped.set_point(bump, QuadMesh::Point(moved.x(), moved.y(), moved.z()));
  SurfaceModel bulging = build_surface_model(bumped);
  SurfaceChecks checks = check_surfaces(mesh, bulging.layout, bulging.surfaces, &cloud);
  ASSERT_GT(checks.faces_off_cloud, 0u);
  ASSERT_FALSE(checks.off_cloud_sites.empty());
  EXPECT_LE(checks.off_cloud_sites.size(), SurfaceChecks::kMaxOffCloudSites);
  EXPECT_LT((checks.off_cloud_sites[0].position - moved).norm(), 0.5 * kMinor);
  EXPECT_GT(checks.off_cloud_sites[0].surface_distance, checks.off_cloud_sites[0].allowed_distance);
  EXPECT_GT(checks.off_cloud_slack, 0.0);
}

TEST(CadFiles, StepAndIgesReadBackWithEverySurface) {
  test::TempDir dir;
  QuadMesh mesh = torus_grid(24, 10, 3);
  SurfaceModel model = build_surface_model(mesh);
  CadModel cad(model.surfaces, 1e-7);
  EXPECT_EQ(cad.face_count(), 2 * model.surfaces.size());
  EXPECT_EQ(cad.free_edges(), 0u);
  for (const char* name : {"torus.step", "torus.igs"}) {
    cad.write(dir.file(name));
    CadFileContents contents = read_cad_file(dir.file(name));
    // The torus closing with a shift of 3 is one surface, periodic around
    // the tube; the seam along it is closed by cutting it in two faces.
    EXPECT_EQ(contents.faces, 2 * model.surfaces.size()) << name;
    EXPECT_EQ(contents.bspline_faces, contents.faces) << name;
    EXPECT_EQ(contents.free_edges, 0u) << name << ": a closed shell";
    EXPECT_EQ(contents.shells, 1u) << name;
    EXPECT_TRUE(contents.valid) << name;
  }
  GeneratedShape shape = test::small_shape("t-shape", 20000);
  EvolutionSetup setup = prepare_evolution(build_skeleton_graph(shape.skeleton, "t"), shape.cloud, {}, 6, "t");
  SurfaceModel t_model = build_surface_model(setup.initial.mesh);
  CadModel t_cad(t_model.surfaces, 1e-6 * setup.median_radius);
  t_cad.write(dir.file("t.step"));
  CadFileContents contents = read_cad_file(dir.file("t.step"));
  EXPECT_EQ(contents.faces, t_model.surfaces.size());
  EXPECT_EQ(contents.bspline_faces, contents.faces);
  // Sewn along every seam: the only free edges are the open ends' rims.
  EXPECT_EQ(mesh_statistics(setup.initial.mesh).boundary_loops > 0, contents.free_edges > 0);
  EXPECT_TRUE(contents.valid);
  EXPECT_EQ(contents.shells, 1u);
  // The theta graph is closed: a closed, valid shell.
  GeneratedShape theta = test::small_shape("theta", 20000);
  EvolutionSetup theta_setup =
      prepare_evolution(build_skeleton_graph(theta.skeleton, "theta"), theta.cloud, {}, 6, "theta");
  SurfaceModel theta_model = build_surface_model(theta_setup.initial.mesh);
  CadModel(theta_model.surfaces, 1e-6 * theta_setup.median_radius).write(dir.file("theta.step"));
  CadFileContents theta_contents = read_cad_file(dir.file("theta.step"));
  EXPECT_EQ(theta_contents.free_edges, 0u);
  EXPECT_EQ(theta_contents.shells, 1u);
  EXPECT_TRUE(theta_contents.valid);
}

//! The first `count` CARTESIAN_POINT lines of a STEP file.
std::vector<std::string> step_points(const std::string& text, size_t count) {
  std::vector<std::string> points;
  for (size_t at = 0; points.size() < count && (at = text.find("CARTESIAN_POINT", at)) != std::string::npos; ++at)
    points.push_back(text.substr(at, text.find(';', at) - at));
  return points;
}

TEST(CadFiles, UnitsAreDeclaredAndTheCoordinatesKept) {
  test::TempDir dir;
  SurfaceModel model = build_surface_model(torus_grid(12, 8, 0));
  CadModel cad(model.surfaces, 1e-7);
  cad.write(dir.file("mm.step"));
  cad.write(dir.file("m.step"), "m");
  cad.write(dir.file("in.step"), "in");
  cad.write(dir.file("m.igs"), "m");
  std::string mm = read_file(dir.file("mm.step")), m = read_file(dir.file("m.step")),
              in = read_file(dir.file("in.step"));
  EXPECT_NE(mm.find("SI_UNIT(.MILLI.,.METRE.)"), std::string::npos);
  EXPECT_NE(m.find("SI_UNIT($,.METRE.)"), std::string::npos);
  EXPECT_EQ(m.find("SI_UNIT(.MILLI.,.METRE.)"), std::string::npos);
  EXPECT_NE(in.find("'INCH'"), std::string::npos);
  // A scan in metres stays the same numbers, declared as metres.
  EXPECT_EQ(step_points(m, 20), step_points(mm, 20));
  EXPECT_EQ(step_points(in, 20), step_points(mm, 20));
  EXPECT_NE(read_file(dir.file("m.igs")).find(",1HM,"), std::string::npos);
  EXPECT_EQ(read_cad_file(dir.file("m.step")).faces, model.surfaces.size());
  EXPECT_THROW(cad.write(dir.file("km.step"), "km"), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir.file("km.step")));
}

TEST(CadFiles, BadPathsAndFilesFailClearly) {
  test::TempDir dir;
  SurfaceModel model = build_surface_model(torus_grid(12, 8, 0));
  CadModel cad(model.surfaces, 1e-7);
  EXPECT_THROW(cad.write(dir.file("out.obj")), OutputError);
  EXPECT_THROW(cad.write(dir.file("missing/out.step")), OutputError);
  EXPECT_FALSE(std::filesystem::exists(dir.file("missing/out.step")));
  EXPECT_THROW(read_cad_file(dir.write("broken.step", "ISO-10303-21;\nthis is not STEP\n")), InputError);
  EXPECT_THROW(read_cad_file(dir.file("absent.igs")), InputError);
}

}  // namespace
}  // namespace mcquad
