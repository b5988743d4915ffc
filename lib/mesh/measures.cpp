#include "mesh/measures.h"

#include <cmath>

#include <Eigen/Geometry>

#include "core/error.h"
#include "core/number_format.h"

namespace skinslide {

std::vector<double> bar_lengths(const Positions3& points,
                                const std::vector<std::array<Index, 2>>& bars) {
  std::vector<double> lengths(bars.size());
  for (size_t i = 0; i < bars.size(); ++i)
    lengths[i] = (points[bars[i][0]] - points[bars[i][1]]).norm();
  return lengths;
}

void require_computable_span(const Positions3& points, const std::vector<Index>& ids) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  size_t largest = 0;
  double largest_coordinate = -1;
  for (size_t i = 0; i < points.size(); ++i) {
    lo = lo.cwiseMin(points[i]);
    hi = hi.cwiseMax(points[i]);
    if (const double c = points[i].cwiseAbs().maxCoeff(); c > largest_coordinate) {
      largest_coordinate = c;
      largest = i;
    }
  }
  if (points.empty()) return;
  // Halved first: the diagonal of a box near the largest doubles would itself overflow.
  const double span = 2 * (0.5 * hi - 0.5 * lo).stableNorm();
  if (span == 0 || (span >= kSmallestPatchSpan && span <= kLargestPatchSpan)) return;
  const Vec3& p = points[largest];
  const std::string where = "vertex " + std::to_string(ids[largest]) + " at (" + log_number(p[0]) +
                            ", " + log_number(p[1]) + ", " + log_number(p[2]) +
                            "): coordinates too ";
  if (span < kSmallestPatchSpan)
    throw Error(ErrorKind::Input,
                where + "small: the patch spans " + log_number(span) +
                    ", under the smallest span of " + log_number(kSmallestPatchSpan) +
                    " (frames are compared with the bind, and caches hold positions, in float32, "
                    "which loses precision under 1e-38; lengths' squares underflow a double "
                    "further down); scale the mesh up");
  throw Error(ErrorKind::Input,
              where + "large: the patch spans " + log_number(span) +
                  ", and its lengths' squares and products overflow a double beyond a span of " +
                  log_number(kLargestPatchSpan) + "; scale the mesh down");
}

Folds count_folds(const Positions2& net, const std::vector<Triangle>& triangles) {
  std::vector<double> area(triangles.size());
  int positive = 0, negative = 0;
  for (size_t t = 0; t < triangles.size(); ++t) {
    const Vec2 e1 = net[triangles[t][1]] - net[triangles[t][0]];
    const Vec2 e2 = net[triangles[t][2]] - net[triangles[t][0]];
    area[t] = e1.x() * e2.y() - e1.y() * e2.x();
    positive += area[t] > 0;
    negative += area[t] < 0;
  }
  const double sign = positive >= negative ? 1.0 : -1.0;
  Folds folds;
  for (size_t t = 0; t < area.size(); ++t) {
    folds.flipped += area[t] * sign <= 0;
    if (area[t] * sign < 0) folds.reversed.push_back(static_cast<Index>(t));
  }
  return folds;
}

int flipped_triangles(const Positions2& net, const std::vector<Triangle>& triangles) {
  return count_folds(net, triangles).flipped;
}

bool turned_against(const Vec3& slid, const Vec3& frame) {
  const double frame_size = frame.cwiseAbs().maxCoeff();
  if (frame_size == 0) return false;
  const double slid_size = slid.cwiseAbs().maxCoeff();
  if (!(slid_size > 0)) return true;
  return !((slid / slid_size).dot(frame / frame_size) > 0);
}

int turned_triangles(const std::vector<Triangle>& triangles, const Positions3& frame,
                     const Positions3& slid) {
  int turned = 0;
  for (const Triangle& t : triangles) {
    const Vec3 nf = (frame[t[1]] - frame[t[0]]).cross(frame[t[2]] - frame[t[0]]);
    const Vec3 ns = (slid[t[1]] - slid[t[0]]).cross(slid[t[2]] - slid[t[0]]);
    turned += turned_against(ns, nf) ? 1 : 0;
  }
  return turned;
}

}  // namespace skinslide
