#include "pipeline/fit_options.h"

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "surfaces/cad_model.h"

namespace mcquad {
namespace {

constexpr double kDegrees = 180.0 / M_PI;

//! Every ranged option of fit, in user units.
constexpr OptionRange kOptionRanges[] = {
    {"start_fraction", 0.05, 0.95},
    {"block_fraction", 0.05, 0.95},
    {"resolution", 0, HUGE_VAL},
    {"min_junction_angle", 0, 120},
    {"junction_inflation", 0, 0.95},
    {"relaxation", 0, 1},
    {"held_back_relaxation", 0, 1},
    {"hit_band", 0, 1},
    {"min_facing", -1, 0.95},
    {"turned_face_rounds", 0, 1000},
    {"tolerance", 0, HUGE_VAL},
    {"cones", 1, 64},
    {"generators", 1, 64},
    {"alpha_max", 0, 89},
    {"samples", 1, 1024},
    {"epsilon", 0, HUGE_VAL},
    {"leaf_size", 0, double(size_t(1) << 20)},
};

void check_range(const char* option, double value) {
  const OptionRange& range = fit_option_range(option);
  // Angles come back from radians with a rounding error; an ulp over the bound is the bound.
  double slack = 1e-9 * std::max(1.0, std::abs(range.high));
  if (!(value >= range.low - slack && value <= range.high + slack))
    throw InputError(std::string(option) + ": " + std::to_string(value) + " is outside [" + std::to_string(range.low) +
                     ", " + std::to_string(range.high) + "]");
}

}  // namespace

InitialMeshOptions effective_initial_options(const FitOptions& options) {
  InitialMeshOptions initial = options.initial;
  const bool robust = options.evolution.mode == EvolutionParameters::Mode::kRobust;
  initial.coarse_first = options.evolve && robust && options.evolution.coarse_to_fine;
  if (!robust) {
    initial.junction_inflation = 0;
    initial.block_fraction = initial.start_fraction;
    initial.block_edges = BlockEdges::kMidway;
    initial.limb_ports = false;
  }
  return initial;
}

void check_fit_options(const FitOptions& options) {
  const auto& e = options.evolution;
  const auto& i = options.initial;
  check_range("start_fraction", i.start_fraction);
  check_range("block_fraction", i.block_fraction);
  check_range("resolution", i.resolution);
  check_range("min_junction_angle", i.min_junction_angle * kDegrees);
  check_range("junction_inflation", i.junction_inflation);
  check_range("relaxation", e.relaxation);
  check_range("held_back_relaxation", e.held_back_relaxation);
  check_range("hit_band", e.hit_band);
  check_range("min_facing", e.min_facing);
  check_range("turned_face_rounds", e.turned_face_rounds);
  check_range("tolerance", e.tolerance);
  check_range("cones", e.cones);
  check_range("generators", e.generators);
  check_range("alpha_max", e.alpha_max * kDegrees);
  check_range("samples", e.samples);
  check_range("epsilon", e.epsilon);
  check_range("leaf_size", double(options.leaf_size));
  if (options.evolve && i.stage != ConstructionStage::kRefined)
    throw InputError(std::string("stage: '") + word_of(i.stage, construction_stage_words()) +
                     "' stops the construction early, so it applies to the initial mesh alone, not to a fit");
  check_cad_unit(options.surfaces.units);
}

const OptionRange& fit_option_range(const std::string& name) {
  for (const OptionRange& range : kOptionRanges)
    if (name == range.name) return range;
  throw InputError("no range is defined for the option '" + name + "'");
}

const OptionWords<EndMode>& end_mode_words() {
  static const OptionWords<EndMode> kWords{
      {"auto", EndMode::kAuto}, {"open", EndMode::kOpen}, {"capped", EndMode::kCapped}};
  return kWords;
}

const OptionWords<BackendKind>& backend_words() {
  static const OptionWords<BackendKind> kWords{
      {"auto", BackendKind::kAuto}, {"serial", BackendKind::kSerial}, {"opencl", BackendKind::kOpenCL}};
  return kWords;
}

const OptionWords<EvolutionParameters::Mode>& evolution_mode_words() {
  using Mode = EvolutionParameters::Mode;
  static const OptionWords<Mode> kWords{{"robust", Mode::kRobust}, {"paper", Mode::kPaper}};
  return kWords;
}

const OptionWords<ConstructionStage>& construction_stage_words() {
  static const OptionWords<ConstructionStage> kWords{{"blocks", ConstructionStage::kBlocks},
                                                     {"extruded", ConstructionStage::kExtruded},
                                                     {"refined", ConstructionStage::kRefined}};
  return kWords;
}

const OptionWords<bool>& on_off_words() {
  static const OptionWords<bool> kWords{{"on", true}, {"off", false}};
  return kWords;
}

const OptionWords<bool>& projection_words() {
  static const OptionWords<bool> kWords{{"mean", true}, {"min", false}};
  return kWords;
}

EndMode end_mode_from_name(const std::string& name, const std::string& option) {
  return value_of_word(name, option, end_mode_words());
}

BackendKind backend_from_name(const std::string& name, const std::string& option) {
  return value_of_word(name, option, backend_words());
}

EvolutionParameters::Mode evolution_mode_from_name(const std::string& name, const std::string& option) {
  return value_of_word(name, option, evolution_mode_words());
}

}  // namespace mcquad
