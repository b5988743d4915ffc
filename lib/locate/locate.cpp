#include "locate/locate.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <tuple>

#include "core/check.h"
#include "locate/barycentric.h"

namespace skinslide {
namespace {

// Among `candidates` (ascending, unique), the triangle holding p by the documented rule.
std::optional<Location> best_holder(const Vec2& p, const Positions2& net,
                                    const std::vector<Triangle>& triangles,
                                    const std::vector<Index>& candidates) {
  std::optional<Location> best;
  double best_min = -INFINITY;
  for (Index t : candidates) {
    const Triangle& tri = triangles[t];
    const Barycentric w = barycentric(p, net[tri[0]], net[tri[1]], net[tri[2]]);
    if (!w.ok || w.min() < -kInsideEps) continue;
    if (w.min() > best_min) {  // strict: the lower index keeps a tie
      best_min = w.min();
      best = Location{t, w.w, false};
    }
  }
  return best;
}

// A uniform n x n grid of square cells over the net's extent: the cell of a point, and the
// cells a triangle's bounding box covers.
class GridCells {
 public:
  GridCells(const Positions2& net, int n) : n_(n) {
    Vec2 hi(-INFINITY, -INFINITY);
    for (const Vec2& p : net) {
      lo_ = lo_.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    cell_ = std::max((hi - lo_).maxCoeff() / n_, 1e-300);
  }
  int n() const { return n_; }
  double size() const { return cell_; }
  std::array<int, 2> of(const Vec2& p) const {
    return {clamp_cell((p.x() - lo_.x()) / cell_), clamp_cell((p.y() - lo_.y()) / cell_)};
  }
  size_t index(int i, int j) const { return static_cast<size_t>(j) * n_ + i; }
  /// i0, j0, i1, j1: the cells from (i0, j0) to (i1, j1) cover the triangle's box.
  std::array<int, 4> box(const Positions2& net, const Triangle& t) const {
    const Vec2& a = net[t[0]];
    const Vec2& b = net[t[1]];
    const Vec2& c = net[t[2]];
    return {clamp_cell((std::min({a.x(), b.x(), c.x()}) - lo_.x()) / cell_),
            clamp_cell((std::min({a.y(), b.y(), c.y()}) - lo_.y()) / cell_),
            clamp_cell((std::max({a.x(), b.x(), c.x()}) - lo_.x()) / cell_),
            clamp_cell((std::max({a.y(), b.y(), c.y()}) - lo_.y()) / cell_)};
  }

 private:
  int clamp_cell(double x) const {
    if (!(x >= 0)) return 0;
    return std::min(static_cast<int>(x), n_ - 1);
  }
  int n_;
  Vec2 lo_{INFINITY, INFINITY};
  double cell_ = 1;
};

// A uniform grid over the triangles' bounding boxes: complete candidate sets for the fallback.
class TriangleGrid {
 public:
  TriangleGrid(const Positions2& net, const std::vector<Triangle>& triangles,
               const GridCells& cells)
      : net_(net), triangles_(triangles), cells_(cells), n_(cells.n()) {
    start_.assign(static_cast<size_t>(n_) * n_ + 1, 0);
    // Two passes (count, fill) keep each cell's list in ascending triangle order.
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<Index> fill(start_.begin(), start_.end() - 1);
      for (size_t t = 0; t < triangles.size(); ++t) {
        const auto [i0, j0, i1, j1] = cells_.box(net_, triangles_[t]);
        for (int j = j0; j <= j1; ++j)
          for (int i = i0; i <= i1; ++i) {
            const size_t c = cells_.index(i, j);
            if (pass == 0)
              ++start_[c + 1];
            else
              items_[fill[c]++] = static_cast<Index>(t);
          }
      }
      if (pass == 0) {
        for (size_t c = 0; c + 1 < start_.size(); ++c) start_[c + 1] += start_[c];
        items_.resize(start_.back());
      }
    }
  }

