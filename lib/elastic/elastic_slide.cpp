#include "elastic/elastic_slide.h"

#include <algorithm>

#include "core/error.h"
#include "core/stopwatch.h"
#include "elastic/line_search.h"
#include "elastic/surface_map.h"
#include "mesh/measures.h"

namespace skinslide {
namespace {

// Rule 11's weights move a vertex part of its way in the chart, and a triangle between a vertex
// that goes all of its way and one that goes part can fold (orientation is not convex in the
// corners): the moving corners of a slid triangle folded in the chart, or turned against its frame
// triangle, go back to the frame, until none is (at the frame nothing is). Returns how many.
int hold_weighted_folds(const ElasticSetup& setup, const Patch& patch, const Positions3& frame,
                        std::vector<ChartPoint>& where, Positions2& uv, Positions3& output) {
  const Chart& chart = setup.chart;
  int held = 0;
  for (bool any = true; any;) {
    any = false;
    for (const Triangle& t : patch.triangles) {
      if (!slid_triangle_folds(chart, setup.movable_slot, uv, frame, output, t)) continue;
      for (Index v : t)
        if (const Index i = setup.movable_slot[v]; i >= 0 && output[v] != frame[v]) {
          uv[i] = chart.uv[v];
          where[i] = at_node(chart, v);
          output[v] = frame[v];
          ++held;
          any = true;
        }
    }
  }
  return held;
}

}  // namespace

std::shared_ptr<const ElasticSetup> elastic_patch_setup(Patch& patch, const Positions3& points,
                                                        const std::vector<double>& weight,
                                                        double blend) {
  std::vector<Index> movable;
  for (Index v : patch.free_vertices)
    if (weight.empty() || weight[patch.vertices[v]] > 0) movable.push_back(v);
  auto setup = std::make_shared<const ElasticSetup>(
      elastic_setup(points, patch.triangles, patch.loops, patch.outer_loop, movable, blend));
  patch.bind_net.assign(
      setup->chart.uv.begin(),
      setup->chart.uv.begin() + static_cast<std::ptrdiff_t>(patch.vertices.size()));
  patch.bind_net_flips = flipped_triangles(patch.bind_net, patch.triangles);
  return setup;
}

ElasticSlide elastic_slide(const ElasticSetup& setup, const Patch& patch, const Positions3& points,
                           const std::vector<double>& weight, const ElasticOptions& options,
                           int id_image_size) {
  const auto t0 = Clock::now();
  const ElasticResult relaxed = relax_patch(setup, points, options);
  const double solve_seconds = seconds_since(t0);
  ElasticSlide result = elastic_written(setup, patch, points, weight, relaxed, id_image_size);
  result.slid.solve_seconds = solve_seconds;
  return result;
}

ElasticSlide elastic_written(const ElasticSetup& setup, const Patch& patch,
                             const Positions3& points, const std::vector<double>& weight,
                             const ElasticResult& relaxed, int id_image_size) {
  ElasticSlide result;
  ElasticReport& report = result.report;
  PatchSlide& slid = result.slid;
  report.energy_before = relaxed.energy_before;
  report.energy_after = relaxed.energy_after;
  report.iterations = relaxed.iterations;
  report.solves = relaxed.solves;
  report.solve_iterations = relaxed.solver_iterations;
  report.escalations = relaxed.escalations;
  report.held = relaxed.held;
  report.gain_left = relaxed.gain_left;
  report.window_returned = relaxed.window_returned;
  report.energy_own = relaxed.energy_after;
  report.stop = stop_name(relaxed.stop);
  const Chart& chart = setup.chart;
  slid.net = patch.bind_net;
  slid.frame_in_bind_net = true;
  slid.placed = static_cast<Index>(setup.movable.size());
  Positions3 output = points;
  const size_t m = setup.movable.size();
  std::vector<ChartPoint> where = relaxed.where;
  Positions2 uv = relaxed.uv;
  for (size_t i = 0; i < m; ++i) {
    const Index v = setup.movable[i];
    const double w = weight.empty() ? 1.0 : weight[patch.vertices[v]];
    Vec3 p = relaxed.position[i];
    if (w != 1) {
      uv[i] = chart.uv[v] + w * (uv[i] - chart.uv[v]);
      where[i] = locate_in_chart(chart, uv[i], where[i].triangle);
      p = facet_point(chart, points, where[i]);
    }
    if (!p.allFinite())
      throw Error(ErrorKind::Numeric, "vertex " + std::to_string(patch.vertices[v]) +
                                          ": the slid position is not finite");
    output[v] = p;
  }
  if (!weight.empty()) report.held += hold_weighted_folds(setup, patch, points, where, uv, output);
  for (size_t i = 0; i < m; ++i) {
    const Index v = setup.movable[i];
    slid.net[v] = uv[i];
    slid.vertex.push_back(v);
    slid.triangle.push_back(where[i].triangle);
    slid.weight.push_back(where[i].weight);
    slid.position.push_back(output[v]);
  }
  report.slid_flips = turned_triangles(patch.triangles, points, output);
  // The elastic frame is looked up in the fixed chart: its ID image is the chart's.
  if (id_image_size > 0) slid.id_image = id_raster(patch.bind_net, patch.triangles, id_image_size);
  return result;
}

}  // namespace skinslide
