#include "options.h"

#include <cmath>
#include <functional>
#include <map>
#include <string>

#include "core/errors.h"

namespace py = pybind11;

namespace mcquad {
namespace {

constexpr double kDegree = M_PI / 180.0;

//! How one keyword reads and writes its field of `Options`.
template <typename Options>
struct Field {
  std::function<py::object(const Options&)> get;
  std::function<void(Options&, const py::handle&)> set;
};

template <typename Options>
using FieldTable = std::map<std::string, Field<Options>>;

//! A plain field: the Python value is the struct's value.
template <typename Options, typename T>
Field<Options> plain(T Options::*member) {
  return {[member](const Options& o) { return py::cast(o.*member); },
          [member](Options& o, const py::handle& v) { o.*member = v.cast<T>(); }};
}

//! A field reached through a nested struct (options.evolution.cones).
template <typename Options, typename Inner, typename T>
Field<Options> nested(Inner Options::*inner, T Inner::*member) {
  return {[inner, member](const Options& o) { return py::cast(o.*inner.*member); },
          [inner, member](Options& o, const py::handle& v) { o.*inner.*member = v.cast<T>(); }};
}

//! An angle kept in radians, given in degrees.
template <typename Options, typename Inner>
Field<Options> degrees(Inner Options::*inner, double Inner::*member) {
  // Rounded so that 75 degrees reads back as 75, not 75.00000000000001.
  return {[inner, member](const Options& o) { return py::cast(std::round(o.*inner.*member / kDegree * 1e9) / 1e9); },
          [inner, member](Options& o, const py::handle& v) { o.*inner.*member = v.cast<double>() * kDegree; }};
}

//! A field given as one of its option's words (pipeline/fit_options.h).
template <typename Options, typename Value>
Field<Options> word(Value& (*field)(Options&), const OptionWords<Value>& (*words)(), const char* option) {
  return {[field, words](const Options& o) {
            Options copy = o;  // the accessor is the setter's; options are small
            return py::cast(std::string(word_of(field(copy), words())));
          },
          [field, words, option](Options& o, const py::handle& v) {
            field(o) = value_of_word(v.cast<std::string>(), option, words());
          }};
}

const FieldTable<FitOptions>& fit_fields() {
  using O = FitOptions;
  using E = EvolutionParameters;
  using I = InitialMeshOptions;
  static const FieldTable<O> table = {
      {"ends", word<O, EndMode>([](O& o) -> EndMode& { return o.initial.ends; }, end_mode_words, "ends")},
      {"start_fraction", nested(&O::initial, &I::start_fraction)},
      {"block_fraction", nested(&O::initial, &I::block_fraction)},
      {"resolution", nested(&O::initial, &I::resolution)},
      {"target_vertices", nested(&O::initial, &I::target_vertices)},
      {"min_junction_angle", degrees(&O::initial, &I::min_junction_angle)},
      {"junction_inflation", nested(&O::initial, &I::junction_inflation)},
      {"limb_ports", nested(&O::initial, &I::limb_ports)},
      {"write_skeleton", plain(&O::construction_skeleton)},
      {"backend", word<O, BackendKind>([](O& o) -> BackendKind& { return o.backend; }, backend_words, "backend")},
      {"device", plain(&O::device)},
      {"mode", word<O, E::Mode>([](O& o) -> E::Mode& { return o.evolution.mode; }, evolution_mode_words, "mode")},
      {"relaxation", nested(&O::evolution, &E::relaxation)},
      {"projection",
       word<O, bool>([](O& o) -> bool& { return o.evolution.mean_projection; }, projection_words, "projection")},
      {"fill_holes", nested(&O::evolution, &E::fill_holes)},
      {"nearest_plane", nested(&O::evolution, &E::nearest_plane)},
      {"crossing_guard", nested(&O::evolution, &E::crossing_guard)},
      {"held_back_relaxation", nested(&O::evolution, &E::held_back_relaxation)},
      {"own_cells", nested(&O::evolution, &E::own_cells)},
      {"local_epsilon", nested(&O::evolution, &E::local_epsilon)},
      {"coarse_to_fine", nested(&O::evolution, &E::coarse_to_fine)},
      {"refine_uncovered", nested(&O::evolution, &E::refine_uncovered)},
      {"push_deep", nested(&O::evolution, &E::push_deep)},
      {"reach_uncovered", nested(&O::evolution, &E::reach_uncovered)},
      {"hit_band", nested(&O::evolution, &E::hit_band)},
      {"facing_cells", nested(&O::evolution, &E::facing_cells)},
      {"min_facing", nested(&O::evolution, &E::min_facing)},
      {"curvature_correction", nested(&O::evolution, &E::curvature_correction)},
      {"turned_face_rounds", nested(&O::evolution, &E::turned_face_rounds)},
      {"iterations", nested(&O::evolution, &E::iterations)},
      {"tolerance", nested(&O::evolution, &E::tolerance)},
      {"seed", nested(&O::evolution, &E::seed)},
      {"cones", nested(&O::evolution, &E::cones)},
      {"generators", nested(&O::evolution, &E::generators)},
      {"alpha_max", degrees(&O::evolution, &E::alpha_max)},
      {"samples", nested(&O::evolution, &E::samples)},
      {"epsilon", nested(&O::evolution, &E::epsilon)},
      {"leaf_size", plain(&O::leaf_size)},
      {"snapshots", plain(&O::snapshots_directory)},
      {"surfaces",
       {[](const O& o) { return py::cast(o.surfaces.cad_path); },
        [](O& o, const py::handle& v) { o.surfaces.cad_path = v.cast<std::string>(); }}},
      {"control_nets",
       {[](const O& o) { return py::cast(o.surfaces.control_nets_path); },
        [](O& o, const py::handle& v) { o.surfaces.control_nets_path = v.cast<std::string>(); }}},
      {"units",
       {[](const O& o) { return py::cast(o.surfaces.units); },
        [](O& o, const py::handle& v) { o.surfaces.units = v.cast<std::string>(); }}},
  };
  return table;
}

const FieldTable<ShapeOptions>& shape_fields() {
  using S = ShapeOptions;
  static const FieldTable<S> table = {
      {"points", plain(&S::points)},
      {"noise", plain(&S::noise)},
      {"seed", plain(&S::seed)},
      {"angle", plain(&S::angle_degrees)},
      {"branch_radius", plain(&S::branch_radius)},
      {"arms", plain(&S::arms)},
      {"outliers", plain(&S::outliers)},
      {"density_ratio", plain(&S::density_ratio)},
      {"holes", plain(&S::holes)},
  };
  return table;
}

template <typename Options>
Options options_from_dict(const py::dict& given, const FieldTable<Options>& table) {
  Options options;
  for (const auto& [key, value] : given) {
    auto name = key.template cast<std::string>();
    auto field = table.find(name);
    if (field == table.end()) throw InputError("unknown option '" + name + "'");
    try {
      field->second.set(options, value);
    } catch (const py::cast_error&) {
      throw InputError(name + ": " + py::repr(value).template cast<std::string>() + " has the wrong type");
    }
  }
  return options;
}

template <typename Options>
py::dict defaults_of(const FieldTable<Options>& table) {
  Options options;
  py::dict out;
  for (const auto& [name, field] : table) out[py::str(name)] = field.get(options);
  return out;
}

}  // namespace

FitOptions fit_options_from_dict(const py::dict& options) { return options_from_dict(options, fit_fields()); }
py::dict fit_defaults() { return defaults_of(fit_fields()); }
ShapeOptions shape_options_from_dict(const py::dict& options) { return options_from_dict(options, shape_fields()); }
py::dict shape_defaults() { return defaults_of(shape_fields()); }

}  // namespace mcquad
