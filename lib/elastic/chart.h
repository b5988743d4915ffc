// The elastic method's chart: one fixed, injective 2D map of a patch, built once at bind time.
// Every frame's slide happens in it: a free vertex moves in the chart and lands on the frame's
// surface at the frame triangle under its chart point, so it never leaves the surface.
#pragma once

#include <array>
#include <vector>

#include "core/types.h"

namespace skinslide {

/// The patch as a disk in the unit square: its outer loop on the circle of radius 1/2 about
/// (1/2, 1/2), spaced by bind arc length from the loop's first vertex (angle 0, turning so that
/// the patch's triangles are counter-clockwise); every hole closed by a virtual centre node; every
/// other node where its mean-value weights (Floater 2003) on the bind balance it. A convex border
/// and positive weights make the embedding injective (Tutte, Floater); a chart is kept only when
/// every triangle has positive area, whichever solve gave it.
///
/// Nodes: the patch's vertices (local ids 0..n-1), then one centre per hole, in loop order.
/// Triangles: the patch's triangles first (same ids and corners as given), then each hole's fill
/// triangles (centre, loop edge), all counter-clockwise.
struct Chart {
  Positions2 uv;                                ///< per node
  std::vector<Triangle> triangles;              ///< patch triangles, then fill triangles
  Index patch_triangle_count = 0;               ///< triangles[0 .. count) are the patch's
  std::vector<std::array<Index, 3>> neighbour;  ///< across the edge opposite corner k; -1: border
  std::vector<Eigen::Matrix2d> inverse_edges;   ///< inverse of [uv_b - uv_a, uv_c - uv_a]
  /// CSR: patch triangles with corner v (patch vertices only), ascending.
  std::vector<Index> corner_start;
  std::vector<Index> corner_triangles;
  bool uniform_weights = false;  ///< mean-value weights gave a flat triangle; Tutte's were used
  bool iterative = false;        ///< positions from the iterative solve, not the sparse LU one
};

/// How disk_chart solves its embedding's linear system; the defaults are the elastic method's
/// (lib/elastic/README.md rule 2), tests vary them.
struct ChartSolver {
  /// Systems of at least this many rows (the nodes off the outer loop) are solved iteratively
  /// first: BiCGSTAB preconditioned by smoothed-aggregation multigrid
  /// (solve/smoothed_aggregation.h), from zero. Smaller systems, and those whose iterative
  /// solution does not converge or leaves a chart triangle without area, are solved by one sparse
  /// LU factorisation (COLAMD order).
  Index iterative_from = 1000;
  double tolerance = 1e-9;   ///< iterative: converged at |b - A x| <= tolerance |b| per column
  int max_iterations = 100;  ///< iterative: BiCGSTAB iterations at most (about 10 are taken)
};

/// Builds the chart of one patch (a disk with holes, consistently oriented).
/// \param points bind position of every patch vertex (#n); triangles index them.
/// \param loops boundary loops (local ids, in walking order); `outer_loop` indexes them.
/// \throw Error(Numeric) when even uniform weights leave a chart triangle without area.
/// \throw Error(Input) when the outer loop has zero length.
Chart disk_chart(const Positions3& points, const std::vector<Triangle>& triangles,
                 const std::vector<std::vector<Index>>& loops, Index outer_loop,
                 const ChartSolver& solver = {});

/// The z of the 2D cross product a x b: twice the signed area of the triangle (0, a, b), positive
/// when b lies counter-clockwise of a.
inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// A point of the chart on a patch triangle: barycentric weights, each in [0, 1], summing to 1.
struct ChartPoint {
  Index triangle = -1;
  std::array<double, 3> weight{1, 0, 0};
};

/// Signed barycentrics of `p` in chart triangle t (sum 1).
std::array<double, 3> chart_barycentric(const Chart& chart, Index t, const Vec2& p);

/// The patch triangle that holds `p`, found by walking from triangle `start` across the edge of
/// the most negative barycentric (fill triangles included), with the barycentrics clamped to
/// [0, 1] and renormalised. A point past the outer circle ends on the border triangle the walk
/// reached; a point that round-off leaves in a hole goes to the patch triangle across the loop
/// edge. Never fails: a walk that has not ended after every triangle's count of steps falls back
/// to the nearest patch triangle.
ChartPoint locate_in_chart(const Chart& chart, const Vec2& p, Index start);

}  // namespace skinslide
