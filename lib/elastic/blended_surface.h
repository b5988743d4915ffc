// The frame's surface as the slide sees it (lib/elastic/README.md rule 5): the frame's facets
// blended into one another near the chart's edges and nodes, so that the surface is smooth (C1)
// over the chart. On the facets themselves a point's slope jumps where it crosses a chart edge;
// the energy's minimum then sticks to edges and slips off them from one frame to the next, and
// the slide jitters in slow motion. Over the blended surface the minimum moves as smoothly as the
// frame does. Only the relaxation uses it, with --blend above 0: every slid vertex is written at
// its chart point on the frame's own facets (surface_map.h), so it stays on the frame's surface.
//
// Phi_b(u) = sum_f phi_f(u) P_f(u) / sum_f phi_f(u) over the patch triangles f around u, with P_f
// facet f's plane extended beyond its triangle (the barycentric combination of its frame corners,
// signed barycentrics) and phi_f = the product over f's three edges of a smoothstep ramp of u's
// signed distance to that edge's line, from 0 at -w to 1 at +w (w the edge's blend half-width;
// the patch's border and its holes' edges are not blended). Neighbouring planes agree on their
// shared edge and every plane through a node passes through it, so Phi_b interpolates the frame
// at every node; the sum runs over every triangle whose weight can be non-zero on the point's
// triangle (a needle's reaches past its tip), so it is one C1 function from either side of an
// edge. Two band lines that meet at a sharp corner (a needle's tip, a cap's base) meet far beyond
// it, past other nodes: there phi_f also fades with the distance from f, to 0 before the nearest
// node that is not f's corner, so the surface still passes through every node. Next to slivers
// the bands narrow (kSliverFanShare in the .cpp), so that the slide written on the facets keeps
// what the relaxation gained: tests/bench/elastic.md "Slivers under the blend".
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "core/types.h"
#include "elastic/arap.h"
#include "elastic/chart.h"

namespace skinslide {

struct FrameSurface;

/// One patch triangle's edges in the chart, edge k opposite corner k: the inward unit normal of
/// its line and its offset (u's signed distance from the line is normal . u - offset, positive
/// inside), and its blend half-width (0: the patch's border or a hole's, not blended).
struct BlendEdges {
  std::array<Vec2, 3> normal;
  std::array<double, 3> offset;
  std::array<double, 3> width;
  /// How far from the triangle its weight reaches: it fades from 1 at distance reach / 2 to 0 at
  /// `reach`, the distance of the nearest node the bands would reach that is not its corner
  /// (infinite: no such node, no fade).
  double reach = INFINITY;
};

/// Bind-time data of the blend over one chart: plain data, read-only afterwards.
struct SurfaceBlend {
  std::vector<BlendEdges> edges;  ///< per patch triangle
  /// CSR per patch triangle t: the patch triangles whose weight may be non-zero on t, t first.
  std::vector<Index> around_start;
  std::vector<Index> around;
  /// Per patch triangle the box (lo x, lo y, hi x, hi y) of where its weight is not zero.
  std::vector<std::array<double, 4>> support;
};

/// \param width_share each edge's blend half-width over the smaller inradius (in the chart) of
/// the two triangles that share it (--blend; > 0), and at most 3x that share of the smallest
/// inradius around either of its ends (next to a sliver: kSliverFanShare). At 1 and above no
/// point of a triangle lies beyond every band: the surface has no flat part left.
SurfaceBlend surface_blend(const Chart& chart, double width_share);

/// Phi_b at chart point u, which lies on (or by round-off beside) patch triangle t; its Jacobian
/// dPhi_b/du (3x2) in `jacobian` when not null. `surface` must have a blend (and its facets'
/// planes: frame_surface).
Vec3 blended_point(const FrameSurface& surface, Index t, const Vec2& u, Mat32* jacobian = nullptr);

}  // namespace skinslide
