#include "pipeline/slide_frame.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

#include <Eigen/Geometry>

#include "core/check.h"
#include "core/error.h"
#include "locate/locate.h"
#include "unwrap/bar_net.h"
#include "unwrap/force_density.h"

namespace skinslide {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// std of log(L / L_bind) over the bars; `points` indexed by local ids.
double edge_log_spread(const PatchNet& patch, const Positions3& points) {
  double sum = 0, sum2 = 0;
  size_t n = 0;
  for (size_t b = 0; b < patch.bars.size(); ++b) {
    const double l = (points[patch.bars[b][0]] - points[patch.bars[b][1]]).norm();
    if (!(l > 0) || !(patch.bind_lengths[b] > 0)) continue;
    const double r = std::log(l / patch.bind_lengths[b]);
    sum += r;
    sum2 += r * r;
    ++n;
  }
  if (n == 0) return 0;
  const double mean = sum / static_cast<double>(n);
  return std::sqrt(std::max(0.0, sum2 / static_cast<double>(n) - mean * mean));
}

// Appends local vertex v of `patch`, written at p, on patch triangle t at barycentrics w.
void append_slid(const PatchNet& patch, Index v, Index t, const std::array<double, 3>& w,
                 const Vec3& p, SlidVertices& moved) {
  const Index fan = patch.triangle_fan[t];
  moved.vertex.push_back(patch.vertices[v]);
  moved.sample.push_back(SurfaceSample{patch.triangle_face[t], {0, fan + 1, fan + 2}, w});
  moved.position.push_back(p);
}

// Slid triangles whose normal turns against the frame's own (frame triangles with area only).
int turned_triangles(const PatchNet& patch, const Positions3& frame, const Positions3& slid) {
  int turned = 0;
  for (const Triangle& t : patch.triangles) {
    const Vec3 nf = (frame[t[1]] - frame[t[0]]).cross(frame[t[2]] - frame[t[0]]);
    if (nf.isZero(0)) continue;
    const Vec3 ns = (slid[t[1]] - slid[t[0]]).cross(slid[t[2]] - slid[t[0]]);
    turned += ns.dot(nf) <= 0 ? 1 : 0;
  }
  return turned;
}

// The elastic method: relax in the chart, then each vertex of weight w < 1 goes back a fraction
// 1 - w of the way to its start in the chart, so that it stays on the frame's surface.
PatchFrameReport slide_patch_elastic(const BindSetup& setup, const PatchNet& patch,
                                     const Positions3& points, const FrameExtras& extras,
                                     SlidVertices& moved) {
  PatchFrameReport report;
  const ElasticSetup& elastic = *patch.elastic;
  auto t0 = std::chrono::steady_clock::now();
  ElasticResult relaxed = relax_patch(elastic, points, setup.options.elastic);
  report.solve_seconds = seconds_since(t0);
  report.energy_before = relaxed.energy_before;
  report.energy_after = relaxed.energy_after;
  report.iterations = relaxed.iterations;
  report.held = relaxed.held;
  report.stop = stop_name(relaxed.stop);
  t0 = std::chrono::steady_clock::now();
  const Chart& chart = elastic.chart;
  report.frame_net = patch.bind_net;
  Positions3 output = points;
  double total = 0;
  for (size_t i = 0; i < elastic.movable.size(); ++i) {
    const Index v = elastic.movable[i];
    const double w = setup.weight.empty() ? 1.0 : setup.weight[patch.vertices[v]];
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
    report.frame_net[v] = uv;
    output[v] = p;
    ++report.moved;
    ++report.located_in_image;
    append_slid(patch, v, where.triangle, where.weight, p, moved);
    const double d = (p - points[v]).norm();
    report.max_slide = std::max(report.max_slide, d);
    total += d;
  }
  report.mean_slide =
      elastic.movable.empty() ? 0.0 : total / static_cast<double>(elastic.movable.size());
  report.slid_flips = turned_triangles(patch, points, output);
  if (extras.edge_spread) {
    report.spread_frame = edge_log_spread(patch, points);
    report.spread_slid = edge_log_spread(patch, output);
  }
  // The elastic frame is looked up in the fixed chart: its ID image is the chart's.
  if (extras.id_image)
    report.id_image = id_raster(patch.bind_net, patch.triangles, setup.options.lookup_size);
  report.transfer_seconds = seconds_since(t0);
  return report;
}

PatchFrameReport slide_patch(const BindSetup& setup, const PatchNet& patch, const Positions3& frame,
                             const FrameExtras& extras, SlidVertices& moved) {
  PatchFrameReport report;
  if (patch.skipped) return report;
  const SlideOptions& opt = setup.options;
  Positions3 points(patch.vertices.size());
  for (size_t i = 0; i < points.size(); ++i) points[i] = frame[patch.vertices[i]];
  if (patch.elastic) return slide_patch_elastic(setup, patch, points, extras, moved);

  auto t0 = std::chrono::steady_clock::now();
  const std::vector<double> q =
      force_densities(bar_lengths(points, patch.bars), opt.density, opt.q_floor);
  FrameNetSolution net = patch.solver->solve(q, frame_net_options(opt));
  report.cg_iterations = net.iterations;
  report.cg_residual = net.residual;
  report.direct_solve = net.direct;
  report.frame_net = std::move(net.positions);
  const Folds folds = count_folds(report.frame_net, patch.triangles);
  report.frame_net_flips = folds.flipped;
  report.solve_seconds = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  IdImage image;
  if (opt.locate == Locate::Image || extras.id_image)
    image = id_raster(report.frame_net, patch.triangles, opt.lookup_size);
  Positions2 targets(patch.free_vertices.size());
  for (size_t k = 0; k < targets.size(); ++k) targets[k] = patch.bind_net[patch.free_vertices[k]];
  // Each target is the bind-net position of a free vertex: the walk starts at that vertex.
  const std::vector<Location> where =
      opt.locate == Locate::Image
          ? locate_points(targets, report.frame_net, patch.triangles, image)
          : locate_points_by_walk(targets, patch.free_vertices, report.frame_net, patch.triangles,
                                  patch.topology, folds.reversed);

  report.locate_seconds = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  // The slid patch as a whole is only needed for its edge-length spread.
  Positions3 output;
  if (extras.edge_spread) output = points;
  double total = 0;
  for (size_t k = 0; k < where.size(); ++k) {
    const Location& loc = where[k];
    const Triangle& tri = patch.triangles[loc.triangle];
    Vec3 p = Vec3::Zero();
    for (int c = 0; c < 3; ++c) p += loc.weight[c] * points[tri[c]];
    const Index v = patch.free_vertices[k];
    if (!p.allFinite())
      throw Error(ErrorKind::Numeric, "vertex " + std::to_string(patch.vertices[v]) +
                                          ": the slid position is not finite");
    // Weight 1 keeps the slid point's bits; weight 0 leaves the vertex out, so its line is the
    // frame's own.
    const double w = setup.weight.empty() ? 1.0 : setup.weight[patch.vertices[v]];
    if (w == 0) {
      (loc.fallback ? report.located_fallback : report.located_in_image) += 1;
      continue;
    }
    if (w != 1) p = points[v] + w * (p - points[v]);
    if (extras.edge_spread) output[v] = p;
    ++report.moved;
    append_slid(patch, v, loc.triangle, loc.weight, p, moved);
    const double d = (p - points[v]).norm();
    report.max_slide = std::max(report.max_slide, d);
    total += d;
    (loc.fallback ? report.located_fallback : report.located_in_image) += 1;
  }
  report.mean_slide = where.empty() ? 0.0 : total / static_cast<double>(where.size());
  if (extras.edge_spread) {
    report.spread_frame = edge_log_spread(patch, points);
    report.spread_slid = edge_log_spread(patch, output);
  }
  report.transfer_seconds = seconds_since(t0);
  if (extras.id_image) report.id_image = std::move(image);
  return report;
}

}  // namespace

