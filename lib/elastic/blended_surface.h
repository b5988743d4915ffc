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

#include "core/types.h"
#include "elastic/arap.h"
#include "elastic/chart.h"
#include "elastic/surface_blend.h"
#include "elastic/surface_map.h"

namespace skinslide {

/// \param width_share each edge's blend half-width over the smaller inradius (in the chart) of
/// the two triangles that share it (--blend; > 0), and at most 3x that share of the smallest
/// inradius around either of its ends (next to a sliver: kSliverFanShare). At 1 and above no
/// point of a triangle lies beyond every band: the surface has no flat part left.
SurfaceBlend surface_blend(const Chart& chart, double width_share);

/// Phi_b at chart point u, which lies on (or by round-off beside) patch triangle t; its Jacobian
/// dPhi_b/du (3x2) in `jacobian` when not null. `surface` must have a blend (and its facets'
/// planes: frame_surface).
Vec3 blended_point(const FrameSurface& surface, Index t, const Vec2& u, Mat32* jacobian = nullptr);

/// Where the relaxation sees a point at chart point u (on `where`): on the blended surface, or on
/// Phi without a blend.
Vec3 relaxed_point(const FrameSurface& surface, const ChartPoint& where, const Vec2& u);

}  // namespace skinslide
