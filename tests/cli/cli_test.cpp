#include <gtest/gtest.h>

#include <sys/wait.h>

#include <fstream>
#include <sstream>

#include "core/errors.h"
#include "helpers.h"
#include "io/skeleton_io.h"

namespace mcquad {
namespace {

struct CliRun {
  int code;
  std::string output;
};

//! Runs the mcquad binary (path from CMake), capturing stdout+stderr.
CliRun mcquad(const std::string& arguments) {
  std::string command = std::string(MCQUAD_CLI_PATH) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
  int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

TEST(Cli, VersionAndHelp) {
  EXPECT_EQ(mcquad("--version").code, 0);
  for (const char* sub : {"fit", "init", "generate", "skeleton", "devices", "metrics", "surfaces"})
    EXPECT_EQ(mcquad(std::string(sub) + " --help").code, 0) << sub;
  EXPECT_EQ(mcquad("").code, kExitUsage);
  EXPECT_EQ(mcquad("fit a.ply").code, kExitUsage);
}

TEST(Cli, GenerateInitFitMetricsEndToEnd) {
  test::TempDir dir;
  CliRun generated = mcquad("generate t-shape -o " + dir.file("") + " --points 15000");
  ASSERT_EQ(generated.code, 0) << generated.output;
  std::string points = dir.file("t-shape.ply"), skeleton = dir.file("t-shape.skeleton.obj");
  CliRun init = mcquad("init " + points + " " + skeleton + " -o " + dir.file("init.obj") + " --stage extruded");
  EXPECT_EQ(init.code, 0) << init.output;
  CliRun fit = mcquad("fit " + points + " " + skeleton + " -o " + dir.file("fit.ply") + " --report " +
                      dir.file("r.json") + " --backend serial --iterations 3 --snapshots " + dir.file("snaps"));
  ASSERT_EQ(fit.code, 0) << fit.output;
  EXPECT_TRUE(std::filesystem::exists(dir.file("snaps/iteration-003.obj")));
  std::ifstream report(dir.file("r.json"));
  std::stringstream text;
  text << report.rdbuf();
  auto json = nlohmann::json::parse(text.str());
  EXPECT_EQ(json["evolution"]["iterations"].size(), 3u);
  EXPECT_EQ(json["backend"]["name"], "serial");
  EXPECT_EQ(json["parameters"]["projection"], "mean");  // robust mode's defaults
  EXPECT_EQ(json["parameters"]["fill_holes"], true);
  EXPECT_EQ(json["parameters"]["nearest_plane"], false);  // opt-in (docs/DESIGN.md, "Blind vertices")
  CliRun paper_like =
      mcquad("fit " + points + " " + skeleton + " -o " + dir.file("p.obj") + " --report " + dir.file("p.json") +
             " --backend serial --iterations 1 --projection min --fill-holes off --nearest-plane on");
  ASSERT_EQ(paper_like.code, 0) << paper_like.output;
  std::ifstream paper_report(dir.file("p.json"));
  auto paper_json = nlohmann::json::parse(paper_report);
  EXPECT_EQ(paper_json["parameters"]["projection"], "min");
  EXPECT_EQ(paper_json["parameters"]["fill_holes"], false);
  EXPECT_EQ(paper_json["parameters"]["nearest_plane"], true);
  EXPECT_EQ(mcquad("fit " + points + " " + skeleton + " -o " + dir.file("q.obj") + " --projection median").code,
            kExitUsage);
  CliRun metrics = mcquad("metrics " + dir.file("fit.ply") + " " + points + " --skeleton " + skeleton);
  EXPECT_EQ(metrics.code, 0) << metrics.output;
  EXPECT_NE(metrics.output.find("euler_characteristic"), std::string::npos);
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

TEST(Cli, SameSeedSameOutputByteForByte) {
  test::TempDir dir;
  ASSERT_EQ(mcquad("generate torus -o " + dir.file("") + " --points 8000 --seed 3").code, 0);
  ASSERT_EQ(mcquad("generate torus -o " + dir.file("again") + " --points 8000 --seed 3").code, 0);
  EXPECT_EQ(file_bytes(dir.file("torus.ply")), file_bytes(dir.file("again/torus.ply")));
  std::string inputs = dir.file("torus.ply") + " " + dir.file("torus.skeleton.obj");
  for (const char* backend : {"serial", "opencl"}) {
    if (std::string(backend) == "opencl" && !test::opencl_required() && mcquad("devices").code != 0) continue;
    std::string common = std::string(" --iterations 5 --seed 11 --backend ") + backend;
    ASSERT_EQ(mcquad("fit " + inputs + " -o " + dir.file("a.ply") + common).code, 0);
    ASSERT_EQ(mcquad("fit " + inputs + " -o " + dir.file("b.ply") + common).code, 0);
    EXPECT_EQ(file_bytes(dir.file("a.ply")), file_bytes(dir.file("b.ply"))) << backend;
    ASSERT_EQ(
        mcquad("fit " + inputs + " -o " + dir.file("c.ply") + " --iterations 5 --seed 12 --backend " + backend).code,
        0);
    EXPECT_NE(file_bytes(dir.file("a.ply")), file_bytes(dir.file("c.ply"))) << backend;
  }
}

TEST(Cli, VerdictWarnsAndStrictFailsAfterWritingTheOutputs) {
  test::TempDir dir;
  ASSERT_EQ(mcquad("generate t-shape -o " + dir.file("") + " --points 20000").code, 0);
  std::string inputs = dir.file("t-shape.ply") + " " + dir.file("t-shape.skeleton.obj") + " --backend serial";
  CliRun good = mcquad("fit " + inputs + " -o " + dir.file("good.obj") + " --strict");
  EXPECT_EQ(good.code, kExitOk) << good.output;
  EXPECT_NE(good.output.find("verdict: pass (10 of 10 checks passed)"), std::string::npos) << good.output;
  EXPECT_EQ(good.output.find("check failed"), std::string::npos) << good.output;
  // No iterations: the initial mesh inside the tube, far from the cloud.
  std::string unfitted =
      "fit " + inputs + " --iterations 0 -o " + dir.file("far.obj") + " --report " + dir.file("far.json");
  CliRun lenient = mcquad(unfitted);
  EXPECT_EQ(lenient.code, kExitOk) << lenient.output;
  size_t uncovered = lenient.output.find("mcquad: warning: check failed: uncovered_cloud = ");
  ASSERT_NE(uncovered, std::string::npos) << lenient.output;
  // The warning names where: the cloud points farthest from the mesh.
  std::string line = lenient.output.substr(uncovered, lenient.output.find('\n', uncovered) - uncovered);
  EXPECT_NE(line.find("; at ("), std::string::npos) << line;
  EXPECT_NE(lenient.output.find("verdict: FAIL"), std::string::npos) << lenient.output;
  std::filesystem::remove(dir.file("far.obj"));
  CliRun strict = mcquad(unfitted + " --strict");
  EXPECT_EQ(strict.code, kExitVerdict) << strict.output;
  EXPECT_TRUE(std::filesystem::exists(dir.file("far.obj")));
  std::ifstream report(dir.file("far.json"));
  auto json = nlohmann::json::parse(report);
  EXPECT_FALSE(json["verdict"]["passed"].get<bool>());
  EXPECT_EQ(json["metrics"]["inward_measured_against"], "scan normals");  // the generated cloud has normals
  // metrics judges a mesh the same way: the fitted one passes, the unfitted one fails.
  std::string skeleton = " --skeleton " + dir.file("t-shape.skeleton.obj");
  CliRun judged = mcquad("metrics " + dir.file("good.obj") + " " + dir.file("t-shape.ply") + skeleton + " --strict");
  EXPECT_EQ(judged.code, kExitOk) << judged.output;
  EXPECT_NE(judged.output.find("verdict: pass (10 of 10 checks passed)"), std::string::npos) << judged.output;
  CliRun far = mcquad("metrics " + dir.file("far.obj") + " " + dir.file("t-shape.ply") + skeleton);
  EXPECT_EQ(far.code, kExitOk) << far.output;
  EXPECT_NE(far.output.find("check failed: uncovered_cloud"), std::string::npos) << far.output;
  EXPECT_EQ(mcquad("metrics " + dir.file("far.obj") + " " + dir.file("t-shape.ply") + skeleton + " --strict").code,
            kExitVerdict);
}

TEST(Cli, BadInputsGiveOneLineAndDocumentedCodes) {
  test::TempDir dir;
  ASSERT_EQ(mcquad("generate tube -o " + dir.file("") + " --points 3000").code, 0);
  std::string points = dir.file("tube.ply"), skeleton = dir.file("tube.skeleton.obj");
  std::string bad = dir.write("bad.xyz", "1 2 3\n4 nan 6\n");
  CliRun r = mcquad("fit " + bad + " " + skeleton + " -o " + dir.file("o.obj"));
  EXPECT_EQ(r.code, kExitInput);
  EXPECT_NE(r.output.find(bad), std::string::npos) << r.output;
  EXPECT_EQ(mcquad("fit " + points + " " + dir.file("none.obj") + " -o " + dir.file("o.obj")).code, kExitInput);
  EXPECT_EQ(mcquad("fit " + points + " " + skeleton + " -o " + dir.file("nodir/o.obj")).code, kExitOutput);
  CliRun format = mcquad("fit " + points + " " + skeleton + " -o " + dir.file("o.xyz"));
  EXPECT_EQ(format.code, kExitOutput);
  EXPECT_NE(format.output.find("(expected .obj, .off, .ply, .om, .stl, .stla)"), std::string::npos) << format.output;
  EXPECT_EQ(mcquad("generate nothing -o " + dir.file("")).code, kExitInput);
  EXPECT_FALSE(std::filesystem::exists(dir.file("o.obj")));
  CliRun device =
      mcquad("fit " + points + " " + skeleton + " -o " + dir.file("o.obj") + " --backend opencl --device 99");
  EXPECT_EQ(device.code, kExitDevice) << device.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("o.obj")));
  // An explicit device is not replaced by the serial backend, even with --backend auto.
  CliRun automatic = mcquad("fit " + points + " " + skeleton + " -o " + dir.file("o.obj") + " --device 99");
  EXPECT_EQ(automatic.code, kExitDevice) << automatic.output;
  EXPECT_NE(automatic.output.find("OpenCL device 99 does not exist"), std::string::npos) << automatic.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("o.obj")));
}