FrameNetMethod frame_net_method(FrameSolver solver, std::ptrdiff_t free_nodes) {
  switch (solver) {
    case FrameSolver::Cholesky:
      return FrameNetMethod::Cholesky;
    case FrameSolver::Cg:
      return FrameNetMethod::Cg;
    case FrameSolver::Multigrid:
      return FrameNetMethod::Multigrid;
    case FrameSolver::Auto:
      break;
  }
  return free_nodes >= kMultigridFreeNodes ? FrameNetMethod::Multigrid : FrameNetMethod::Cholesky;
}

FrameNetOptions frame_net_options(const SlideOptions& options) {
  FrameNetOptions o;
  o.cg_tolerance = options.cg_tolerance;
  o.cg_max_iterations = options.cg_max_iterations;
  return o;
}

FrameResult slide_frame(const BindSetup& setup, const Positions3& frame,
                        const FrameExtras& extras) {
  if (static_cast<Index>(frame.size()) != setup.vertex_count)
    throw Error(ErrorKind::Input, "the frame has " + std::to_string(frame.size()) +
                                      " vertices; the bind has " +
                                      std::to_string(setup.vertex_count));
  FrameResult result;
  SlidVertices& slid = result.slid;
  size_t free_vertices = 0;
  for (const PatchNet& patch : setup.patches) free_vertices += patch.free_vertices.size();
  slid.vertex.reserve(free_vertices);
  slid.sample.reserve(free_vertices);
  slid.position.reserve(free_vertices);
  for (size_t p = 0; p < setup.patches.size(); ++p) {
    try {
      result.patches.push_back(slide_patch(setup, setup.patches[p], frame, extras, slid));
    } catch (const Error& e) {
      throw Error(e.kind(), "patch " + std::to_string(p) + ": " + e.what());
    }
  }
  // Each patch lists its vertices in ascending order: one patch, or patches that do not
  // interleave, need no reordering of the frame's largest lists.
  if (!std::is_sorted(slid.vertex.begin(), slid.vertex.end())) {
    std::vector<size_t> order(slid.vertex.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return slid.vertex[a] < slid.vertex[b]; });
    SlidVertices sorted;
    sorted.vertex.reserve(order.size());
    sorted.sample.reserve(order.size());
    sorted.position.reserve(order.size());
    for (size_t k : order) {
      sorted.vertex.push_back(slid.vertex[k]);
      sorted.sample.push_back(slid.sample[k]);
      sorted.position.push_back(slid.position[k]);
    }
    slid = std::move(sorted);
  }
  for (size_t k = 1; k < slid.vertex.size(); ++k)
    SKINSLIDE_CHECK(slid.vertex[k] != slid.vertex[k - 1], "a vertex slides in one patch only");
  return result;
}

}  // namespace skinslide