  /// The rule's choice among the triangles whose box covers p's cell, else the nearest.
  Location locate(const Vec2& p) const {
    const auto [pi, pj] = cells_.of(p);
    const size_t c = cells_.index(pi, pj);
    const std::vector<Index> candidates(items_.begin() + start_[c], items_.begin() + start_[c + 1]);
    if (auto holder = best_holder(p, net_, triangles_, candidates)) {
      holder->fallback = true;
      return *holder;
    }
    return nearest(p);
  }

  /// The nearest triangle to p (lowest index on ties), with the barycentrics of its closest
  /// point: for a point that no triangle holds.
  Location nearest(const Vec2& p) const {
    const auto [pi, pj] = cells_.of(p);
    // Rings of cells around p until no unseen cell can be closer.
    Location best;
    best.fallback = true;
    double best_d2 = INFINITY;
    auto visit = [&](int i, int j) {
      if (i < 0 || j < 0 || i >= n_ || j >= n_) return;
      for (Index k = start_[cells_.index(i, j)]; k < start_[cells_.index(i, j) + 1]; ++k) {
        const Index t = items_[k];
        const Triangle& tri = triangles_[t];
        const ClosestPoint cp = closest_point(p, net_[tri[0]], net_[tri[1]], net_[tri[2]]);
        if (cp.distance2 < best_d2 || (cp.distance2 == best_d2 && t < best.triangle)) {
          best_d2 = cp.distance2;
          best.triangle = t;
          best.weight = cp.w;
        }
      }
    };
    for (int r = 0; r < n_; ++r) {
      const double ring_gap = std::max(0, r - 1) * cells_.size();
      if (ring_gap * ring_gap > best_d2) break;
      if (r == 0) {
        visit(pi, pj);
        continue;
      }
      for (int i = pi - r; i <= pi + r; ++i) {
        visit(i, pj - r);
        visit(i, pj + r);
      }
      for (int j = pj - r + 1; j <= pj + r - 1; ++j) {
        visit(pi - r, j);
        visit(pi + r, j);
      }
    }
    SKINSLIDE_CHECK(best.triangle >= 0, "the fallback found no triangle");
    return best;
  }

 private:
  const Positions2& net_;
  const std::vector<Triangle>& triangles_;
  const GridCells& cells_;
  int n_;
  std::vector<Index> start_;
  std::vector<Index> items_;
};

// Where some triangles might hold a point: their bounding boxes, each grown by kInsideEps of its
// diagonal (and a little more for rounding), marked on a grid over the boxes' extent. A point in
// no marked cell has a barycentric below -kInsideEps in each of those triangles, so none of them
// holds it; a marked cell only sends its points down the slow path.
class NearTriangles {
 public:
  NearTriangles(const Positions2& net, const std::vector<Triangle>& triangles,
                const std::vector<Index>& which)
      : marked_(kCells * kCells, 0) {
    std::vector<std::pair<Vec2, Vec2>> boxes;
    for (Index t : which) {
      const Vec2& a = net[triangles[t][0]];
      const Vec2& b = net[triangles[t][1]];
      const Vec2& c = net[triangles[t][2]];
      const Vec2 lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
      const double grow = 4 * kInsideEps * (hi - lo).norm() + 1e-300;
      boxes.push_back({lo - Vec2(grow, grow), hi + Vec2(grow, grow)});
      lo_ = lo_.cwiseMin(boxes.back().first);
      hi_ = hi_.cwiseMax(boxes.back().second);
    }
    for (const auto& [lo, hi] : boxes)
      for (int j = cell(lo.y(), 1); j <= cell(hi.y(), 1); ++j)
        for (int i = cell(lo.x(), 0); i <= cell(hi.x(), 0); ++i) marked_[j * kCells + i] = 1;
  }
  bool contains(const Vec2& p) const {
    if (p.x() < lo_.x() || p.y() < lo_.y() || p.x() > hi_.x() || p.y() > hi_.y()) return false;
    return marked_[cell(p.y(), 1) * kCells + cell(p.x(), 0)] != 0;
  }