TEST(Cli, SurfacesFromFitAndFromAMesh) {
  test::TempDir dir;
  ASSERT_EQ(mcquad("generate t-shape -o " + dir.file("") + " --points 15000").code, 0);
  std::string points = dir.file("t-shape.ply"), skeleton = dir.file("t-shape.skeleton.obj");
  CliRun fit = mcquad("fit " + points + " " + skeleton + " -o " + dir.file("t.obj") +
                      " --backend serial --iterations 5" + " --surfaces " + dir.file("t.step") + " --control-nets " +
                      dir.file("nets.obj") + " --report " + dir.file("r.json"));
  ASSERT_EQ(fit.code, 0) << fit.output;
  EXPECT_NE(fit.output.find("B-spline faces read back"), std::string::npos) << fit.output;
  std::ifstream report(dir.file("r.json"));
  auto json = nlohmann::json::parse(report);
  const auto& surfaces = json["surfaces"];
  EXPECT_EQ(surfaces["cad_file"]["faces_read_back"], surfaces["layout"]["regions"]);
  EXPECT_TRUE(std::filesystem::exists(dir.file("nets.obj")));
  // The surfaces' own check joins the verdict, with its figure from the surface checks.
  bool judged = false;
  for (const auto& check : json["verdict"]["checks"])
    if (check["name"] == "surfaces_off_cloud") {
      judged = true;
      EXPECT_EQ(check["value"].get<double>(), surfaces["checks"]["faces_off_cloud"].get<double>());
      EXPECT_EQ(check["sites"].size(),
                std::min<size_t>(20 /* kMaxOffCloudSites */, surfaces["checks"]["off_cloud_sites"].size()));
    }
  EXPECT_TRUE(judged) << json["verdict"].dump();
  CliRun iges = mcquad("surfaces " + dir.file("t.obj") + " -o " + dir.file("t.igs") + " --cloud " + points +
                       " --json " + dir.file("s.json"));
  ASSERT_EQ(iges.code, 0) << iges.output;
  EXPECT_NE(iges.output.find("distance to the cloud"), std::string::npos) << iges.output;
  EXPECT_TRUE(std::filesystem::exists(dir.file("s.json")));
  // Bad inputs and outputs: one line, documented codes, nothing written.
  EXPECT_EQ(mcquad("surfaces " + dir.file("none.obj") + " -o " + dir.file("x.step")).code, kExitInput);
  EXPECT_EQ(mcquad("surfaces " + dir.file("t.obj") + " -o " + dir.file("x.stl")).code, kExitOutput);
  EXPECT_EQ(mcquad("surfaces " + dir.file("t.obj") + " -o " + dir.file("nodir/x.step")).code, kExitOutput);
  EXPECT_EQ(
      mcquad("fit " + points + " " + skeleton + " -o " + dir.file("u.obj") + " --surfaces " + dir.file("u.dxf")).code,
      kExitOutput);
  EXPECT_FALSE(std::filesystem::exists(dir.file("u.obj")));
  std::string triangles = dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  CliRun unsupported = mcquad("surfaces " + triangles + " -o " + dir.file("x.step"));
  EXPECT_EQ(unsupported.code, kExitUnsupported) << unsupported.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.step")));
}

}  // namespace
}  // namespace mcquad

