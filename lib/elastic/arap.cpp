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

RotationFit fit_rotation(const Mat32& J, double s, const Vec3& frame_normal) {
  RotationFit out;
  const double a = J.col(0).squaredNorm(), b = J.col(0).dot(J.col(1)), c = J.col(1).squaredNorm();
  const double tr = a + c;
  // The eigenvalues of J^T J, each to round-off: the energy of a frame at rest is then round-off
  // squared, not round-off.
  const double half_gap = std::sqrt(0.25 * (a - c) * (a - c) + b * b);
  const double l1 = 0.5 * tr + half_gap;
  const double det = std::max(a * c - b * b, 0.0);
  const double l2 = l1 > 0 ? det / l1 : 0.0;
  const double s1 = std::sqrt(l1), s2 = std::sqrt(l2);
  out.energy = (s1 - s) * (s1 - s) + (s2 - s) * (s2 - s);
  if (!(tr > 0)) return out;
  // R = U V^T from J's singular vectors; with J of rank one, U's second column lies in the
  // frame's tangent plane.
  Vec2 v1 = std::abs(b) > 0 ? Vec2(b, l1 - a) : (a >= c ? Vec2(1, 0) : Vec2(0, 1));
  v1.normalize();
  const Vec2 v2(-v1.y(), v1.x());
  const Vec3 u1 = J * v1 / s1;
  Vec3 u2 = Vec3::Zero();
  if (s2 > kRankOne * s1) {
    u2 = J * v2 / s2;
  } else if (const double nn = frame_normal.norm(); nn > 0) {
    u2 = frame_normal.cross(u1) / nn;
  }
  out.rotation = u1 * v1.transpose() + u2 * v2.transpose();
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
