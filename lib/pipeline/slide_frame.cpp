#include "pipeline/slide_frame.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/check.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "elastic/window_mean.h"
#include "mesh/measures.h"

namespace skinslide {
namespace {

// std of log(L / L_bind) over the bars; `points` indexed by local ids.
double edge_log_spread(const Patch& patch, const Positions3& points) {
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

// True when every vertex of `patch` is at its bind position to float32 precision: a frame that
// went through a float32 file (a PC2 sample, a glTF) from the bind pose.
bool at_rest(const Patch& patch, std::span<const Vec3> frame, const Positions3& bind) {
  if (bind.empty()) return false;
  for (const Index v : patch.vertices)
    for (int c = 0; c < 3; ++c)
      if (static_cast<float>(frame[v][c]) != static_cast<float>(bind[v][c])) return false;
  return true;
}

// The frame's positions of patch p's vertices (local ids), checked computable.
Positions3 patch_points(const Patch& patch, std::span<const Vec3> frame) {
  Positions3 points(patch.vertices.size());
  for (size_t i = 0; i < points.size(); ++i) points[i] = frame[patch.vertices[i]];
  require_computable_span(points, patch.vertices);
  return points;
}

// Patch p written at the window's mean (rule 12), from its own relaxation.
MethodSlide windowed_patch(const BindSetup& setup, std::size_t p, const Patch& patch,
                           const Positions3& points, const WindowedFrame& window,
                           int id_image_size) {
  if (patch.skipped) return MethodSlide{PatchSlide{}, ElasticReport{}};
  const ElasticSetup& elastic = *std::get<ElasticMethod>(setup.method).patches[p];
  const ElasticResult written =
      window_mean(elastic, points, window.own->patches[p], window.mean[p]);
  ElasticSlide slide =
      elastic_written(elastic, patch, points, setup.weight, written, id_image_size);
  slide.slid.solve_seconds = window.own->seconds[p];
  // The energy of the frame's own relaxation, in whose place the mean is written: the frame's
  // line compares the two.
  slide.report.energy_own = window.own->patches[p].energy_after;
  return {std::move(slide.slid), std::move(slide.report)};
}

// Slides patch p by the method (or writes the window's mean), then gathers what it wrote (mesh
// ids, surface samples) and the slide figures both methods share.
PatchFrameReport slide_and_gather(const BindSetup& setup, std::size_t p,
                                  std::span<const Vec3> frame, const FrameExtras& extras,
                                  const WindowedFrame* window, SlidVertices& moved) {
  const Patch& patch = setup.patches[p];
  const Positions3 points = patch_points(patch, frame);
  MethodSlide slide =
      window ? windowed_patch(setup, p, patch, points, *window, extras.id_image_size)
             : slide_patch(setup.method, p, patch, points, setup.weight, extras.id_image_size);
  PatchFrameReport report;
  report.method = std::move(slide.report);
  PatchSlide& slid = slide.slid;
  // The method relaxes what float32 rounding left of the bind's energy; that slide is rounding
  // noise, and the bind comes back unchanged.
  report.at_rest = !patch.skipped && at_rest(patch, frame, setup.bind_positions);
  if (report.at_rest) {
    slid.vertex.clear();
    slid.placed = 0;
    mark_at_rest(report.method);
  }
  report.solve_seconds = slid.solve_seconds;
  report.locate_seconds = slid.locate_seconds;
  const auto t0 = Clock::now();
  // The slid patch as a whole is only needed for its edge-length spread.
  Positions3 output;
  if (extras.edge_spread) output = points;
  double total = 0;
  for (size_t k = 0; k < slid.vertex.size(); ++k) {
    const Index v = slid.vertex[k], t = slid.triangle[k];
    const Vec3& position = slid.position[k];
    if (extras.edge_spread) output[v] = position;
    ++report.moved;
    const Index fan = patch.triangle_fan[t];
    moved.vertex.push_back(patch.vertices[v]);
    moved.sample.push_back(
        SurfaceSample{patch.triangle_face[t], {0, fan + 1, fan + 2}, slid.weight[k]});
    moved.position.push_back(position);
    const double d = (position - points[v]).norm();
    report.max_slide = std::max(report.max_slide, d);
    total += d;
  }
  report.mean_slide = slid.placed == 0 ? 0.0 : total / static_cast<double>(slid.placed);
  if (extras.edge_spread) {
    report.spread_frame = edge_log_spread(patch, points);
    report.spread_slid = edge_log_spread(patch, output);
  }
  report.frame_net = std::move(slid.net);
  report.frame_in_bind_net = slid.frame_in_bind_net;
  report.id_image = std::move(slid.id_image);
  report.transfer_seconds = seconds_since(t0);
  return report;
}

}  // namespace

Figures frame_figures(const PatchFrameReport& report) {
  Figures figures = report_figures(report.method);
  figures.push_back({"at_rest", report.at_rest});
  figures.push_back({"moved", static_cast<long long>(report.moved)});
  figures.push_back({"max_slide", report.max_slide});
  figures.push_back({"mean_slide", report.mean_slide});
  figures.push_back({"spread_frame", report.spread_frame});
  figures.push_back({"spread_slid", report.spread_slid});
  return figures;
}

namespace {

// A frame with another vertex count than the bind's is refused.
void require_bind_count(const BindSetup& setup, std::span<const Vec3> frame) {
  if (static_cast<Index>(frame.size()) != setup.vertex_count)
    throw Error(ErrorKind::Input, "the frame has " + std::to_string(frame.size()) +
                                      " vertices; the bind has " +
                                      std::to_string(setup.vertex_count));
}

}  // namespace

FrameRelaxations relax_frame(const BindSetup& setup, std::span<const Vec3> frame) {
  require_bind_count(setup, frame);
  const ElasticMethod& method = std::get<ElasticMethod>(setup.method);
  FrameRelaxations out;
  out.patches.resize(setup.patches.size());
  out.seconds.assign(setup.patches.size(), 0.0);
  for (size_t p = 0; p < setup.patches.size(); ++p) {
    const Patch& patch = setup.patches[p];
    if (patch.skipped) continue;
    labelled("patch " + std::to_string(p), [&] {
      const Positions3 points = patch_points(patch, frame);
      const ElasticSetup& elastic = *method.patches[p];
      const auto t0 = Clock::now();
      ElasticResult& r = out.patches[p] = relax_patch(elastic, points, method.options);
      out.seconds[p] = seconds_since(t0);
      // A frame at rest is written unchanged (slide_and_gather): its slide is none.
      if (at_rest(patch, frame, setup.bind_positions)) put_at_start(elastic, points, r);
    });
  }
  return out;
}

FrameResult slide_frame(const BindSetup& setup, std::span<const Vec3> frame,
                        const FrameExtras& extras, const WindowedFrame* window) {
  require_bind_count(setup, frame);
  FrameResult result;
  SlidVertices& slid = result.slid;
  size_t free_vertices = 0;
  for (const Patch& patch : setup.patches) free_vertices += patch.free_vertices.size();
  slid.vertex.reserve(free_vertices);
  slid.sample.reserve(free_vertices);
  slid.position.reserve(free_vertices);
  for (size_t p = 0; p < setup.patches.size(); ++p) {
    result.patches.push_back(labelled("patch " + std::to_string(p), [&] {
      return slide_and_gather(setup, p, frame, extras, window, slid);
    }));
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
