#include "surfaces/cad_model.h"

#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRep_Builder.hxx>
#include <Geom_BSplineSurface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include "core/errors.h"
#include "io/file_utils.h"

namespace mcquad {
namespace {

//! Where OpenCASCADE's periodic uniform cubic puts the pole centred at knot
//! k: it numbers from the first pole acting on [0, 1], one before ours.
constexpr int kPeriodicPoleShift = 1;

//! OpenCASCADE reports through its messenger on standard output; the tool's
//! stdout is the user's, so the printers go.
struct CadUnit {
  const char* name;  //!< as mcquad spells it
  const char* step;  //!< OpenCASCADE's name for STEP
  const char* iges;  //!< and for IGES
};

const CadUnit kUnits[] = {{"mm", "MM", "MM"}, {"cm", "CM", "CM"},   {"m", "M", "M"},
                          {"um", "UM", "UM"}, {"in", "INCH", "IN"}, {"ft", "FT", "FT"}};

const CadUnit& unit_named(const std::string& name) {
  for (const auto& unit : kUnits)
    if (name == unit.name) return unit;
  throw InputError("units: '" + name + "' is not one of " + kCadUnits);
}

//! The model's coordinates are in `unit` already: OpenCASCADE's own unit is
//! set to the same, so that it writes the numbers unchanged under that name.
void set_cascade_unit(const CadUnit& unit, bool step) {
  Interface_Static::SetCVal("xstep.cascade.unit", step ? unit.step : unit.iges);
  if (step) Interface_Static::SetCVal("write.step.unit", unit.step);
}

void silence_opencascade() {
  static bool done = [] {
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
    return true;
  }();
  (void)done;
}

void fill_knots(int poles, bool periodic, TColStd_Array1OfReal& knots, TColStd_Array1OfInteger& mults) {
  int distinct = periodic ? poles + 1 : poles - 2;
  knots.Resize(1, distinct, false);
  mults.Resize(1, distinct, false);
  for (int k = 1; k <= distinct; ++k) {
    knots(k) = double(k - 1);
    mults(k) = periodic || (k > 1 && k < distinct) ? 1 : 4;
  }
}

int occt_pole_index(int k, int poles, bool periodic) {
  return periodic ? (k + kPeriodicPoleShift + poles) % poles + 1 : k + 1;
}

Handle(Geom_BSplineSurface) to_occt(const BSplineSurface& s) {
  TColgp_Array2OfPnt poles(1, s.poles_u, 1, s.poles_v);
  for (int j = 0; j < s.poles_v; ++j)
    for (int i = 0; i < s.poles_u; ++i) {
      const Eigen::Vector3d& p = s.pole(i, j);
      poles(occt_pole_index(i, s.poles_u, s.periodic_u), occt_pole_index(j, s.poles_v, s.periodic_v)) =
          gp_Pnt(p.x(), p.y(), p.z());
    }
  TColStd_Array1OfReal u_knots(1, 1), v_knots(1, 1);
  TColStd_Array1OfInteger u_mults(1, 1), v_mults(1, 1);
  fill_knots(s.poles_u, s.periodic_u, u_knots, u_mults);
  fill_knots(s.poles_v, s.periodic_v, v_knots, v_mults);
  return new Geom_BSplineSurface(poles, u_knots, v_knots, u_mults, v_mults, 3, 3, s.periodic_u, s.periodic_v);
}

std::string failure_text(const Standard_Failure& failure) {
  const char* text = failure.GetMessageString();
  return std::string(failure.DynamicType()->Name()) + (text && *text ? std::string(": ") + text : "");
}

enum class CadFormat { kStep, kIges };

CadFormat format_of(const std::string& path) {
  std::string extension = file_extension(path);
  if (extension == "step" || extension == "stp") return CadFormat::kStep;
  if (extension == "iges" || extension == "igs") return CadFormat::kIges;
  throw OutputError(path + ": unknown CAD format '." + extension + "' (use .step, .stp, .iges or .igs)");
}

}  // namespace

struct SurfaceEvaluator::Impl {
  Handle(Geom_BSplineSurface) surface;
};

SurfaceEvaluator::SurfaceEvaluator(const BSplineSurface& surface) : impl_(std::make_unique<Impl>()) {
  try {
    impl_->surface = to_occt(surface);
  } catch (const Standard_Failure& failure) {
    throw UnsupportedError("surfaces: OpenCASCADE refused a B-spline surface (" + failure_text(failure) + ")");
  }
}
SurfaceEvaluator::~SurfaceEvaluator() = default;
SurfaceEvaluator::SurfaceEvaluator(SurfaceEvaluator&&) noexcept = default;
SurfaceEvaluator& SurfaceEvaluator::operator=(SurfaceEvaluator&&) noexcept = default;

Eigen::Vector3d SurfaceEvaluator::point(double u, double v) const {
  gp_Pnt p = impl_->surface->Value(u, v);
  return {p.X(), p.Y(), p.Z()};
}

Eigen::Vector3d SurfaceEvaluator::normal(double u, double v) const {
  gp_Pnt p;
  gp_Vec du, dv;
  impl_->surface->D1(u, v, p, du, dv);
  gp_Vec n = du.Crossed(dv);
  double length = n.Magnitude();
  if (length == 0) return Eigen::Vector3d::Zero();
  return Eigen::Vector3d(n.X(), n.Y(), n.Z()) / length;
}

struct CadModel::Impl {
  TopoDS_Shape shape;
  size_t faces = 0;
  size_t free_edges = 0;
};

namespace {

TopoDS_Face make_face(const Handle(Geom_BSplineSurface) & surface, double u0, double u1, double v0, double v1,
                      double tolerance) {
  BRepBuilderAPI_MakeFace face(surface, u0, u1, v0, v1, tolerance);
  if (!face.IsDone()) throw UnsupportedError("surfaces: OpenCASCADE could not make a face of a B-spline surface");
  return face.Face();
}

size_t free_edges_of(const std::vector<TopoDS_Face>& faces, double tolerance) {
  BRepBuilderAPI_Sewing sewing(tolerance);
  for (const auto& face : faces) sewing.Add(face);
  sewing.Perform();
  return size_t(sewing.NbFreeEdges());
}

//! One face, or two where that closes a seam one face cannot: a surface
//! closed in a direction without being periodic there (the knot's tube,
//! whose ends meet turned by a cyclic shift) has two boundary edges on the
//! same curve, which OpenCASCADE neither makes a seam nor sews within one
//! face. Cut in two halves across that direction, the halves sew to each
//! other along both cuts.
std::vector<TopoDS_Face> faces_of(const Handle(Geom_BSplineSurface) & surface, double tolerance) {
  double u0, u1, v0, v1;
  surface->Bounds(u0, u1, v0, v1);
  std::vector<TopoDS_Face> best = {make_face(surface, u0, u1, v0, v1, tolerance)};
  size_t best_free = free_edges_of(best, tolerance);
  if (best_free == 0) return best;
  std::vector<std::vector<TopoDS_Face>> halves;
  if (!surface->IsUPeriodic()) {
    double um = 0.5 * (u0 + u1);
    halves.push_back({make_face(surface, u0, um, v0, v1, tolerance), make_face(surface, um, u1, v0, v1, tolerance)});
  }
  if (!surface->IsVPeriodic()) {
    double vm = 0.5 * (v0 + v1);
    halves.push_back({make_face(surface, u0, u1, v0, vm, tolerance), make_face(surface, u0, u1, vm, v1, tolerance)});
  }
  for (auto& candidate : halves) {
    // A cut adds two edges; it pays only where it closes more than it opens.
    size_t free = free_edges_of(candidate, tolerance);
    if (free < best_free) best = std::move(candidate), best_free = free;
  }
  return best;
}

}  // namespace

CadModel::CadModel(const std::vector<BSplineSurface>& surfaces, double tolerance) : impl_(std::make_unique<Impl>()) {
  silence_opencascade();
  try {
    BRepBuilderAPI_Sewing sewing(tolerance);
    for (const BSplineSurface& surface : surfaces) {
      SurfaceEvaluator evaluator(surface);
      for (const TopoDS_Face& face : faces_of(evaluator.impl_->surface, tolerance)) sewing.Add(face);
    }
    sewing.Perform();
    impl_->shape = sewing.SewedShape();
    impl_->free_edges = size_t(sewing.NbFreeEdges());
  } catch (const Standard_Failure& failure) {
    throw UnsupportedError("surfaces: OpenCASCADE failed to sew the faces (" + failure_text(failure) + ")");
  }
  for (TopExp_Explorer explorer(impl_->shape, TopAbs_FACE); explorer.More(); explorer.Next()) impl_->faces += 1;
}
CadModel::~CadModel() = default;

size_t CadModel::face_count() const { return impl_->faces; }
size_t CadModel::free_edges() const { return impl_->free_edges; }

const char* const kCadUnits = "mm, cm, m, um, in, ft";

void check_cad_unit(const std::string& unit) { unit_named(unit); }

void CadModel::write(const std::string& path, const std::string& unit_name) const {
  CadFormat format = format_of(path);
  const CadUnit& unit = unit_named(unit_name);
  write_atomically(path, [&](const std::string& temporary) {
    try {
      if (format == CadFormat::kStep) {
        STEPControl_Controller::Init();
        set_cascade_unit(unit, true);
        STEPControl_Writer writer;
        if (writer.Transfer(impl_->shape, STEPControl_AsIs) != IFSelect_RetDone ||
            writer.Write(temporary.c_str()) != IFSelect_RetDone)
          throw OutputError(path + ": OpenCASCADE could not write the STEP file");
      } else {
        IGESControl_Controller::Init();
        set_cascade_unit(unit, false);
        IGESControl_Writer writer(unit.iges, 1);  // mode 1: faces as B-rep entities
        if (!writer.AddShape(impl_->shape))
          throw OutputError(path + ": OpenCASCADE could not convert the shape to IGES");
        writer.ComputeModel();
        if (!writer.Write(temporary.c_str())) throw OutputError(path + ": OpenCASCADE could not write the IGES file");
      }
    } catch (const Standard_Failure& failure) {
      throw OutputError(path + ": OpenCASCADE failed writing (" + failure_text(failure) + ")");
    }
  });
}

CadFileContents read_cad_file(const std::string& path) {
  silence_opencascade();
  TopoDS_Shape shape;
  try {
    bool step = format_of(path) == CadFormat::kStep;
    if (step) {
      STEPControl_Reader reader;
      if (reader.ReadFile(path.c_str()) != IFSelect_RetDone)
        throw InputError(path + ": OpenCASCADE cannot read this STEP file");
      reader.TransferRoots();
      shape = reader.OneShape();
    } else {
      IGESControl_Controller::Init();
      IGESControl_Reader reader;
      if (reader.ReadFile(path.c_str()) != IFSelect_RetDone)
        throw InputError(path + ": OpenCASCADE cannot read this IGES file");
      reader.TransferRoots();
      shape = reader.OneShape();
    }
  } catch (const Standard_Failure& failure) {
    throw InputError(path + ": OpenCASCADE failed reading (" + failure_text(failure) + ")");
  } catch (const OutputError& error) {  // an unknown extension, here on the reading side
    throw InputError(error.what());
  }
  CadFileContents contents;
  for (TopExp_Explorer explorer(shape, TopAbs_FACE); explorer.More(); explorer.Next()) {
    contents.faces += 1;
    BRepAdaptor_Surface surface(TopoDS::Face(explorer.Current()));
    contents.bspline_faces += surface.GetType() == GeomAbs_BSplineSurface;
  }
  BRepBuilderAPI_Sewing sewing;
  sewing.Load(shape);
  sewing.Perform();
  contents.free_edges = size_t(sewing.NbFreeEdges());
  TopoDS_Shape sewn = sewing.SewedShape();
  for (TopExp_Explorer explorer(sewn, TopAbs_SHELL); explorer.More(); explorer.Next()) contents.shells += 1;
  contents.valid = BRepCheck_Analyzer(sewn).IsValid();
  return contents;
}

}  // namespace mcquad
