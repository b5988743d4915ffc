// The elastic method's energy: as-rigid-as-possible against the bind's triangles (Sorkine &
// Alexa 2007), lib/elastic/README.md rules 3, 4 and 6. Per triangle the deformation gradient J
// (3x2) from its bind shape; the energy w sum_t (s1 - s)^2 + (s2 - s)^2 of J's singular values,
// and with rotations R_t held, w sum_t |J_t - s R_t|^2, a quadratic in the positions.
#pragma once

#include <array>
#include <vector>

#include "core/types.h"

namespace skinslide {

using Mat32 = Eigen::Matrix<double, 3, 2>;

/// A bind triangle's rest shape: the inverse D of its edge matrix in a 2D frame of its own plane,
/// so that J = [x_b - x_a, x_c - x_a] D. Zero for a triangle with
/// 2 |area| <= 1e-12 (|e1|^2 + |e2|^2 + |e2 - e1|^2): its shape is round-off, it has no energy.
Eigen::Matrix2d rest_inverse(const Vec3& a, const Vec3& b, const Vec3& c);

inline bool has_rest_shape(const Eigen::Matrix2d& D) { return D(0, 0) != 0; }

/// The three gradient rows G_k of a triangle with rest inverse D: J = sum_k x_k G_k^T.
std::array<Vec2, 3> gradient_rows(const Eigen::Matrix2d& D);

/// J of triangle `t` at positions `x` (indexed by the triangle's ids).
Mat32 deformation_gradient(const Positions3& x, const Triangle& t, const Eigen::Matrix2d& D);

/// J = s1 u1 v1^T + s2 u2 v2^T (s1 >= s2 >= 0); `found` false for J = 0. A J of rank one takes
/// u2 in the plane normal to `frame_normal` (zero if that is zero).
struct SingularFrame {
  double s1 = 0, s2 = 0;
  Vec3 u1 = Vec3::Zero(), u2 = Vec3::Zero();
  Vec2 v1 = Vec2::Zero(), v2 = Vec2::Zero();
  bool found = false;
};
SingularFrame singular_frame(const Mat32& J, const Vec3& frame_normal);

/// The rotation nearest J (3x2 with orthonormal columns: ARAP's local step) and the ARAP energy
/// (s1 - s)^2 + (s2 - s)^2 of J's singular values, which is |J - s R|^2 for that R. A J of rank
/// one takes R's second column in the plane normal to `frame_normal`.
struct RotationFit {
  double energy = 0;
  Mat32 rotation = Mat32::Zero();
};
RotationFit fit_rotation(const Mat32& J, double s, const Vec3& frame_normal);

/// The ARAP energy's second derivative in J with the rotation refitted (min_R |J - s R|^2), made
/// semi-definite: 2 (I - sum_m softening_m mode_m (x) mode_m) over J's entries, the three modes
/// orthonormal. Zero softening (the held-rotation curvature 2 I) for J = 0.
struct TriangleCurvature {
  std::array<Mat32, 3> mode{Mat32::Zero(), Mat32::Zero(), Mat32::Zero()};
  std::array<double, 3> softening{0, 0, 0};
  /// The curvature times dJ, per unit weight.
  Mat32 times(const Mat32& dJ) const {
    Mat32 out = 2 * dJ;
    for (int m = 0; m < 3; ++m) out -= 2 * softening[m] * mode[m].cwiseProduct(dJ).sum() * mode[m];
    return out;
  }
};
TriangleCurvature arap_curvature(const Mat32& J, double s, const Vec3& frame_normal);

/// The triangles and rest shapes the energy sums over, with every triangle's weight.
struct ArapTriangles {
  /// The patch's triangles (local ids) are the first `count` (the chart's: fill triangles follow).
  const std::vector<Triangle>& triangles;
  Index count = 0;
  const std::vector<Eigen::Matrix2d>& rest_inverse;  ///< per patch triangle
  double weight = 0;  ///< every triangle's: the mean bind triangle area
};

/// ARAP energy at `x` with target stretch `s`: w sum_t min_R |J_t - s R|^2.
double arap_energy(const ArapTriangles& mesh, const Positions3& x, double s,
                   const std::vector<Vec3>& frame_normals);

/// ARAP's local step: every triangle's nearest rotation at `x` (zero without a rest shape).
std::vector<Mat32> fitted_rotations(const ArapTriangles& mesh, const Positions3& x,
                                    const std::vector<Vec3>& frame_normals);

/// ARAP's global energy with the rotations R held, w sum_t |J_t - s R_t|^2; with `gradient`,
/// also its gradient per vertex of `x`.
double held_rotation_energy(const ArapTriangles& mesh, const Positions3& x, double s,
                            const std::vector<Mat32>& R, Positions3* gradient = nullptr);

}  // namespace skinslide
