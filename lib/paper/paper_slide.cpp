#include "paper/paper_slide.h"

#include <algorithm>
#include <future>
#include <utility>

#include "core/check.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "paper/square_boundary.h"

namespace skinslide {
namespace {

Positions3 gather(const Positions3& positions, const std::vector<Index>& ids) {
  Positions3 out(ids.size());
  for (size_t i = 0; i < ids.size(); ++i) out[i] = positions[ids[i]];
  return out;
}

Index bar_index(const std::vector<std::array<Index, 2>>& bars, Index a, Index b) {
  const std::array<Index, 2> key{std::min(a, b), std::max(a, b)};
  const auto it = std::lower_bound(bars.begin(), bars.end(), key);
  SKINSLIDE_CHECK(it != bars.end() && *it == key, "a loop edge is a bar");
  return static_cast<Index>(it - bars.begin());
}

std::string corners_text(const std::array<Index, 4>& c) {
  return "--corners " + std::to_string(c[0]) + "," + std::to_string(c[1]) + "," +
         std::to_string(c[2]) + "," + std::to_string(c[3]);
}

// The outer loop on the square: at the chosen corners (checked to be in the loop's walking
// order), else at the automatic ones.
SquareBoundary square(const Patch& patch, const Positions3& points, const CornerChoice& choice) {
  const auto& outer = patch.loops[patch.outer_loop];
  if (!choice.chosen) return square_positions(gather(points, outer));
  std::array<Index, 4> at{};
  for (int j = 0; j < 4; ++j) {
    const auto local =
        std::lower_bound(patch.vertices.begin(), patch.vertices.end(), choice.corners[j]) -
        patch.vertices.begin();
    at[j] = static_cast<Index>(std::find(outer.begin(), outer.end(), local) - outer.begin());
  }
  std::array<Index, 4> walk{};  // the corners as the loop meets them, from the first one named
  const Index n = static_cast<Index>(outer.size());
  std::vector<std::pair<Index, Index>> by_offset;
  for (int j = 0; j < 4; ++j) by_offset.push_back({(at[j] - at[0] + n) % n, choice.corners[j]});
  std::sort(by_offset.begin(), by_offset.end());
  for (int j = 0; j < 4; ++j) walk[j] = by_offset[j].second;
  if (walk != choice.corners)
    throw Error(ErrorKind::Usage, choice.source +
                                      ": the corners are not in the loop's walking order; "
                                      "walking from " +
                                      std::to_string(choice.corners[0]) +
                                      " the loop meets them as " + corners_text(walk).substr(10));
  return square_positions(gather(points, outer), at);
}

// The bind net: the outer loop on the square, everything else in equilibrium. With Holes::Fill
// each hole gets a virtual free node joined to its loop vertices, with the loop's mean q, so the
// hole keeps its size instead of collapsing towards the free loop. Solved as the frames will be:
// by multigrid, or by Cholesky, whose ordering then serves the frames too.
Positions2 bind_net(const Patch& patch, const std::vector<double>& q, const Positions2& outer_2d,
                    const PaperOptions& options, FrameNetMethod method,
                    std::vector<Index>& node_order) {
  const Index n = static_cast<Index>(patch.vertices.size());
  BarNet net;
  net.node_count = n;
  net.bars = patch.bars;
  std::vector<double> q_all = q;
  if (options.holes == Holes::Fill) {
    for (size_t l = 0; l < patch.loops.size(); ++l) {
      if (static_cast<Index>(l) == patch.outer_loop) continue;
      const auto& loop = patch.loops[l];
      double q_mean = 0;
      for (size_t k = 0; k < loop.size(); ++k)
        q_mean += q[bar_index(patch.bars, loop[k], loop[(k + 1) % loop.size()])];
      q_mean /= static_cast<double>(loop.size());
      const Index centre = net.node_count++;
      for (Index v : loop) {
        net.bars.push_back({v, centre});
        q_all.push_back(q_mean);
      }
    }
  }
  net.fixed.assign(net.node_count, 0);
  Positions2 start(net.node_count, Vec2::Zero());
  const auto& outer = patch.loops[patch.outer_loop];
  for (size_t k = 0; k < outer.size(); ++k) {
    net.fixed[outer[k]] = 1;
    start[outer[k]] = outer_2d[k];
  }
  Positions2 solved = method == FrameNetMethod::Multigrid
                          ? solve_bar_net_multigrid(net, q_all, start, options.cg_tolerance,
                                                    options.cg_max_iterations)
                          : solve_bar_net(net, q_all, start, &node_order);
  solved.resize(n);
  return solved;
}

// The frame nets: the patch's bars, every loop vertex and pin fixed at its bind-net position.
BarNet frame_net(const Patch& patch) {
  BarNet frame;
  frame.node_count = static_cast<Index>(patch.vertices.size());
  frame.bars = patch.bars;
  frame.fixed.assign(patch.vertices.size(), 1);
  for (Index v : patch.free_vertices) frame.fixed[v] = 0;
  return frame;
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

FrameNetOptions frame_net_options(const PaperOptions& options) {
  FrameNetOptions o;
  o.cg_tolerance = options.cg_tolerance;
  o.cg_max_iterations = options.cg_max_iterations;
  return o;
}

PaperSetup paper_setup(Patch& patch, const Positions3& points, const PaperOptions& options,
                       const CornerChoice& corners, bool spare_thread) {
  PaperSetup setup;
  // The frame nets' triangle neighbours, for the walks that locate points in them.
  setup.topology = triangle_topology(patch.triangles, static_cast<Index>(patch.vertices.size()));
  const SquareBoundary outer_2d = square(patch, points, corners);
  setup.corners_chosen = corners.chosen;
  const auto& outer = patch.loops[patch.outer_loop];
  for (int j = 0; j < 4; ++j) setup.corners[j] = outer[outer_2d.corners[j]];
  const std::vector<double> q =
      force_densities(patch.bind_lengths, options.density, options.q_floor);
  const FrameNetMethod method = frame_net_method(
      options.frame_solver, static_cast<std::ptrdiff_t>(patch.free_vertices.size()));
  BarNet frame = frame_net(patch);
  // The frame nets' solver depends on their bars and fixed nodes, not on the bind net it starts
  // from: with a spare thread, a multigrid one (its free system, slots and levels) is built
  // while the bind net is solved, then warm-started at it (tests/bench/README.md "Performance").
  // The same solver either way.
  std::future<FrameNetSolver> prepared;
  if (spare_thread && method == FrameNetMethod::Multigrid)
    prepared = std::async(std::launch::async, [&frame] {
      const Index nodes = frame.node_count;
      return FrameNetSolver(std::move(frame), Positions2(nodes, Vec2::Zero()),
                            FrameNetMethod::Multigrid);
    });
  // The frame nets' free nodes are among the bind net's: its fill-reducing order serves them too.
  std::vector<Index> node_order;
  patch.bind_net = bind_net(patch, q, outer_2d.positions, options, method, node_order);
  patch.bind_net_flips = flipped_triangles(patch.bind_net, patch.triangles);
  setup.solver = std::make_shared<const FrameNetSolver>(
      prepared.valid() ? prepared.get().starting_at(patch.bind_net)
                       : FrameNetSolver(std::move(frame), patch.bind_net, method, node_order));
  return setup;
}

PaperSlide paper_slide(const PaperSetup& setup, const Patch& patch, const Positions3& points,
                       const std::vector<double>& weight, const PaperOptions& options,
                       int id_image_size) {
  PaperSlide result;
  PaperReport& report = result.report;
  PatchSlide& slid = result.slid;
  auto t0 = Clock::now();
  const std::vector<double> q =
      force_densities(bar_lengths(points, patch.bars), options.density, options.q_floor);
  FrameNetSolution net = setup.solver->solve(q, frame_net_options(options));
  report.cg_iterations = net.iterations;
  report.cg_residual = net.residual;
  report.direct_solve = net.direct;
  slid.net = std::move(net.positions);
  const Folds folds = count_folds(slid.net, patch.triangles);
  report.frame_net_flips = folds.flipped;
  slid.solve_seconds = seconds_since(t0);

  t0 = Clock::now();
  const bool by_image = options.locate == Locate::Image;
  IdImage image;
  if (by_image) image = id_raster(slid.net, patch.triangles, options.lookup_size);
  Positions2 targets(patch.free_vertices.size());
  for (size_t k = 0; k < targets.size(); ++k) targets[k] = patch.bind_net[patch.free_vertices[k]];
  // Each target is the bind-net position of a free vertex: the walk starts at that vertex.
  const std::vector<Location> where =
      by_image ? locate_points(targets, slid.net, patch.triangles, image)
               : locate_points_by_walk(targets, patch.free_vertices, slid.net, patch.triangles,
                                       setup.topology, folds.reversed);
  slid.locate_seconds = seconds_since(t0);
  if (id_image_size > 0)
    slid.id_image = by_image && id_image_size == options.lookup_size
                        ? std::move(image)
                        : id_raster(slid.net, patch.triangles, id_image_size);

  slid.placed = static_cast<Index>(where.size());
  Positions3 output = points;
  for (size_t k = 0; k < where.size(); ++k) {
    const Location& loc = where[k];
    (loc.fallback ? report.located_fallback : report.located_in_image) += 1;
    const Triangle& tri = patch.triangles[loc.triangle];
    Vec3 p = Vec3::Zero();
    for (int c = 0; c < 3; ++c) p += loc.weight[c] * points[tri[c]];
    const Index v = patch.free_vertices[k];
    if (!p.allFinite())
      throw Error(ErrorKind::Numeric, "vertex " + std::to_string(patch.vertices[v]) +
                                          ": the slid position is not finite");
    // Weight 1 keeps the slid point's bits; weight 0 leaves the vertex out, so its line is the
    // frame's own.
    const double w = weight.empty() ? 1.0 : weight[patch.vertices[v]];
    if (w == 0) continue;
    if (w != 1) p = points[v] + w * (p - points[v]);
    slid.vertex.push_back(v);
    slid.triangle.push_back(loc.triangle);
    slid.weight.push_back(loc.weight);
    slid.position.push_back(p);
    output[v] = p;
  }
  // The paper's nets may fold where the frame's bars fold; never in silence.
  report.slid_flips = turned_triangles(patch.triangles, points, output);
  return result;
}

}  // namespace skinslide
