#include "elastic/elastic_slide.h"

#include <algorithm>

#include <Eigen/Geometry>

#include "core/error.h"
#include "core/stopwatch.h"
#include "mesh/measures.h"

namespace skinslide {
namespace {

// Slid triangles whose normal turns against the frame's own (frame triangles with area only).
int turned_triangles(const Patch& patch, const Positions3& frame, const Positions3& slid) {
  int turned = 0;
  for (const Triangle& t : patch.triangles) {
    const Vec3 nf = (frame[t[1]] - frame[t[0]]).cross(frame[t[2]] - frame[t[0]]);
    const Vec3 ns = (slid[t[1]] - slid[t[0]]).cross(slid[t[2]] - slid[t[0]]);
    turned += turned_against(ns, nf) ? 1 : 0;
  }
  return turned;
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
  ElasticSlide result;
  ElasticReport& report = result.report;
  PatchSlide& slid = result.slid;
  auto t0 = Clock::now();
  const ElasticResult relaxed = relax_patch(setup, points, options);
  slid.solve_seconds = seconds_since(t0);
  report.energy_before = relaxed.energy_before;
  report.energy_after = relaxed.energy_after;
  report.iterations = relaxed.iterations;
  report.solves = relaxed.solves;
  report.solve_iterations = relaxed.solver_iterations;
  report.escalations = relaxed.escalations;
  report.held = relaxed.held;
  report.gain_left = relaxed.gain_left;
  report.stop = stop_name(relaxed.stop);
  const Chart& chart = setup.chart;
  slid.net = patch.bind_net;
  slid.frame_in_bind_net = true;
  slid.placed = static_cast<Index>(setup.movable.size());
  Positions3 output = points;
  for (size_t i = 0; i < setup.movable.size(); ++i) {
    const Index v = setup.movable[i];
    const double w = weight.empty() ? 1.0 : weight[patch.vertices[v]];
    ChartPoint where = relaxed.where[i];
    Vec2 uv = relaxed.uv[i];
    Vec3 p = relaxed.position[i];
    if (w != 1) {
      uv = chart.uv[v] + w * (uv - chart.uv[v]);
      where = locate_in_chart(chart, uv, where.triangle);
      const Triangle& tri = chart.triangles[where.triangle];
      p = where.weight[0] * points[tri[0]] + where.weight[1] * points[tri[1]] +
          where.weight[2] * points[tri[2]];
    }
    if (!p.allFinite())
      throw Error(ErrorKind::Numeric, "vertex " + std::to_string(patch.vertices[v]) +
                                          ": the slid position is not finite");
    slid.net[v] = uv;
    output[v] = p;
    slid.vertex.push_back(v);
    slid.triangle.push_back(where.triangle);
    slid.weight.push_back(where.weight);
    slid.position.push_back(p);
  }
  report.slid_flips = turned_triangles(patch, points, output);
  // The elastic frame is looked up in the fixed chart: its ID image is the chart's.
  if (id_image_size > 0) slid.id_image = id_raster(patch.bind_net, patch.triangles, id_image_size);
  return result;
}

}  // namespace skinslide
