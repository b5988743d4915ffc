#include "elastic/blended_surface.h"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

#include "elastic/surface_map.h"

namespace skinslide {
namespace {

double inradius(const Chart& chart, Index t) {
  const Triangle& tri = chart.triangles[t];
  const Vec2 &a = chart.uv[tri[0]], &b = chart.uv[tri[1]], &c = chart.uv[tri[2]];
  const double perimeter = (b - a).norm() + (c - b).norm() + (a - c).norm();
  return perimeter > 0 ? std::abs(cross2(b - a, c - a)) / perimeter : 0.0;
}

// A vertex that moves near an edge lies off the facets by up to the crease's angle times the
// edge's band width, and each triangle at that vertex feels it against its own size: a sliver's
// energy grows with that offset over its inradius, so the slide written on the facets gains
// less than the relaxed one, or nothing. An edge's band is therefore at most this many times the
// smallest inradius among the triangles around either of its ends: where neighbouring triangles
// are within 3x of each other's size it changes nothing (the bound's measurements:
// tests/bench/elastic.md "Slivers under the blend").
constexpr double kSliverFanShare = 3;

bool is_patch(const Chart& chart, Index t) { return t >= 0 && t < chart.patch_triangle_count; }

struct Box {
  Vec2 lo = Vec2::Constant(INFINITY), hi = Vec2::Constant(-INFINITY);
  void add(const Vec2& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool meets(const Box& o) const {
    return lo.x() <= o.hi.x() && o.lo.x() <= hi.x() && lo.y() <= o.hi.y() && o.lo.y() <= hi.y();
  }
};

// Where triangle f's weight is not zero: the triangle with its blended edges' lines moved out by
// their half-widths (a needle's reaches far past its tip), boxed.
Box support_box(const Chart& chart, const BlendEdges& e, Index f) {
  Box box;
  for (int k = 0; k < 3; ++k) {
    // Corner k lies on edges k + 1 and k + 2.
    const int a = (k + 1) % 3, b = (k + 2) % 3;
    Eigen::Matrix2d lines;
    lines.row(0) = e.normal[a].transpose();
    lines.row(1) = e.normal[b].transpose();
    const Vec2 rhs(e.offset[a] - e.width[a], e.offset[b] - e.width[b]);
    const Vec2 corner = lines.partialPivLu().solve(rhs);
    box.add(corner.allFinite() ? corner : chart.uv[chart.triangles[f][k]]);
  }
  return box;
}

// Per patch triangle t, every patch triangle whose weight may be non-zero somewhere on t (boxes
// that meet, found through a uniform grid over the chart), t first, the others ascending: the
// blend sums over all of them, so it is the same function seen from either side of an edge.
void gather_around(const Chart& chart, SurfaceBlend& blend) {
  const Index nt = chart.patch_triangle_count;
  std::vector<Box> own(nt), support(nt);
  Box all;
  blend.support.clear();
  for (Index t = 0; t < nt; ++t) {
    for (Index v : chart.triangles[t]) own[t].add(chart.uv[v]);
    // Round-off may leave a located point a hair outside its triangle.
    own[t].lo -= Vec2::Constant(1e-12);
    own[t].hi += Vec2::Constant(1e-12);
    support[t] = support_box(chart, blend.edges[t], t);
    const double reach = blend.edges[t].reach;
    if (std::isfinite(reach)) {
      support[t].lo = support[t].lo.cwiseMax(own[t].lo - Vec2::Constant(reach));
      support[t].hi = support[t].hi.cwiseMin(own[t].hi + Vec2::Constant(reach));
    }
    // Padded as the own boxes are: the box's corners come from a solve, and a node on the box's
    // edge must not be rejected by round-off.
    blend.support.push_back({support[t].lo.x() - 1e-12, support[t].lo.y() - 1e-12,
                             support[t].hi.x() + 1e-12, support[t].hi.y() + 1e-12});
    all.add(own[t].lo);
    all.add(own[t].hi);
  }
  // About two triangles a cell; cells hold the triangles whose support box meets them.
  const Vec2 extent = (all.hi - all.lo).cwiseMax(Vec2::Constant(1e-300));
  const int side = std::clamp(static_cast<int>(std::sqrt(nt / 2.0)), 1, 4096);
  const auto cell = [&](const Vec2& p, int c) {
    return std::clamp(static_cast<int>((p[c] - all.lo[c]) / extent[c] * side), 0, side - 1);
  };
  std::vector<std::vector<Index>> grid(static_cast<size_t>(side) * side);
  for (Index f = 0; f < nt; ++f)
    for (int y = cell(support[f].lo, 1); y <= cell(support[f].hi, 1); ++y)
      for (int x = cell(support[f].lo, 0); x <= cell(support[f].hi, 0); ++x)
        grid[static_cast<size_t>(y) * side + x].push_back(f);
  blend.around_start.assign(static_cast<size_t>(nt) + 1, 0);
  blend.around.clear();
  std::vector<Index> seen(nt, -1), found;
  for (Index t = 0; t < nt; ++t) {
    found.clear();
    seen[t] = t;
    for (int y = cell(own[t].lo, 1); y <= cell(own[t].hi, 1); ++y)
      for (int x = cell(own[t].lo, 0); x <= cell(own[t].hi, 0); ++x)
        for (Index f : grid[static_cast<size_t>(y) * side + x])
          if (seen[f] != t && support[f].meets(own[t])) {
            seen[f] = t;
            found.push_back(f);
          }
    std::sort(found.begin(), found.end());
    blend.around.push_back(t);
    blend.around.insert(blend.around.end(), found.begin(), found.end());
    blend.around_start[t + 1] = static_cast<Index>(blend.around.size());
  }
}

// smoothstep of s clamped to [0, 1], and its derivative.
double ramp(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * (3 - 2 * s);
}
double ramp_slope(double s) { return s <= 0 || s >= 1 ? 0.0 : 6 * s * (1 - s); }

// The ramp of triangle e's edge k at u, and its slope along the edge's normal when `slope` is not
// null: from 0 at -w to 1 at +w of u's signed distance to the edge's line; an edge that is not
// blended (w = 0) keeps its own side only (`own`: u's own triangle, which counts round-off beside
// it as inside).
double edge_ramp(const BlendEdges& e, int k, const Vec2& u, bool own, double* slope) {
  const double h = e.normal[k].dot(u) - e.offset[k];
  const double w = e.width[k];
  if (!(w > 0)) {
    if (slope) *slope = 0;
    return h >= 0 || own ? 1.0 : 0.0;
  }
  // Beyond the band's outer line the ramp is 0 (the quotient below would be <= 0): most triangles
  // listed around a point end here, so the divisions are skipped.
  if (h + w <= 0) {
    if (slope) *slope = 0;
    return 0.0;
  }
  // Inside the band's inner line the ramp is 1 (the quotient would be >= 1), without a division.
  if (h >= w) {
    if (slope) *slope = 0;
    return 1.0;
  }
  const double s = (h + w) / (2 * w);
  if (slope) *slope = ramp_slope(s) / (2 * w);
  return ramp(s);
}

// u's distance to chart triangle t (0 inside) and, outside, its gradient: the unit vector from
// the triangle's nearest point to u.
double distance_to_triangle(const Chart& chart, Index t, const Vec2& u, Vec2* gradient) {
  const Triangle& tri = chart.triangles[t];
  const Vec2 &a = chart.uv[tri[0]], &b = chart.uv[tri[1]], &c = chart.uv[tri[2]];
  if (cross2(b - a, u - a) >= 0 && cross2(c - b, u - b) >= 0 && cross2(a - c, u - c) >= 0) {
    if (gradient) *gradient = Vec2::Zero();
    return 0;
  }
  double best = INFINITY;
  for (int k = 0; k < 3; ++k) {
    const Vec2 &from = chart.uv[tri[(k + 1) % 3]], &to = chart.uv[tri[(k + 2) % 3]];
    const Vec2 edge = to - from;
    const double along = edge.squaredNorm() > 0
                             ? std::clamp((u - from).dot(edge) / edge.squaredNorm(), 0.0, 1.0)
                             : 0.0;
    const Vec2 away = u - (from + along * edge);
    const double d = away.norm();
    if (d < best) {
      best = d;
      if (gradient) *gradient = d > 0 ? Vec2(away / d) : Vec2::Zero();
    }
  }
  return best;
}

// Whether u is certainly within `radius` of chart triangle t: within it of a corner, with a margin
// far above the round-off of distance_to_triangle, so that the two never disagree.
bool surely_within(const Chart& chart, Index t, const Vec2& u, double radius) {
  constexpr double kMargin = 1 - 1e-9;
  const double limit = kMargin * radius * radius;
  for (Index v : chart.triangles[t])
    if ((chart.uv[v] - u).squaredNorm() <= limit) return true;
  return false;
}

// Whether triangle f's bands reach u, a point off f (every ramp above 0).
bool in_bands(const BlendEdges& e, const Vec2& u) {
  for (int k = 0; k < 3; ++k)
    if (!(edge_ramp(e, k, u, false, nullptr) > 0)) return false;
  return true;
}

// Per patch triangle, the distance of the nearest node its bands reach that is not its corner
// (BlendEdges::reach). Such a node lies in the support box of f, so it is a corner of a triangle
// g with f among g's `around`.
void limit_reach(const Chart& chart, SurfaceBlend& blend) {
  const Index nt = chart.patch_triangle_count;
  for (Index g = 0; g < nt; ++g)
    for (Index a = blend.around_start[g] + 1; a < blend.around_start[g + 1]; ++a) {
      const Index f = blend.around[a];
      BlendEdges& e = blend.edges[f];
      for (Index n : chart.triangles[g]) {
        const Triangle& corners = chart.triangles[f];
        if (n == corners[0] || n == corners[1] || n == corners[2]) continue;
        if (!in_bands(e, chart.uv[n])) continue;
        e.reach = std::min(e.reach, distance_to_triangle(chart, f, chart.uv[n], nullptr));
      }
    }
}

}  // namespace

SurfaceBlend surface_blend(const Chart& chart, double width_share) {
  const Index nt = chart.patch_triangle_count;
  SurfaceBlend blend;
  blend.edges.resize(nt);
  std::vector<double> r(nt);
  for (Index t = 0; t < nt; ++t) r[t] = inradius(chart, t);
  // Per node the smallest inradius of the triangles around it (kSliverFanShare).
  std::vector<double> fan_r(chart.uv.size(), INFINITY);
  for (Index t = 0; t < nt; ++t)
    for (Index v : chart.triangles[t]) fan_r[v] = std::min(fan_r[v], r[t]);
  for (Index t = 0; t < nt; ++t) {
    const Triangle& tri = chart.triangles[t];
    BlendEdges& e = blend.edges[t];
    for (int k = 0; k < 3; ++k) {
      const Vec2 &a = chart.uv[tri[(k + 1) % 3]], &b = chart.uv[tri[(k + 2) % 3]];
      // Counter-clockwise triangles: the inside is to the left of a -> b.
      Vec2 n(a.y() - b.y(), b.x() - a.x());
      const double length = n.norm();
      if (length > 0) n /= length;
      e.normal[k] = n;
      e.offset[k] = n.dot(a);
      const Index across = chart.neighbour[t][k];
      const double fan = std::min(fan_r[tri[(k + 1) % 3]], fan_r[tri[(k + 2) % 3]]);
      e.width[k] = is_patch(chart, across)
                       ? width_share * std::min({r[t], r[across], kSliverFanShare * fan})
                       : 0.0;
    }
  }
  gather_around(chart, blend);
  limit_reach(chart, blend);
  gather_around(chart, blend);
  return blend;
}

Vec3 blended_point(const FrameSurface& surface, Index t, const Vec2& u, Mat32* jacobian) {
  const SurfaceBlend& blend = *surface.blend;
  double total = 0;
  Vec3 sum = Vec3::Zero();
  Vec2 total_slope = Vec2::Zero();
  Mat32 sum_slope = Mat32::Zero();
  for (Index a = blend.around_start[t]; a < blend.around_start[t + 1]; ++a) {
    const Index f = blend.around[a];
    const std::array<double, 4>& box = blend.support[f];
    // The point's own triangle always counts: it keeps the sum above zero.
    if (f != t && (u.x() < box[0] || u.y() < box[1] || u.x() > box[2] || u.y() > box[3])) continue;
    const BlendEdges& e = blend.edges[f];
    std::array<double, 3> r{}, dr{};
    bool outside = false;
    for (int k = 0; k < 3 && !outside; ++k) {
      r[k] = edge_ramp(e, k, u, f == t, jacobian ? &dr[k] : nullptr);
      outside = !(r[k] > 0);
    }
    if (outside) continue;
    double phi = r[0] * r[1] * r[2];
    Vec2 slope = Vec2::Zero();
    if (jacobian)
      slope = dr[0] * r[1] * r[2] * e.normal[0] + r[0] * dr[1] * r[2] * e.normal[1] +
              r[0] * r[1] * dr[2] * e.normal[2];
    if (f != t && std::isfinite(e.reach) && !surely_within(surface.chart, f, u, e.reach / 2)) {
      // The fade from reach / 2 to reach; constant near the triangle, where the distance has a
      // corner. (The point lies on its own triangle t: no fade there.)
      Vec2 away;
      const double d = distance_to_triangle(surface.chart, f, u, &away);
      if (d >= e.reach) continue;
      if (d > e.reach / 2) {
        const double s = (e.reach - d) / (e.reach / 2);
        const double fade = ramp(s);
        slope = fade * slope - phi * ramp_slope(s) / (e.reach / 2) * away;
        phi *= fade;
      }
    }
    const Mat32& J = surface.facet_jacobian[f];
    const Index corner = surface.chart.triangles[f][0];
    const Vec3 plane = surface.frame[corner] + J * (u - surface.chart.uv[corner]);
    total += phi;
    sum += phi * plane;
    if (jacobian) {
      total_slope += slope;
      sum_slope += phi * J + plane * slope.transpose();
    }
  }
  const Vec3 x = sum / total;
  if (jacobian) *jacobian = (sum_slope - x * total_slope.transpose()) / total;
  return x;
}

Vec3 relaxed_point(const FrameSurface& surface, const ChartPoint& where, const Vec2& u) {
  return surface.blend ? blended_point(surface, where.triangle, u) : surface_point(surface, where);
}

}  // namespace skinslide
