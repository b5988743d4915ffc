#include "elastic/arap.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include <Eigen/LU>

namespace skinslide {
namespace {

// Below this share of its edges' squares, a triangle's area is round-off: it has no rest shape.
constexpr double kFlatTriangle = 1e-12;
// A J whose second singular value is below this share of its first has rank one.
constexpr double kRankOne = 1e-12;

}  // namespace

Eigen::Matrix2d rest_inverse(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 f1 = b - a, f2 = c - a;
  const double l1 = f1.norm();
  const double twice_area = f1.cross(f2).norm();
  const double scale = f1.squaredNorm() + f2.squaredNorm() + (f2 - f1).squaredNorm();
  if (!(l1 > 0) || !(twice_area > kFlatTriangle * scale)) return Eigen::Matrix2d::Zero();
  const Vec3 ex = f1 / l1;
  Eigen::Matrix2d B;
  B << l1, f2.dot(ex), 0, twice_area / l1;
  return B.inverse();
}

std::array<Vec2, 3> gradient_rows(const Eigen::Matrix2d& D) {
  const Vec2 g1 = D.row(0).transpose(), g2 = D.row(1).transpose();
  return {-(g1 + g2), g1, g2};
}

Mat32 deformation_gradient(const Positions3& x, const Triangle& t, const Eigen::Matrix2d& D) {
  Mat32 e;
  e.col(0) = x[t[1]] - x[t[0]];
  e.col(1) = x[t[2]] - x[t[0]];
  return e * D;
}

SingularFrame singular_frame(const Mat32& J, const Vec3& frame_normal) {
  SingularFrame out;
  const double a = J.col(0).squaredNorm(), b = J.col(0).dot(J.col(1)), c = J.col(1).squaredNorm();
  const double tr = a + c;
  // The eigenvalues of J^T J, each to round-off: the energy of a frame at rest is then round-off
  // squared, not round-off.
  const double half_gap = std::sqrt(0.25 * (a - c) * (a - c) + b * b);
  const double l1 = 0.5 * tr + half_gap;
  const double det = std::max(a * c - b * b, 0.0);
  const double l2 = l1 > 0 ? det / l1 : 0.0;
  out.s1 = std::sqrt(l1);
  out.s2 = std::sqrt(l2);
  if (!(tr > 0)) return out;
  // J's singular vectors; with J of rank one, u2 lies in the frame's tangent plane.
  Vec2 v1 = std::abs(b) > 0 ? Vec2(b, l1 - a) : (a >= c ? Vec2(1, 0) : Vec2(0, 1));
  v1.normalize();
  out.v1 = v1;
  out.v2 = Vec2(-v1.y(), v1.x());
  out.u1 = J * out.v1 / out.s1;
  if (out.s2 > kRankOne * out.s1) {
    out.u2 = J * out.v2 / out.s2;
  } else if (const double nn = frame_normal.norm(); nn > 0) {
    out.u2 = frame_normal.cross(out.u1) / nn;
  }
  out.found = true;
  return out;
}

RotationFit fit_rotation(const Mat32& J, double s, const Vec3& frame_normal) {
  RotationFit out;
  const SingularFrame f = singular_frame(J, frame_normal);
  out.energy = (f.s1 - s) * (f.s1 - s) + (f.s2 - s) * (f.s2 - s);
  if (f.found) out.rotation = f.u1 * f.v1.transpose() + f.u2 * f.v2.transpose();
  return out;
}

TriangleCurvature arap_curvature(const Mat32& J, double s, const Vec3& frame_normal) {
  TriangleCurvature out;
  const SingularFrame f = singular_frame(J, frame_normal);
  if (!f.found || f.u2.isZero(0)) return out;
  const Vec3 n = f.u1.cross(f.u2);
  // The modes whose stiffness the rotation's refit takes away, and the share it takes: a twist in
  // J's plane, 2 s / (s1 + s2), and each column turning out of it, s / s_k (Smith et al. 2019,
  // "Analytic Eigensystems for Isotropic Distortion Energies"), at most all of it (the
  // projection to a semi-definite curvature).
  out.mode[0] = (f.u1 * f.v2.transpose() - f.u2 * f.v1.transpose()) / std::sqrt(2.0);
  out.mode[1] = n * f.v1.transpose();
  out.mode[2] = n * f.v2.transpose();
  const double sum = f.s1 + f.s2;
  out.softening[0] = sum > 0 ? std::min(1.0, 2 * s / sum) : 1.0;
  out.softening[1] = f.s1 > 0 ? std::min(1.0, s / f.s1) : 1.0;
  out.softening[2] = f.s2 > 0 ? std::min(1.0, s / f.s2) : 1.0;
  return out;
}

double arap_energy(const ArapTriangles& mesh, const Positions3& x, double s,
                   const std::vector<Vec3>& frame_normals) {
  double total = 0;
  for (Index t = 0; t < mesh.count; ++t) {
    const Eigen::Matrix2d& D = mesh.rest_inverse[t];
    if (has_rest_shape(D))
      total +=
          fit_rotation(deformation_gradient(x, mesh.triangles[t], D), s, frame_normals[t]).energy;
  }
  return mesh.weight * total;
}

std::vector<Mat32> fitted_rotations(const ArapTriangles& mesh, const Positions3& x,
                                    const std::vector<Vec3>& frame_normals) {
  std::vector<Mat32> R(mesh.count, Mat32::Zero());
  for (Index t = 0; t < mesh.count; ++t) {
    const Eigen::Matrix2d& D = mesh.rest_inverse[t];
    if (has_rest_shape(D))
      R[t] = fit_rotation(deformation_gradient(x, mesh.triangles[t], D), 1.0, frame_normals[t])
                 .rotation;
  }
  return R;
}

double held_rotation_energy(const ArapTriangles& mesh, const Positions3& x, double s,
                            const std::vector<Mat32>& R, Positions3* gradient) {
  if (gradient) gradient->assign(x.size(), Vec3::Zero());
  double total = 0;
  for (Index t = 0; t < mesh.count; ++t) {
    const Eigen::Matrix2d& D = mesh.rest_inverse[t];
    if (!has_rest_shape(D)) continue;
    const Triangle& tri = mesh.triangles[t];
    const Mat32 r = deformation_gradient(x, tri, D) - s * R[t];
    total += r.squaredNorm();
    if (!gradient) continue;
    const std::array<Vec2, 3> G = gradient_rows(D);
    for (int k = 0; k < 3; ++k) (*gradient)[tri[k]] += 2 * mesh.weight * (r * G[k]);
  }
  return mesh.weight * total;
}

}  // namespace skinslide
