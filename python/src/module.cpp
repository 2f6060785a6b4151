// The Python face of the mcquad library (the package mcquad, module
// mcquad._core): numpy arrays in and out, the library's exceptions as Python
// ones, the GIL released while the pipeline runs. python/mcquad/__init__.py
// holds the documented functions; this file only converts.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <functional>
#include <memory>

#include "core/errors.h"
#include "core/progress.h"
#include "generate/shapes.h"
#include "io/mesh_io.h"
#include "io/point_cloud_io.h"
#include "io/skeleton_io.h"
#include "pipeline/skeleton_extraction.h"
#include "pipeline/fit.h"
#include "pipeline/measure.h"
#include "pipeline/surfaces.h"
#include "arrays.h"
#include "options.h"

namespace py = pybind11;
using namespace mcquad;

namespace {

//! Sends this thread's progress to a Python callable while it lives. Made
//! and destroyed with the GIL held; the sink itself takes the GIL for each
//! call, as the pipeline runs without it. The callable is held by the
//! caller's frame, so a borrowed pointer is safe to copy without the GIL.
class ScopedProgress {
 public:
  explicit ScopedProgress(const py::object& callback) {
    if (callback.is_none()) return;
    PyObject* target = callback.ptr();
    set_progress_sink([target](const std::string& label, size_t done, size_t total) {
      py::gil_scoped_acquire gil;
      py::handle callable(target);
      callable(label, done, total);
    });
  }
  ~ScopedProgress() { set_progress_sink({}); }
  ScopedProgress(const ScopedProgress&) = delete;
  ScopedProgress& operator=(const ScopedProgress&) = delete;
};

py::object parse_json(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

py::tuple fit_arrays(FloatArray points, const py::object& normals, DoubleArray nodes, IndexArray edges,
                     const py::dict& options, const std::string& points_name, const std::string& skeleton_name,
                     const py::object& progress) {
  FitInput input;
  input.points_name = points_name;
  input.skeleton_name = skeleton_name;
  input.cloud = cloud_from_array(points, points_name, normals);
  input.skeleton = skeleton_from_arrays(nodes, edges, skeleton_name);
  FitOptions fit_options = fit_options_from_dict(options);
  FitResult result;
  {
    ScopedProgress scoped(progress);
    py::gil_scoped_release release;
    result = run_fit(std::move(input), fit_options);
  }
  return py::make_tuple(vertices_of(result.mesh), faces_of(result.mesh), parse_json(to_json(result.report).dump()));
}

py::tuple read_points(const std::string& path) {
  PointCloud cloud;
  {
    py::gil_scoped_release release;
    cloud = read_point_cloud(path, true);
  }
  py::object normals = py::none();
  if (!cloud.normals.empty()) {
    PointCloud as_points;
    as_points.points = std::move(cloud.normals);
    normals = points_of(as_points);
  }
  return py::make_tuple(points_of(cloud), normals);
}

//! mcquad.extract_skeleton: nodes, edges, radii and the report of `mcquad skeleton --report`.
py::tuple extract_skeleton_arrays(FloatArray points, const std::string& name, size_t voxels) {
  PointCloud cloud = cloud_from_array(points, name, py::none());
  SkeletonExtractionOptions options;
  options.target_voxels = voxels;
  double seconds = 0;
  ExtractedSkeleton extracted;
  {
    py::gil_scoped_release release;
    extracted = extract_skeleton_timed(cloud, name, options, seconds);
  }
  py::array_t<double> radii(py::ssize_t(extracted.radii.size()));
  std::copy(extracted.radii.begin(), extracted.radii.end(), radii.mutable_data());
  return py::make_tuple(nodes_of(extracted.skeleton), edges_of(extracted.skeleton), radii,
                        parse_json(to_json(skeleton_report(extracted, name, seconds)).dump()));
}

py::tuple read_skeleton_arrays(const std::string& path) {
  SkeletonData skeleton = read_skeleton(path);
  return py::make_tuple(nodes_of(skeleton), edges_of(skeleton));
}

void write_mesh_arrays(const std::string& path, DoubleArray vertices, IndexArray faces) {
  QuadMesh mesh = mesh_from_arrays(vertices, faces, "mesh");
  py::gil_scoped_release release;
  write_mesh(path, mesh);
}

py::tuple read_mesh_arrays(const std::string& path) {
  QuadMesh mesh = read_mesh(path);
  return py::make_tuple(vertices_of(mesh), faces_of(mesh));
}

py::object metrics_json(DoubleArray vertices, IndexArray faces, FloatArray points, const py::object& normals,
                        const py::object& nodes, const py::object& edges, size_t leaf_size) {
  QuadMesh mesh = mesh_from_arrays(vertices, faces, "mesh");
  PointCloud cloud = cloud_from_array(points, "points", normals);
  sort_spatially(cloud);  // as fit sorts it: the same figures as its report, and faster (measure.h)
  std::unique_ptr<SkeletonData> skeleton;
  if (!nodes.is_none())
    skeleton = std::make_unique<SkeletonData>(
        skeleton_from_arrays(nodes.cast<DoubleArray>(), edges.cast<IndexArray>(), "skeleton"));
  nlohmann::json metrics;
  {
    py::gil_scoped_release release;
    metrics = measure_mesh(mesh, cloud, skeleton.get(), "skeleton", leaf_size).metrics;
  }
  return parse_json(metrics.dump());
}

py::object surfaces_json(DoubleArray vertices, IndexArray faces, const std::string& cad_path, const py::object& points,
                         const std::string& control_nets, double tangent_tolerance, const std::string& units) {
  QuadMesh mesh = mesh_from_arrays(vertices, faces, "mesh");
  if (mesh.n_faces() == 0) throw InputError("mesh: the mesh has no faces");
  std::unique_ptr<PointCloud> cloud;
  if (!points.is_none()) cloud = std::make_unique<PointCloud>(cloud_from_array(points.cast<FloatArray>(), "points"));
  SurfaceOutputs outputs;
  outputs.cad_path = cad_path;
  outputs.control_nets_path = control_nets;
  outputs.tangent_tolerance_degrees = tangent_tolerance;
  outputs.units = units;
  SurfaceReport report;
  {
    py::gil_scoped_release release;
    report = export_surfaces(mesh, cloud.get(), outputs);
  }
  return parse_json(to_json(report).dump());
}

py::dict generate(const std::string& name, const py::object& directory, const py::dict& options) {
  ShapeOptions shape_options = shape_options_from_dict(options);
  GeneratedShape shape;
  {
    py::gil_scoped_release release;
    shape = generate_shape(name, shape_options);
  }
  if (!directory.is_none()) write_generated_shape(shape, py::str(directory).cast<std::string>());
  py::dict out;
  out["name"] = shape.name;
  out["points"] = points_of(shape.cloud);
  out["nodes"] = nodes_of(shape.skeleton);
  out["edges"] = edges_of(shape.skeleton);
  out["open_ends"] = shape.open_ends;
  out["independent_cycles"] = shape.independent_cycles;
  return out;
}

py::list shape_names() {
  py::list names;
  for (const auto& [name, what] : shape_catalogue()) names.append(py::make_tuple(name, what));
  return names;
}

//! Python exception classes deriving from mcquad.Error and, where it fits,
//! the built-in a Python user would catch (ValueError, OSError).
void register_exceptions(py::module_& m) {
  static PyObject* error =
      PyErr_NewExceptionWithDoc("mcquad.Error", "Base of every mcquad error.", PyExc_RuntimeError, nullptr);
  auto derived = [&](const char* name, const char* doc, PyObject* builtin) {
    py::tuple bases = builtin ? py::tuple(py::make_tuple(py::handle(error), py::handle(builtin)))
                              : py::tuple(py::make_tuple(py::handle(error)));
    PyObject* type = PyErr_NewExceptionWithDoc(name, doc, bases.ptr(), nullptr);
    return type;
  };
  static PyObject* input =
      derived("mcquad.InputError", "Malformed or inconsistent input: files, arrays, options.", PyExc_ValueError);
  static PyObject* unsupported = derived("mcquad.UnsupportedError", "Valid input this version cannot handle.", nullptr);
  static PyObject* device = derived("mcquad.DeviceError", "No usable OpenCL device, or a device fault.", nullptr);
  static PyObject* output = derived("mcquad.OutputError", "An output file could not be written.", PyExc_OSError);
  m.attr("Error") = py::handle(error);
  m.attr("InputError") = py::handle(input);
  m.attr("UnsupportedError") = py::handle(unsupported);
  m.attr("DeviceError") = py::handle(device);
  m.attr("OutputError") = py::handle(output);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(input, e.what());
    } catch (const UnsupportedError& e) {
      PyErr_SetString(unsupported, e.what());
    } catch (const DeviceError& e) {
      PyErr_SetString(device, e.what());
    } catch (const OutputError& e) {
      PyErr_SetString(output, e.what());
    }
  });
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "mcquad's compiled core; use the functions of the mcquad package.";
  m.attr("__version__") = MCQUAD_VERSION;
  register_exceptions(m);
  m.def("fit", &fit_arrays, py::arg("points"), py::arg("normals"), py::arg("nodes"), py::arg("edges"),
        py::arg("options"), py::arg("points_name"), py::arg("skeleton_name"), py::arg("progress") = py::none());
  m.def("fit_defaults", &fit_defaults, "The fit options' defaults, as the CLI shows them.");
  m.def("shape_defaults", &shape_defaults, "The generator options' defaults.");
  m.def("read_points", &read_points, py::arg("path"));
  m.def("read_skeleton", &read_skeleton_arrays, py::arg("path"));
  m.def("extract_skeleton", &extract_skeleton_arrays, py::arg("points"), py::arg("name"), py::arg("voxels"));
  m.def("read_mesh", &read_mesh_arrays, py::arg("path"));
  m.def("write_mesh", &write_mesh_arrays, py::arg("path"), py::arg("vertices"), py::arg("faces"));
  m.def("generate", &generate, py::arg("name"), py::arg("directory"), py::arg("options"));
  m.def("shape_names", &shape_names);
  m.def("metrics", &metrics_json, py::arg("vertices"), py::arg("faces"), py::arg("points"), py::arg("normals"),
        py::arg("nodes"), py::arg("edges"), py::arg("leaf_size"));
  m.def("surfaces", &surfaces_json, py::arg("vertices"), py::arg("faces"), py::arg("cad_path"), py::arg("points"),
        py::arg("control_nets"), py::arg("tangent_tolerance"), py::arg("units"));
}
