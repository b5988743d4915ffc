// The frame's surface over the patch's chart: Phi(u), the barycentric combination of the frame
// positions of the chart triangle holding u (lib/elastic/README.md rule 5), and its Jacobians,
// which turn a vertex's chart step into 3D motion (rule 7). Phi is piecewise linear: at a chart
// edge or node its slope depends on the direction a point leaves in. With --blend the relaxation
// moves on the facets blended smooth instead (blended_surface.h); the slid vertices are written
// on Phi either way.
#pragma once

#include <vector>

#include "core/types.h"
#include "elastic/arap.h"
#include "elastic/chart.h"
#include "elastic/surface_blend.h"

namespace skinslide {

/// One frame over one chart: per patch triangle the frame's normal (not normalised: twice the
/// area). Built once per frame; read-only afterwards.
struct FrameSurface {
  const Chart& chart;
  const Positions3& frame;    ///< the frame's positions of the patch's vertices (local ids)
  std::vector<Vec3> normals;  ///< per patch triangle
  double area = 0;            ///< the frame's patch area
  /// The surface the relaxation moves on: the chart's blend (bind time), or null: the facets.
  const SurfaceBlend* blend = nullptr;
  /// With a blend, per patch triangle the slope of its plane over the chart: the plane is
  /// frame[corner 0] + facet_jacobian (u - uv[corner 0]). (An origin at u = 0 would lose the
  /// plane's digits at the nodes: a sliver's slope is huge.)
  std::vector<Mat32> facet_jacobian;
};

FrameSurface frame_surface(const Chart& chart, const Positions3& frame,
                           const SurfaceBlend* blend = nullptr);

/// dPhi/du (3x2) over patch triangle t, computed when asked (a few operations) rather than
/// stored: a frame in flight holds less.
Mat32 surface_jacobian(const FrameSurface& surface, Index t);

/// Phi at a chart point: on its frame triangle.
Vec3 surface_point(const FrameSurface& surface, const ChartPoint& p);

/// The same point from the chart and the frame's positions alone (local ids), without a
/// FrameSurface: where a slid vertex is written.
Vec3 facet_point(const Chart& chart, const Positions3& frame, const ChartPoint& p);

/// A point exactly at its chart node v: on a patch triangle around it.
ChartPoint at_node(const Chart& chart, Index v);

/// At a chart node Phi has no Jacobian: the least-squares linear map from the node's chart
/// one-ring to its frame one-ring, projected on the frame's tangent plane there (the
/// area-weighted normal; edges weighted 1 / |chart edge|^2). A model: the line search measures
/// the true energy.
Mat32 node_jacobian(const FrameSurface& surface, Index v);

/// The patch triangle a point enters when it leaves `u` (on triangle t; at node `node`, or -1)
/// along `d`: at a node the incident triangle whose wedge holds d; on an edge the triangle across
/// it when d points out; else its own.
Index entered_triangle(const Chart& chart, Index node, const Vec2& u, Index t, const Vec2& d);

/// A step `d` modelled at node v with the node's Jacobian T: the chart step that moves the point
/// as the model meant, in the wedge that holds that step (the wedge's own Jacobian inverted on
/// the model's 3D motion T d); `d` itself when no wedge takes it.
Vec2 redirected_from_node(const FrameSurface& surface, Index v, const Mat32& T, const Vec2& d);

}  // namespace skinslide
