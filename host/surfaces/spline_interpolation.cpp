#include "surfaces/spline_interpolation.h"

#include <Eigen/SparseLU>
#include <string>

#include "core/errors.h"

namespace mcquad {
namespace {

using Rows = Eigen::Matrix<double, Eigen::Dynamic, 3>;

//! Span index and the four non-zero cubic basis values at x (The NURBS Book,
//! algorithms A2.1 and A2.2) on a clamped knot vector for `poles` poles.
int cubic_basis(const std::vector<double>& knots, int poles, double x, double values[4]) {
  int span = 3;
  if (x >= knots[size_t(poles)]) {
    span = poles - 1;
  } else {
    while (knots[size_t(span + 1)] <= x) ++span;
  }
  double left[4], right[4];
  values[0] = 1;
  for (int j = 1; j <= 3; ++j) {
    left[j] = x - knots[size_t(span + 1 - j)];
    right[j] = knots[size_t(span + j)] - x;
    double saved = 0;
    for (int r = 0; r < j; ++r) {
      double temp = values[r] / (right[r + 1] + left[j - r]);
      values[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    values[j] = saved;
  }
  return span;
}

//! Cubic interpolation along one direction, factored once per region
//! direction and applied to every row of data. Clamped: the data at 0..m-1
//! plus the end derivatives; periodic: the data only.
class CurveInterpolation {
 public:
  CurveInterpolation(int data_count, bool periodic) : m_(data_count), periodic_(periodic) {
    int n = poles();
    std::vector<Eigen::Triplet<double>> entries;
    if (periodic_) {
      for (int j = 0; j < m_; ++j) {
        entries.emplace_back(j, (j + m_ - 1) % m_, 1.0 / 6.0);
        entries.emplace_back(j, j, 4.0 / 6.0);
        entries.emplace_back(j, (j + 1) % m_, 1.0 / 6.0);
      }
    } else {
      std::vector<double> knots(size_t(n + 4));
      for (int k = 0; k < n + 4; ++k) knots[size_t(k)] = std::clamp(double(k - 3), 0.0, double(m_ - 1));
      for (int j = 0; j < m_; ++j) {
        double values[4];
        int span = cubic_basis(knots, n, double(j), values);
        for (int k = 0; k < 4; ++k)
          if (values[k] != 0) entries.emplace_back(j, span - 3 + k, values[k]);
      }
      // Knots one apart: S'(0) = 3 (P1 - P0), S'(m-1) = 3 (P[n-1] - P[n-2]).
      entries.emplace_back(m_, 0, -3.0);
      entries.emplace_back(m_, 1, 3.0);
      entries.emplace_back(m_ + 1, n - 2, -3.0);
      entries.emplace_back(m_ + 1, n - 1, 3.0);
    }
    // Summing duplicates makes a periodic m of 1 or 2 well defined too.
    Eigen::SparseMatrix<double> matrix(n, n);
    matrix.setFromTriplets(entries.begin(), entries.end());
    solver_.compute(matrix);
    if (solver_.info() != Eigen::Success)
      throw UnsupportedError("surfaces: no interpolating B-spline through " + std::to_string(m_) + " points");
  }

  int poles() const { return periodic_ ? m_ : m_ + 2; }

  //! data: m rows; start/end: the end derivatives (ignored when periodic).
  Rows solve(const Rows& data, const Eigen::RowVector3d& start, const Eigen::RowVector3d& end) const {
    Rows rhs(poles(), 3);
    rhs.topRows(m_) = data;
    if (!periodic_) {
      rhs.row(m_) = start;
      rhs.row(m_ + 1) = end;
    }
    return solver_.solve(rhs);
  }

 private:
  int m_;
  bool periodic_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> solver_;
};

Eigen::RowVector3d row_of(const QuadMesh& mesh, int v) { return point_of(mesh, QuadMesh::VertexHandle(v)).transpose(); }

Eigen::RowVector3d tangent(const QuadMesh& mesh, int from, int toward) {
  return grid_tangent(mesh, QuadMesh::VertexHandle(from), QuadMesh::VertexHandle(toward)).transpose();
}

}  // namespace

BSplineSurface interpolate_region(const QuadMesh& mesh, const PatchRegion& region) {
  const int cu = region.columns, rv = region.rows;
  if ((!region.periodic_u && cu < 2) || (!region.periodic_v && rv < 2))
    throw UnsupportedError("surfaces: a region needs at least one face in each direction");
  CurveInterpolation along_u(cu, region.periodic_u), along_v(rv, region.periodic_v);
  const Eigen::RowVector3d zero = Eigen::RowVector3d::Zero();
  const int nv = along_v.poles();

  // 1. Every column of vertices along v, with the cross tangents of the v-sides.
  std::vector<Rows> columns(static_cast<size_t>(cu));
  for (int i = 0; i < cu; ++i) {
    Rows data(rv, 3);
    for (int j = 0; j < rv; ++j) data.row(j) = row_of(mesh, region.vertex(i, j));
    Eigen::RowVector3d start = zero, end = zero;
    if (!region.periodic_v) {
      start = tangent(mesh, region.vertex(i, 0), region.vertex(i, 1));
      end = -tangent(mesh, region.vertex(i, rv - 1), region.vertex(i, rv - 2));
    }
    columns[size_t(i)] = along_v.solve(data, start, end);
  }
  // 2. The u-sides' cross tangents, interpolated along v the same way (zero
  // twists), give the end derivatives of step 3's rows.
  Rows side_start = Rows::Zero(nv, 3), side_end = Rows::Zero(nv, 3);
  if (!region.periodic_u) {
    Rows start(rv, 3), end(rv, 3);
    for (int j = 0; j < rv; ++j) {
      start.row(j) = tangent(mesh, region.vertex(0, j), region.vertex(1, j));
      end.row(j) = -tangent(mesh, region.vertex(cu - 1, j), region.vertex(cu - 2, j));
    }
    side_start = along_v.solve(start, zero, zero);
    side_end = along_v.solve(end, zero, zero);
  }
  // 3. Every row of step 1's poles along u.
  BSplineSurface surface;
  surface.periodic_u = region.periodic_u;
  surface.periodic_v = region.periodic_v;
  surface.poles_u = along_u.poles();
  surface.poles_v = nv;
  surface.poles.resize(size_t(surface.poles_u) * size_t(nv));
  for (int k = 0; k < nv; ++k) {
    Rows data(cu, 3);
    for (int i = 0; i < cu; ++i) data.row(i) = columns[size_t(i)].row(k);
    Rows row = along_u.solve(data, side_start.row(k), side_end.row(k));
    for (int i = 0; i < surface.poles_u; ++i)
      surface.poles[size_t(k) * size_t(surface.poles_u) + size_t(i)] = row.row(i).transpose();
  }
  return surface;
}

}  // namespace mcquad
