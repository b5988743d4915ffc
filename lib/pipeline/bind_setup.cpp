#include "pipeline/bind_setup.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "core/error.h"
#include "unwrap/bar_net.h"
#include "unwrap/force_density.h"
#include "unwrap/square_boundary.h"

namespace skinslide {
namespace {

Positions3 gather(const Positions3& positions, const std::vector<Index>& ids) {
  Positions3 out(ids.size());
  for (size_t i = 0; i < ids.size(); ++i) out[i] = positions[ids[i]];
  return out;
}

double diagonal(const Positions3& points) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

Index bar_index(const std::vector<std::array<Index, 2>>& bars, Index a, Index b) {
  const std::array<Index, 2> key{std::min(a, b), std::max(a, b)};
  const auto it = std::lower_bound(bars.begin(), bars.end(), key);
  SKINSLIDE_CHECK(it != bars.end() && *it == key, "a loop edge is a bar");
  return static_cast<Index>(it - bars.begin());
}

// The bind net: the outer loop on the square, everything else in equilibrium. With Holes::Fill
// each hole gets a virtual free node joined to its loop vertices, with the loop's mean q, so the
// hole keeps its size instead of collapsing towards the free loop.
Positions2 bind_net(const PatchNet& patch, const std::vector<double>& q, const Positions2& outer_2d,
                    Holes holes, std::vector<Index>& node_order) {
  const Index n = static_cast<Index>(patch.vertices.size());
  BarNet net;
  net.node_count = n;
  net.bars = patch.bars;
  std::vector<double> q_all = q;
  if (holes == Holes::Fill) {
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
  Positions2 solved = solve_bar_net(net, q_all, start, &node_order);
  solved.resize(n);
  return solved;
}

PatchNet patch_net(const PolyMesh& bind, const PatchComponent& comp, const SlideOptions& options) {
  PatchNet patch;
  patch.selection = comp.selection;
  patch.faces = comp.faces;
  patch.vertices = comp.vertices;
  auto local = [&](Index v) {
    const auto it = std::lower_bound(patch.vertices.begin(), patch.vertices.end(), v);
    SKINSLIDE_CHECK(it != patch.vertices.end() && *it == v, "patch vertex");
    return static_cast<Index>(it - patch.vertices.begin());
  };
  for (Index f : patch.faces) {
    const Index* fv = bind.face_begin(f);
    const Index m = bind.face_size(f);
    for (Index k = 0; k < m; ++k) {
      const Index a = local(fv[k]), b = local(fv[(k + 1) % m]);
      patch.bars.push_back({std::min(a, b), std::max(a, b)});
    }
    // Polygons are triangulated only for location and interpolation, as the fan (v0, vi, vi+1).
    for (Index k = 0; k + 2 < m; ++k) {
      patch.triangles.push_back({local(fv[0]), local(fv[k + 1]), local(fv[k + 2])});
      patch.triangle_face.push_back(f);
      patch.triangle_fan.push_back(k);
    }
  }
  std::sort(patch.bars.begin(), patch.bars.end());
  patch.bars.erase(std::unique(patch.bars.begin(), patch.bars.end()), patch.bars.end());

  const Positions3 points = gather(bind.positions, patch.vertices);
  patch.bind_diagonal = diagonal(points);
  std::vector<double> lengths;
  std::vector<Index> starts;
  std::vector<char> on_loop(patch.vertices.size(), 0);
  for (const auto& mesh_loop : comp.loops) {
    std::vector<Index> loop;
    for (Index v : mesh_loop) {
      loop.push_back(local(v));
      on_loop[loop.back()] = 1;
    }
    lengths.push_back(loop_length(gather(points, loop)));
    starts.push_back(loop.front());
    patch.loops.push_back(std::move(loop));
  }
  patch.outer_loop = outer_loop(lengths, starts);
  for (Index v = 0; v < static_cast<Index>(patch.vertices.size()); ++v)
    if (!on_loop[v]) patch.free_vertices.push_back(v);
  patch.skipped = patch.free_vertices.empty();
  if (patch.skipped) return patch;  // nothing to move: no unwrap needed, whatever the loops
  patch.topology = triangle_topology(patch.triangles, static_cast<Index>(patch.vertices.size()));

  const auto& outer = patch.loops[patch.outer_loop];
  const SquareBoundary square = square_positions(gather(points, outer));
  for (int j = 0; j < 4; ++j) patch.corners[j] = outer[square.corners[j]];
  const std::vector<double> q =
      force_densities(bar_lengths(points, patch.bars), options.density, options.q_floor);
  // The frame nets' free nodes are among the bind net's: its fill-reducing order serves them too.
  std::vector<Index> node_order;
  patch.bind_net = bind_net(patch, q, square.positions, options.holes, node_order);
  patch.bind_net_flips = flipped_triangles(patch.bind_net, patch.triangles);

  // Frame nets: the same bars, every loop vertex fixed at its bind-net position.
  BarNet frame;
  frame.node_count = static_cast<Index>(patch.vertices.size());
  frame.bars = patch.bars;
  frame.fixed = on_loop;
  patch.solver =
      std::make_shared<const FrameNetSolver>(std::move(frame), patch.bind_net, node_order);
  return patch;
}

}  // namespace

BindSetup bind_setup(const PolyMesh& bind, const std::vector<std::vector<Index>>& selections,
                     const SlideOptions& options, const FaceNamer& name_face) {
  const FaceNamer namer =
      name_face ? name_face : [](Index f) { return "face " + std::to_string(f); };
  BindSetup setup;
  setup.options = options;
  setup.vertex_count = bind.vertex_count();
  const std::vector<PatchComponent> comps = patch_components(bind, selections, namer);
  for (size_t c = 0; c < comps.size(); ++c) {
    try {
      setup.patches.push_back(patch_net(bind, comps[c], options));
    } catch (const Error& e) {
      throw Error(e.kind(), "patch " + std::to_string(c) + " (" + namer(comps[c].faces.front()) +
                                ", " + std::to_string(comps[c].faces.size()) +
                                " faces): " + e.what());
    }
  }
  return setup;
}

}  // namespace skinslide
