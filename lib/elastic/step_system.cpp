#include "elastic/step_system.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace skinslide {
namespace {

using Mat2 = Eigen::Matrix<double, Eigen::Dynamic, 2>;

// An inexact Newton step: the line search measures the true energy. A looser solve changes the
// slides (ICT cheek spread 0.819 at 1e-4, 0.839 at 1e-3 and 1e-2) for little time.
constexpr double kStepTolerance = 1e-4;
constexpr int kMaxMultigridIterations = 200;
// A vertex's own tangent coordinates are used when its Jacobian is this far from rank one
// (singular values' ratio 1e-4): closer, they would magnify the solve's error in the chart.
constexpr double kWellConditioned = 1e-8;

// Vertex i's change of variables d_i = S^-1 xi_i, and Q = T S^-1: with S^T S = T^T T, Q has
// orthonormal columns and the system's blocks K_ij Q_i^T Q_j are close to K_ij I. A Jacobian near
// rank one (a frame crushed towards a line there) keeps the chart's own coordinates.
struct TangentFrame {
  Eigen::Matrix2d S_inverse = Eigen::Matrix2d::Identity();
  Mat32 Q = Mat32::Zero();
};

TangentFrame tangent_frame(const Mat32& T) {
  TangentFrame out;
  out.Q = T;
  const Eigen::Matrix2d M = T.transpose() * T;
  const double trace = M.trace(), det = M.determinant();
  if (!(trace > 0) || !std::isfinite(trace) || !(det > kWellConditioned * trace * trace))
    return out;
  const Eigen::Matrix2d S = M.llt().matrixU();
  out.S_inverse = S.inverse();
  out.Q = T * out.S_inverse;
  return out;
}

}  // namespace

SparseMatrix step_pattern(const std::vector<Index>& start, const std::vector<Index>& column) {
  const Index m = static_cast<Index>(start.size()) - 1;
  SparseMatrix H(2 * m, 2 * m);
  H.resizeNonZeros(static_cast<Eigen::Index>(4 * column.size()));
  int* outer = H.outerIndexPtr();
  int* inner = H.innerIndexPtr();
  Index k = 0;
  for (Index j = 0; j < m; ++j)
    for (int b = 0; b < 2; ++b) {
      outer[2 * j + b] = k;
      for (Index e = start[j]; e < start[j + 1]; ++e) {
        inner[k++] = 2 * column[e];
        inner[k++] = 2 * column[e] + 1;
      }
    }
  outer[2 * m] = k;
  std::fill(H.valuePtr(), H.valuePtr() + k, 0.0);
  return H;
}

std::shared_ptr<const StepMultigrid> step_multigrid(const std::vector<Index>& start,
                                                    const std::vector<Index>& column,
                                                    const std::vector<double>& value) {
  const Index m = static_cast<Index>(start.size()) - 1;
  std::vector<double> lumped(m, 0.0);
  for (Index j = 0; j < m; ++j)
    for (Index e = start[j]; e < start[j + 1]; ++e)
      if (column[e] == j || value[e] > 0) lumped[j] += value[e];
  SparseMatrix A = step_pattern(start, column);
  double* a = A.valuePtr();
  Index k = 0;
  for (Index j = 0; j < m; ++j)
    for (int b = 0; b < 2; ++b)
      for (Index e = start[j]; e < start[j + 1]; ++e)
        for (int c = 0; c < 2; ++c, ++k)
          if (c == b) a[k] = column[e] == j ? lumped[j] : std::min(value[e], 0.0);
  AggregationMultigrid hierarchy(A);
  std::vector<Index> level0_slot(hierarchy.value_slot().size());
  for (size_t q = 0; q < level0_slot.size(); ++q)
    level0_slot[hierarchy.value_slot()[q]] = static_cast<Index>(q);
  return std::make_shared<const StepMultigrid>(
      StepMultigrid{std::move(hierarchy), std::move(level0_slot)});
}

StepSystem::StepSystem(const std::vector<Index>& start, const std::vector<Index>& column,
                       const std::vector<double>& value, const StepMultigrid& multigrid)
    : start_(start),
      column_(column),
      value_(value),
      multigrid_(multigrid),
      values_(multigrid.level0_slot.size()) {}

bool StepSystem::solve(const std::vector<Mat32>& T, const std::vector<char>& held,
                       const std::vector<Vec3>& gradient, Positions2& d) {
  const Index m = static_cast<Index>(start_.size()) - 1;
  std::vector<TangentFrame> frame(m);
  for (Index i = 0; i < m; ++i)
    if (!held[i]) frame[i] = tangent_frame(T[i]);
  Index k = 0;
  double trace = 0;
  for (Index j = 0; j < m; ++j)
    for (int b = 0; b < 2; ++b)
      for (Index e = start_[j]; e < start_[j + 1]; ++e) {
        const Index i = column_[e];
        for (int a = 0; a < 2; ++a, ++k) {
          double& v = entry(k);
          if (held[i] || held[j])
            v = (i == j && a == b) ? 1.0 : 0.0;
          else
            v = value_[e] * frame[i].Q.col(a).dot(frame[j].Q.col(b));
          if (i == j && a == b) trace += v;
        }
      }
  // A frame triangle crushed to a line leaves its vertices' blocks singular: a whisper of the
  // identity keeps the system definite without changing any well-posed step.
  const double mu = 1e-12 * trace / std::max<double>(1, 2 * m) + 1e-300;
  k = 0;
  for (Index j = 0; j < m; ++j)
    for (int b = 0; b < 2; ++b)
      for (Index e = start_[j]; e < start_[j + 1]; ++e)
        for (int a = 0; a < 2; ++a, ++k)
          if (column_[e] == j && a == b) entry(k) += mu;
  Mat2 rhs = Mat2::Zero(2 * m, 2);
  for (Index i = 0; i < m; ++i)
    if (!held[i]) rhs.block<2, 1>(2 * i, 0) = -(frame[i].Q.transpose() * gradient[i]);
  Mat2 x = Mat2::Zero(2 * m, 2);
  // A system no larger than the multigrid's coarsest level (a patch of up to about 100 movable
  // vertices) is factorised directly, its ordering computed once per frame, not once per solve.
  bool solved = false;
  if (multigrid_.hierarchy.levels() > 1) {
    const MultigridResult result =
        multigrid_.hierarchy.solve(values_, rhs, x, kStepTolerance, kMaxMultigridIterations);
    multigrid_iterations += result.iterations;
    solved = result.converged && x.allFinite();
  }
  if (!solved) {
    ++direct_solves;
    if (!solve_directly(rhs, x)) return false;
  }
  d.resize(m);
  for (Index i = 0; i < m; ++i)
    d[i] = held[i] ? Vec2::Zero() : Vec2(frame[i].S_inverse * x.block<2, 1>(2 * i, 0));
  return true;
}

// Small systems, and those on which the multigrid stalls (far from K x I2: neighbouring tangent
// planes far apart, as at a crease of the frame): a sparse LDL^T factorisation solves them.
bool StepSystem::solve_directly(const Mat2& b, Mat2& x) {
  if (H_.size() == 0) {
    H_ = step_pattern(start_, column_);
    direct_.analyzePattern(H_);
  }
  const std::vector<Index>& slot = multigrid_.hierarchy.value_slot();
  for (size_t k = 0; k < slot.size(); ++k) H_.valuePtr()[slot[k]] = values_[k];
  direct_.factorize(H_);
  if (direct_.info() != Eigen::Success) return false;
  x.col(0) = direct_.solve(b.col(0));
  x.col(1).setZero();
  return x.allFinite();
}

}  // namespace skinslide
