#pragma once

// Keyword options of the Python package to and from the library's option
// structs: one table per struct, so that the names, the defaults and the
// units (degrees where the CLI takes degrees) have one source.
#include <pybind11/pybind11.h>

#include "generate/shapes.h"
#include "pipeline/fit.h"

namespace mcquad {

//! TypeError-like InputError for a name the table does not hold.
FitOptions fit_options_from_dict(const pybind11::dict& options);
pybind11::dict fit_defaults();

ShapeOptions shape_options_from_dict(const pybind11::dict& options);
pybind11::dict shape_defaults();

}  // namespace mcquad