namespace mcquad {
namespace {

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(Cli, SkeletonFromTheCloudAloneAndInAFitWithoutSkeleton) {
  test::TempDir dir;
  ASSERT_EQ(mcquad("generate t-shape -o " + dir.file("") + " --points 30000").code, 0);
  std::string points = dir.file("t-shape.ply");
  CliRun extracted = mcquad("skeleton " + points + " -o " + dir.file("s.obj") + " --report " + dir.file("s.json"));
  ASSERT_EQ(extracted.code, 0) << extracted.output;
  EXPECT_NE(extracted.output.find("1 junctions, 3 ends, 0 independent cycles, 1 components"), std::string::npos)
      << extracted.output;
  nlohmann::json report = nlohmann::json::parse(file_text(dir.file("s.json")));
  ASSERT_FALSE(report["nodes"].empty());
  for (const auto& node : report["nodes"]) EXPECT_NEAR(node["radius"].get<double>(), 1.0, 0.25);
  // Byte for byte the same on a second run, and the skeleton a fit with none builds on.
  ASSERT_EQ(mcquad("skeleton " + points + " -o " + dir.file("again.obj")).code, 0);
  EXPECT_EQ(file_text(dir.file("s.obj")), file_text(dir.file("again.obj")));
  CliRun fit =
      mcquad("fit " + points + " -o " + dir.file("fit.obj") + " --backend serial --iterations 3 --write-skeleton " +
             dir.file("used.obj") + " --report " + dir.file("fit.json"));
  ASSERT_EQ(fit.code, 0) << fit.output;
  nlohmann::json fit_report = nlohmann::json::parse(file_text(dir.file("fit.json")));
  EXPECT_EQ(fit_report["skeleton_extraction"]["junctions"].get<int>(), 1);
  EXPECT_EQ(fit_report["inputs"]["skeleton"].get<std::string>(), "the skeleton extracted from " + points);
  SkeletonData used = read_skeleton(dir.file("used.obj")), alone = read_skeleton(dir.file("s.obj"));
  EXPECT_EQ(used.edges.size(), alone.edges.size());
}

TEST(Cli, SkeletonOfABadCloudIsAOneLineError) {
  test::TempDir dir;
  std::string few = dir.write("few.xyz", "0 0 0\n1 0 0\n0 1 0\n");
  CliRun too_few = mcquad("skeleton " + few + " -o " + dir.file("s.obj"));
  EXPECT_EQ(too_few.code, kExitInput) << too_few.output;
  EXPECT_NE(too_few.output.find(few + ": 3 points are too few"), std::string::npos) << too_few.output;
  std::string sheet;
  for (int i = 0; i < 150; ++i)
    for (int j = 0; j < 150; ++j)
      sheet += std::to_string(i * 0.05 + 0.001 * (j % 7)) + " " + std::to_string(j * 0.05) + " 0\n";
  std::string sheet_path = dir.write("sheet.xyz", sheet);
  CliRun flat = mcquad("skeleton " + sheet_path + " -o " + dir.file("s.obj"));
  EXPECT_EQ(flat.code, kExitUnsupported) << flat.output;
  EXPECT_NE(flat.output.find("the cloud is a sheet"), std::string::npos) << flat.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("s.obj")));
  CliRun unwritable = mcquad("skeleton " + sheet_path + " -o " + dir.file("no/such/dir/s.obj"));
  EXPECT_EQ(unwritable.code, kExitOutput) << unwritable.output;
}

}  // namespace
}  // namespace mcquad
