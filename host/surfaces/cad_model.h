#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "surfaces/spline_interpolation.h"

namespace mcquad {

//! Evaluates one of our B-spline surfaces through OpenCASCADE's
//! Geom_BSplineSurface, the same object the CAD files are written from, so
//! what the checks measure is what a CAD system reads.
class SurfaceEvaluator {
 public:
  explicit SurfaceEvaluator(const BSplineSurface& surface);
  ~SurfaceEvaluator();
  SurfaceEvaluator(SurfaceEvaluator&&) noexcept;
  SurfaceEvaluator& operator=(SurfaceEvaluator&&) noexcept;

  Eigen::Vector3d point(double u, double v) const;
  //! Unit normal (derivative in u cross derivative in v); zero where degenerate.
  Eigen::Vector3d normal(double u, double v) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  friend class CadModel;
};

//! The length units a CAD file can be declared in, for messages: "mm, cm, m, um, in, ft".
extern const char* const kCadUnits;

//! InputError ("units: ...") unless `unit` is one of kCadUnits.
void check_cad_unit(const std::string& unit);

//! What OpenCASCADE found in a STEP or IGES file it read.
struct CadFileContents {
  size_t faces = 0;
  size_t bspline_faces = 0;  //!< faces whose surface is a B-spline surface
  size_t free_edges = 0;     //!< edges of only one face after sewing (the open boundary)
  size_t shells = 0;         //!< connected shells after sewing
  bool valid = false;        //!< OpenCASCADE's BRepCheck_Analyzer finds the sewn shape valid
};

//! The surfaces as one OpenCASCADE shape: a face per surface, sewn along the
//! shared sides into a shell.
class CadModel {
 public:
  //! `tolerance`: the sewing tolerance, in model units.
  CadModel(const std::vector<BSplineSurface>& surfaces, double tolerance);
  ~CadModel();
  CadModel(const CadModel&) = delete;
  CadModel& operator=(const CadModel&) = delete;

  size_t face_count() const;
  //! Edges used by one face only after sewing: the mesh's open boundary, or
  //! sides that did not meet within the tolerance.
  size_t free_edges() const;

  //! STEP (.step, .stp) or IGES (.iges, .igs) by extension, written
  //! atomically, the coordinates as they are and declared to be in `unit`
  //! (one of kCadUnits). OutputError naming the file on failure or another
  //! extension, InputError for another unit.
  void write(const std::string& path, const std::string& unit = "mm") const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

//! Reads a STEP or IGES file with OpenCASCADE and counts what it holds.
//! InputError naming the file when OpenCASCADE cannot read it.
CadFileContents read_cad_file(const std::string& path);

}  // namespace mcquad
