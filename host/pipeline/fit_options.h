#pragma once

#include <string>
#include <vector>

#include "core/errors.h"
#include "evolution/evolution_backend.h"
#include "evolution/evolution_parameters.h"
#include "mesh/initial_mesh.h"
#include "pipeline/surfaces.h"

namespace mcquad {

struct FitOptions {
  EvolutionParameters evolution;
  InitialMeshOptions initial;
  size_t leaf_size = 0;  //!< at most this many points per cell; 0: automatic (cell_leaf_size)
  BackendKind backend = BackendKind::kAuto;
  std::string device;                 //!< OpenCL device by index or name
  std::string snapshots_directory;    //!< write the mesh after every iteration here
  std::string construction_skeleton;  //!< write the skeleton the mesh was built on here (OBJ)
  bool evolve = true;                 //!< false: stop after the initial mesh (mcquad init)
  bool measure = true;                //!< compute quality metrics for the report
  bool keep_initial_mesh = false;     //!< return the initial mesh too (for the HTML report)
  SurfaceOutputs surfaces;            //!< B-spline surfaces to write (none by default)
};

//! The initial mesh's options as the fit builds it: robust mode's parts of
//! the construction (coarse to fine when evolving, the junctions' inflation)
//! are off in the paper's mode, whatever `options.initial` says.
InitialMeshOptions effective_initial_options(const FitOptions& options);

//! Options out of range or contradicting each other, refused before any
//! work (InputError naming the option). The CLI checks the same ranges while
//! parsing; this holds them for every other caller (the Python package).
void check_fit_options(const FitOptions& options);

//! The range an option must lie in, in the units the CLI and the Python
//! package take it (angles in degrees). One table for both: the CLI checks
//! it while parsing, run_fit for every other caller.
struct OptionRange {
  const char* name;  //!< as the Python keyword: start_fraction, alpha_max, ...
  double low, high;
};
//! The range of a ranged option (InputError for a name without one).
const OptionRange& fit_option_range(const std::string& name);

//! Option words as the CLI and the Python package spell them, one table
//! per option; the CLI hands the same tables to CLI11, the report writes
//! the words back.
template <typename Value>
struct OptionWord {
  const char* word;
  Value value;
};
template <typename Value>
using OptionWords = std::vector<OptionWord<Value>>;

const OptionWords<EndMode>& end_mode_words();
const OptionWords<BackendKind>& backend_words();
const OptionWords<EvolutionParameters::Mode>& evolution_mode_words();
const OptionWords<ConstructionStage>& construction_stage_words();
const OptionWords<bool>& on_off_words();      //!< on, off
const OptionWords<bool>& projection_words();  //!< mean (true), min (false): EvolutionParameters::mean_projection

//! The value of `word` (InputError naming `option` and the accepted words
//! for anything else).
template <typename Value>
Value value_of_word(const std::string& word, const std::string& option, const OptionWords<Value>& words) {
  std::string accepted;
  for (const auto& [w, value] : words) {
    if (word == w) return value;
    accepted += std::string(accepted.empty() ? "" : ", ") + w;
  }
  throw InputError(option + ": '" + word + "' is not one of " + accepted);
}

//! The word of `value` ("?" for one the table lacks).
template <typename Value>
const char* word_of(Value value, const OptionWords<Value>& words) {
  for (const auto& [w, v] : words)
    if (v == value) return w;
  return "?";
}

EndMode end_mode_from_name(const std::string& name, const std::string& option = "ends");
BackendKind backend_from_name(const std::string& name, const std::string& option = "backend");
EvolutionParameters::Mode evolution_mode_from_name(const std::string& name, const std::string& option = "mode");

}  // namespace mcquad
