#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "core/point_cloud.h"
#include "core/quad_mesh.h"
#include "io/skeleton_io.h"

namespace mcquad {

//! What the HTML report shows: a fit's report and the geometry it was about.
struct HtmlReportInput {
  const nlohmann::json* report = nullptr;  //!< the fit's JSON report (verdict, metrics, iterations, ...)
  const QuadMesh* final_mesh = nullptr;
  const QuadMesh* initial_mesh = nullptr;  //!< optional
  const PointCloud* cloud = nullptr;
  const SkeletonData* skeleton = nullptr;  //!< optional
  std::string title;
};

//! Clouds above this many points are shown strided down to it (the page
//! says so); every mesh vertex is shown.
constexpr size_t kHtmlReportMaxCloudPoints = 300000;

//! One self-contained HTML file that opens offline: three.js (Debian's
//! libjs-three, inlined), the cloud, skeleton, initial and final mesh to
//! toggle, the final mesh coloured by each vertex's distance to the cloud,
//! irregular vertices, crossing and failed-check sites, the error level per
//! iteration and the report's tables. Written atomically; OutputError when
//! three.js is missing (naming the package) or the file cannot be written.
void write_html_report(const std::string& path, const HtmlReportInput& input);

//! OutputError, as write_html_report would give, when three.js is missing:
//! checked before a fit, not after it.
void check_three_js();

//! Where three.js is read from: $MCQUAD_THREE_JS_DIR, else Debian's /usr/share/javascript/three.
std::string three_js_directory();

//! `mcquad report REPORT.json -o REPORT.html`: reads the report, the cloud and
//! skeleton it names and the mesh it wrote (outputs.mesh, or `mesh_path`
//! when given), rebuilds the initial mesh from the report's parameters and
//! writes the page. InputError naming the report for what it lacks.
void write_html_report_from_json(const std::string& report_path, const std::string& mesh_path,
                                 const std::string& html_path);

}  // namespace mcquad