 private:
  static constexpr int kCells = 128;
  // Monotone in x, so a point inside a box falls in one of the cells marked for it.
  int cell(double x, int axis) const {
    const double f = (x - lo_[axis]) / (hi_[axis] - lo_[axis]) * kCells;
    if (!(f >= 0)) return 0;  // also NaN, from an extent of zero width
    return f < kCells ? static_cast<int>(f) : kCells - 1;
  }

  Vec2 lo_{INFINITY, INFINITY};
  Vec2 hi_{-INFINITY, -INFINITY};
  std::vector<char> marked_;
};

// The fallback for the points the image or the walk did not place: among the triangles whose
// bounding box covers the point's cell of a grid over the net, the rule's choice; failing that,
// the nearest triangle. For a few points (failed walks) the candidates are collected in one pass
// over the triangles that looks only at the cells holding such points, instead of listing every
// triangle of every cell (tests/bench/README.md "Performance"); that full grid is built for many
// points, and for a point no triangle holds.
void locate_missed(const Positions2& points, const Positions2& net,
                   const std::vector<Triangle>& triangles, const std::vector<size_t>& missed,
                   std::vector<Location>& out) {
  if (missed.empty()) return;
  // About one cell per triangle keeps each point's candidates few.
  const GridCells cells(
      net, std::clamp(static_cast<int>(std::sqrt(static_cast<double>(triangles.size()))), 1, 4096));
  if (missed.size() * 16 > triangles.size()) {
    // Many points (an image with triangles smaller than its pixels): every cell is wanted.
    const TriangleGrid grid(net, triangles, cells);
    for (size_t k : missed) out[k] = grid.locate(points[k]);
    return;
  }
  std::vector<std::pair<size_t, size_t>> by_cell;  // (cell, position in missed), sorted
  for (size_t m = 0; m < missed.size(); ++m) {
    const auto [i, j] = cells.of(points[missed[m]]);
    by_cell.push_back({cells.index(i, j), m});
  }
  std::sort(by_cell.begin(), by_cell.end());
  std::vector<char> wanted(static_cast<size_t>(cells.n()) * cells.n(), 0);
  for (const auto& [c, m] : by_cell) wanted[c] = 1;
  std::vector<std::vector<Index>> candidates(missed.size());  // ascending, as t runs
  for (size_t t = 0; t < triangles.size(); ++t) {
    const auto [i0, j0, i1, j1] = cells.box(net, triangles[t]);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const size_t c = cells.index(i, j);
        if (!wanted[c]) continue;
        for (auto it = std::lower_bound(by_cell.begin(), by_cell.end(), std::pair{c, size_t{0}});
             it != by_cell.end() && it->first == c; ++it)
          candidates[it->second].push_back(static_cast<Index>(t));
      }
  }
  std::optional<TriangleGrid> grid;
  for (size_t m = 0; m < missed.size(); ++m) {
    const Vec2& p = points[missed[m]];
    if (auto holder = best_holder(p, net, triangles, candidates[m])) {
      holder->fallback = true;
      out[missed[m]] = *holder;
      continue;
    }
    if (!grid) grid.emplace(net, triangles, cells);
    out[missed[m]] = grid->nearest(p);
  }
}

// Where a walk failed (it circled, left the net or met a degenerate triangle), the triangles
// around its end, breadth-first across shared edges, up to kTriangles of them: the first that
// holds the point. Points there are near a hole's border or a fold, a few triangles away; this
// spares the whole-net grid of locate_missed, which costs a frame tens of milliseconds on large
// nets (tests/bench/README.md "Performance").
class NearbySearch {
 public:
  explicit NearbySearch(size_t triangle_count) : triangle_count_(triangle_count) {}

