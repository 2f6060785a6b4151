#include "pipeline/fit_report.h"

#include <cmath>

namespace mcquad {
namespace {

nlohmann::json to_json(const FitReport::Parameters& p) {
  const FitOptions& o = p.options;
  const auto& e = o.evolution;
  const bool robust = e.mode == EvolutionParameters::Mode::kRobust;
  return {{"mode", word_of(e.mode, evolution_mode_words())},
          {"relaxation", e.relaxation},
          {"projection", word_of(robust && e.mean_projection, projection_words())},
          {"fill_holes", robust && e.fill_holes},
          {"nearest_plane", robust && e.nearest_plane},
          {"crossing_guard", robust && e.crossing_guard},
          {"held_back_relaxation", robust && e.crossing_guard ? e.held_back_relaxation : 0.0},
          {"own_cells", robust && e.own_cells},
          {"local_epsilon", robust && e.local_epsilon},
          {"hit_band", robust ? e.hit_band : 0.0},
          {"facing_cells", robust && e.facing_cells},
          {"min_facing", e.min_facing},
          {"curvature_correction", robust && e.curvature_correction},
          {"coarse_to_fine", robust && e.coarse_to_fine},
          {"refine_uncovered", robust && e.refine_uncovered},
          {"push_deep", robust && e.push_deep},
          {"reach_uncovered", robust && e.reach_uncovered},
          {"turned_face_rounds", robust ? e.turned_face_rounds : 0u},
          {"cones", e.cones},
          {"generators", e.generators},
          {"alpha_max", e.alpha_max},
          {"samples", e.samples},
          {"epsilon", p.epsilon},
          {"epsilon_automatic", e.epsilon <= 0},
          {"iterations", e.iterations},
          {"tolerance", e.tolerance},
          {"seed", e.seed},
          {"leaf_size", p.leaf_size},
          {"leaf_size_automatic", o.leaf_size == 0},
          {"start_fraction", o.initial.start_fraction},
          {"block_fraction", effective_initial_options(o).block_fraction},
          {"resolution", o.initial.resolution},
          {"target_vertices", o.initial.target_vertices},
          {"ends", word_of(o.initial.ends, end_mode_words())},
          {"min_junction_angle_degrees", o.initial.min_junction_angle * 180.0 / M_PI},
          {"junction_inflation", effective_initial_options(o).junction_inflation},
          {"limb_ports", effective_initial_options(o).limb_ports},
          {"median_radius", p.median_radius}};
}

nlohmann::json to_json(const FitReport::Evolution& e) {
  nlohmann::json iterations = nlohmann::json::array();
  for (const auto& r : e.iterations)
    iterations.push_back({{"iteration", r.iteration},
                          {"error_level", r.error_level},
                          {"seconds", r.seconds},
                          {"step_seconds", r.step_seconds},
                          {"error_seconds", r.error_seconds},
                          {"guard_seconds", r.guard_seconds},
                          {"held_back_vertices", r.held_back_vertices},
                          {"guard_on_host", r.guard_on_host}});
  nlohmann::json j = {{"initial_error_level", e.initial_error_level},
                      {"iterations", iterations},
                      {"stop_reason", e.stop_reason},
                      {"final_error_level", e.final_error_level()}};
  if (e.turned_faces)
    j["turned_faces"] = {{"faces_before", e.turned_faces->faces_before},
                         {"faces_after", e.turned_faces->faces_after},
                         {"area_fraction_before", e.turned_faces->area_before},
                         {"area_fraction_after", e.turned_faces->area_after},
                         {"rounds", e.turned_faces->rounds},
                         {"settle_iterations", e.turned_faces->settle_iterations},
                         {"undone_for_crossings", e.turned_faces->undone_for_crossings},
                         {"deep_push_rounds", e.turned_faces->deep_push_rounds},
                         {"deep_push_kept", e.turned_faces->deep_push_kept}};
  if (e.uncovered_reach)
    j["uncovered_reach"] = {{"rounds", e.uncovered_reach->rounds},
                            {"vertices_moved", e.uncovered_reach->vertices_moved},
                            {"uncovered_points_before", e.uncovered_reach->uncovered_before},
                            {"uncovered_points_after", e.uncovered_reach->uncovered_after},
                            {"settle_iterations", e.uncovered_reach->settle_iterations},
                            {"kept", e.uncovered_reach->kept}};
  return j;
}

}  // namespace

nlohmann::json to_json(const FitReport& r) {
  nlohmann::json report;
  const auto& in = r.inputs;
  report["inputs"] = {{"points", in.points},
                      {"skeleton", in.skeleton},
                      {"point_count", in.point_count},
                      {"skeleton_nodes", in.skeleton_nodes},
                      {"skeleton_bones", in.skeleton_bones},
                      {"skeleton_components", in.skeleton_components}};
  report["parameters"] = to_json(r.parameters);
  if (r.skeleton_extraction) report["skeleton_extraction"] = to_json(*r.skeleton_extraction);
  report["initial_mesh"] = {{"open_ends", r.initial_mesh.open_ends},
                            {"refinement_levels", r.initial_mesh.refinement_levels},
                            {"levels_after_coarse_evolution", r.initial_mesh.levels_after_coarse_evolution},
                            {"inset_ports", r.initial_mesh.inset_ports},
                            {"statistics", to_json(r.initial_mesh.statistics)}};
  if (r.cells)
    report["cells"] = {{"cells", r.cells->cells},
                       {"tree_nodes", r.cells->tree_nodes},
                       {"depth", r.cells->depth},
                       {"megabytes", r.cells->megabytes},
                       {"facing_fraction", r.cells->facing_fraction}};
  if (r.evolution) {
    report["backend"] = {{"name", r.evolution->backend}, {"device", r.evolution->device}};
    report["evolution"] = to_json(*r.evolution);
  }
  if (r.coarse_evolution) report["coarse_evolution"] = to_json(*r.coarse_evolution);
  if (r.coverage_refinement)
    report["coverage_refinement"] = {{"bound", r.coverage_refinement->bound},
                                     {"uncovered_at_default_resolution", r.coverage_refinement->uncovered_at_default},
                                     {"refined", r.coverage_refinement->refined},
                                     {"uncovered_refined", r.coverage_refinement->uncovered_refined},
                                     {"worse_checks", r.coverage_refinement->worse},
                                     {"kept", r.coverage_refinement->kept}};
  if (r.metrics) report["metrics"] = to_json(*r.metrics);
  if (r.verdict) report["verdict"] = to_json(*r.verdict);
  if (r.surfaces) report["surfaces"] = to_json(*r.surfaces);
  nlohmann::json seconds = nlohmann::json::object(), peak = nlohmann::json::object(),
                 resident = nlohmann::json::object();
  for (const auto& [stage, record] : r.stages) {
    seconds[stage] = record.seconds;
    peak[stage] = record.peak_megabytes;
    resident[stage] = record.resident_megabytes;
  }
  report["timings_seconds"] = seconds;
  report["peak_resident_megabytes_after_stage"] = peak;
  report["resident_megabytes_after_stage"] = resident;
  report["peak_resident_megabytes"] = r.peak_resident_megabytes;
  report["version"] = MCQUAD_VERSION;
  if (!r.output_mesh.empty()) report["outputs"] = {{"mesh", r.output_mesh}};
  return report;
}

}  // namespace mcquad
