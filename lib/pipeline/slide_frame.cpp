#include "pipeline/slide_frame.h"

#include <algorithm>
#include <numeric>

#include "core/check.h"
#include "core/error.h"
#include "locate/locate.h"
#include "unwrap/bar_net.h"
#include "unwrap/force_density.h"

namespace skinslide {
namespace {

struct Moved {
  Index vertex;
  SurfaceSample sample;
  Vec3 position;
};

PatchFrameReport slide_patch(const BindSetup& setup, const PatchNet& patch, const Positions3& frame,
                             bool keep_id_image, std::vector<Moved>& moved) {
  PatchFrameReport report;
  if (patch.skipped) return report;
  const SlideOptions& opt = setup.options;
  Positions3 points(patch.vertices.size());
  for (size_t i = 0; i < points.size(); ++i) points[i] = frame[patch.vertices[i]];

  const std::vector<double> q =
      force_densities(bar_lengths(points, patch.bars), opt.density, opt.q_floor);
  FrameNetSolution net = patch.solver->solve(q, frame_net_options(opt));
  report.cg_iterations = net.iterations;
  report.cg_residual = net.residual;
  report.direct_solve = net.direct;
  report.frame_net = std::move(net.positions);
  report.frame_net_flips = flipped_triangles(report.frame_net, patch.triangles);

  IdImage image;
  if (opt.locate == Locate::Image || keep_id_image)
    image = id_raster(report.frame_net, patch.triangles, opt.lookup_size);
  Positions2 targets(patch.free_vertices.size());
  for (size_t k = 0; k < targets.size(); ++k) targets[k] = patch.bind_net[patch.free_vertices[k]];
  // Each target is the bind-net position of a free vertex: the walk starts at that vertex.
  const std::vector<Location> where =
      opt.locate == Locate::Image
          ? locate_points(targets, report.frame_net, patch.triangles, image)
          : locate_points_by_walk(targets, patch.free_vertices, report.frame_net, patch.triangles,
                                  patch.topology, report.frame_net_flips > 0);

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
    const Index fan = patch.triangle_fan[loc.triangle];
    moved.push_back(
        {patch.vertices[v],
         SurfaceSample{patch.triangle_face[loc.triangle], {0, fan + 1, fan + 2}, loc.weight}, p});
    const double d = (p - points[v]).norm();
    report.max_slide = std::max(report.max_slide, d);
    total += d;
    (loc.fallback ? report.located_fallback : report.located_in_image) += 1;
  }
  report.mean_slide = where.empty() ? 0.0 : total / static_cast<double>(where.size());
  if (keep_id_image) report.id_image = std::move(image);
  return report;
}

}  // namespace

FrameNetOptions frame_net_options(const SlideOptions& options) {
  FrameNetOptions o;
  o.method =
      options.frame_solver == FrameSolver::Cg ? FrameNetMethod::Cg : FrameNetMethod::Cholesky;
  o.cg_tolerance = options.cg_tolerance;
  o.cg_max_iterations = options.cg_max_iterations;
  return o;
}

FrameResult slide_frame(const BindSetup& setup, const Positions3& frame, bool keep_id_image) {
  if (static_cast<Index>(frame.size()) != setup.vertex_count)
    throw Error(ErrorKind::Input, "the frame has " + std::to_string(frame.size()) +
                                      " vertices; the bind has " +
                                      std::to_string(setup.vertex_count));
  FrameResult result;
  std::vector<Moved> moved;
  for (size_t p = 0; p < setup.patches.size(); ++p) {
    try {
      result.patches.push_back(slide_patch(setup, setup.patches[p], frame, keep_id_image, moved));
    } catch (const Error& e) {
      throw Error(e.kind(), "patch " + std::to_string(p) + ": " + e.what());
    }
  }
  std::sort(moved.begin(), moved.end(),
            [](const Moved& a, const Moved& b) { return a.vertex < b.vertex; });
  for (size_t k = 1; k < moved.size(); ++k)
    SKINSLIDE_CHECK(moved[k].vertex != moved[k - 1].vertex, "a vertex slides in one patch only");
  result.slid.vertex.reserve(moved.size());
  result.slid.sample.reserve(moved.size());
  result.slid.position.reserve(moved.size());
  for (const Moved& m : moved) {
    result.slid.vertex.push_back(m.vertex);
    result.slid.sample.push_back(m.sample);
    result.slid.position.push_back(m.position);
  }
  return result;
}

}  // namespace skinslide