  /// On success, t and w are the holder and its barycentrics.
  bool find_holder(const Vec2& p, Index& t, const Positions2& net,
                   const std::vector<Triangle>& triangles, const TriangleTopology& topology,
                   Barycentric& w) {
    if (seen_.empty()) seen_.assign(triangle_count_, 0);  // only once a walk has failed
    queue_.assign(1, t);
    seen_[t] = 1;
    bool found = false;
    for (size_t head = 0; head < queue_.size() && head < kTriangles; ++head) {
      const Index u = queue_[head];
      const Triangle& tri = triangles[u];
      const Barycentric b = barycentric(p, net[tri[0]], net[tri[1]], net[tri[2]]);
      if (b.ok && b.min() >= -kInsideEps) {
        t = u;
        w = b;
        found = true;
        break;
      }
      for (Index n : topology.neighbour[u])
        if (n >= 0 && !seen_[n]) {
          seen_[n] = 1;
          queue_.push_back(n);
        }
    }
    for (Index u : queue_) seen_[u] = 0;
    return found;
  }

 private:
  static constexpr size_t kTriangles = 4096;
  size_t triangle_count_;
  std::vector<char> seen_;
  std::vector<Index> queue_;
};

}  // namespace

TriangleTopology triangle_topology(const std::vector<Triangle>& triangles, Index vertex_count) {
  TriangleTopology topo;
  const Index nt = static_cast<Index>(triangles.size());
  topo.corner_start.assign(static_cast<size_t>(vertex_count) + 1, 0);
  for (const Triangle& t : triangles)
    for (Index v : t) ++topo.corner_start[v + 1];
  for (size_t v = 0; v + 1 < topo.corner_start.size(); ++v)
    topo.corner_start[v + 1] += topo.corner_start[v];
  topo.corner_triangles.resize(topo.corner_start.back());
  std::vector<Index> fill(topo.corner_start.begin(), topo.corner_start.end() - 1);
  for (Index t = 0; t < nt; ++t)
    for (Index v : triangles[t]) topo.corner_triangles[fill[v]++] = t;  // ascending t
  // The edge (a, b) opposite corner k of t has its twin (b, a) in a triangle around b: the first
  // such triangle, in ascending order, is the neighbour.
  topo.neighbour.assign(triangles.size(), {-1, -1, -1});
  for (Index t = 0; t < nt; ++t)
    for (Index k = 0; k < 3; ++k) {
      const Index a = triangles[t][(k + 1) % 3], b = triangles[t][(k + 2) % 3];
      for (Index i = topo.corner_start[b]; i < topo.corner_start[b + 1]; ++i) {
        const Triangle& u = triangles[topo.corner_triangles[i]];
        const int j = u[0] == b ? 0 : u[1] == b ? 1 : 2;  // b's corner in u: is a next?
        if (u[(j + 1) % 3] == a) {
          topo.neighbour[t][k] = topo.corner_triangles[i];
          break;
        }
      }
    }
  return topo;
}

std::vector<Location> locate_points(const Positions2& points, const Positions2& net,
                                    const std::vector<Triangle>& triangles, const IdImage& image) {
  SKINSLIDE_CHECK(!triangles.empty(), "a net with triangles");
  std::vector<Location> out(points.size());
  std::vector<size_t> missed;
  std::vector<Index> candidates;
  const int n = image.size;
  for (size_t k = 0; k < points.size(); ++k) {
    const Vec2& p = points[k];
    const int pi = std::clamp(static_cast<int>(std::floor(p.x() * n)), 0, n - 1);
    const int pj = std::clamp(static_cast<int>(std::floor(p.y() * n)), 0, n - 1);
    candidates.clear();
    for (int j = std::max(pj - 1, 0); j <= std::min(pj + 1, n - 1); ++j)
      for (int i = std::max(pi - 1, 0); i <= std::min(pi + 1, n - 1); ++i)
        if (const std::uint32_t id = image.at(i, j))
          candidates.push_back(static_cast<Index>(id - 1));
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    if (auto holder = best_holder(p, net, triangles, candidates))
      out[k] = *holder;
    else
      missed.push_back(k);
  }
  locate_missed(points, net, triangles, missed, out);
  return out;
}

std::vector<Location> locate_points_by_walk(const Positions2& points,
                                            const std::vector<Index>& start, const Positions2& net,
                                            const std::vector<Triangle>& triangles,
                                            const TriangleTopology& topology,
                                            const std::vector<Index>& reversed) {
  SKINSLIDE_CHECK(!triangles.empty(), "a net with triangles");
  SKINSLIDE_CHECK(start.size() == points.size(), "one start node per point");
  SKINSLIDE_CHECK(topology.neighbour.size() == triangles.size(), "topology of these triangles");
  std::vector<Location> out(points.size());
  std::vector<size_t> missed;
  std::vector<Index> candidates;
  const int max_steps = 64 + 4 * static_cast<int>(std::sqrt(static_cast<double>(triangles.size())));
  const NearTriangles near_reversed(net, triangles, reversed);
  NearbySearch nearby(triangles.size());
  Index previous = -1;  // the triangle that held the previous point
  for (size_t k = 0; k < points.size(); ++k) {
    const Vec2& p = points[k];
    const Index v = start[k];
    SKINSLIDE_CHECK(topology.corner_start[v] < topology.corner_start[v + 1],
                    "a start node with triangles");
    // The walk starts from the point's own node, or from the triangle that held the previous
    // point if that is nearer. The node is as far from the point as the frame moved it (many
    // triangles on a large patch); consecutive points are mostly neighbouring vertices, one
    // edge apart. Away from the reversed triangles either start ends in the same holder (or
    // the same candidates); near them, where triangles overlap, the walk keeps the node's start.
    Index t = topology.corner_triangles[topology.corner_start[v]];
    const bool near_fold = near_reversed.contains(p);
    if (previous >= 0 && !near_fold &&
        (net[triangles[previous][0]] - p).squaredNorm() < (net[v] - p).squaredNorm())
      t = previous;
    Barycentric w;
    bool held = false;
    // Around folds and holes a walk can circle for ever; Brent's check (a checkpoint moved at
    // every power of two steps) stops it within two turns of the circle.
    Index checkpoint = t;
    int lap = 1, since_checkpoint = 0;
    for (int step = 0; step <= max_steps; ++step) {
      const Triangle& tri = triangles[t];
      w = barycentric(p, net[tri[0]], net[tri[1]], net[tri[2]]);
      if (!w.ok) break;  // a degenerate triangle: no direction to go
      int worst = 0;
      for (int c = 1; c < 3; ++c)
        if (w.w[c] < w.w[worst]) worst = c;
      if (w.w[worst] >= -kInsideEps) {
        held = true;
        break;
      }
      // Across the edge opposite the most negative barycentric; at a border, the other one.
      Index next = topology.neighbour[t][worst];
      if (next < 0) {
        const int a = (worst + 1) % 3, b = (worst + 2) % 3;
        const int other = w.w[a] < w.w[b] ? a : b;
        if (w.w[other] < -kInsideEps) next = topology.neighbour[t][other];
      }
      if (next < 0 || next == checkpoint) break;
      t = next;
      if (++since_checkpoint == lap) {
        checkpoint = t;
        lap *= 2;
        since_checkpoint = 0;
      }
    }
    const bool walked = held;
    // Near a fold the first holder found need not lead to the rule's choice among overlapping
    // triangles: the grid of locate_missed, which sees them all, decides there.
    if (!held && !near_fold) held = nearby.find_holder(p, t, net, triangles, topology, w);
    if (!held) {
      missed.push_back(k);
      continue;
    }
    previous = t;
    if (w.min() > 0 && !near_fold) {
      out[k] = Location{t, w.w, !walked};
      continue;
    }
    candidates.clear();
    for (Index c : triangles[t])
      candidates.insert(candidates.end(),
                        topology.corner_triangles.begin() + topology.corner_start[c],
                        topology.corner_triangles.begin() + topology.corner_start[c + 1]);
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    out[k] = *best_holder(p, net, triangles, candidates);  // t itself holds p
    out[k].fallback = !walked;
  }
  locate_missed(points, net, triangles, missed, out);
  return out;
}

}  // namespace skinslide
