#include "locate/locate.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

#include <gtest/gtest.h>

#include "locate/barycentric.h"
#include "mesh/measures.h"

namespace skinslide {
namespace {

// A jittered n x n grid net over the unit square, two triangles per cell.
struct Net {
  Positions2 points;
  std::vector<Triangle> triangles;
};
Net grid(int n, double jitter, unsigned seed) {
  Net net;
  std::mt19937 rng{seed};
  std::uniform_real_distribution<double> u(-jitter / n, jitter / n);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      Vec2 p(double(i) / n, double(j) / n);
      if (i > 0 && j > 0 && i < n && j < n) p += Vec2(u(rng), u(rng));
      net.points.push_back(p);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Index a = j * (n + 1) + i;
      net.triangles.push_back({a, a + 1, a + n + 2});
      net.triangles.push_back({a, a + n + 2, a + n + 1});
    }
  return net;
}

TEST(Locate, EveryPointIsFoundInATriangleThatHoldsIt) {
  const Net net = grid(20, 0.3, 0);
  const IdImage img = id_raster(net.points, net.triangles, 64);
  std::mt19937 rng{1};
  std::uniform_real_distribution<double> u(0, 1);
  Positions2 pts;
  for (int k = 0; k < 2000; ++k) pts.emplace_back(u(rng), u(rng));
  const auto loc = locate_points(pts, net.points, net.triangles, img);
  int fallbacks = 0;
  for (size_t k = 0; k < pts.size(); ++k) {
    const Triangle& t = net.triangles[loc[k].triangle];
    const Barycentric w = barycentric(pts[k], net.points[t[0]], net.points[t[1]], net.points[t[2]]);
    fallbacks += loc[k].fallback;
    EXPECT_GE(w.min(), -kInsideEps) << k;
    EXPECT_NEAR((loc[k].weight[0] * net.points[t[0]] + loc[k].weight[1] * net.points[t[1]] +
                 loc[k].weight[2] * net.points[t[2]] - pts[k])
                    .norm(),
                0, 1e-14);
  }
  // Cells are 3.2 px wide: only slivers that cover no pixel centre near the point need the
  // fallback.
  EXPECT_LE(fallbacks, 20);
}

TEST(Locate, APointOnASharedEdgeGoesToTheLargerSmallestBarycentricThenLowerIndex) {
  const Positions2 net{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<Triangle> tris{{0, 1, 2}, {0, 2, 3}};
  const IdImage img = id_raster(net, tris, 16);
  const auto loc = locate_points({{0.5, 0.5}, {0.25, 0.25}}, net, tris, img);
  EXPECT_EQ(loc[0].triangle, 0);  // on the diagonal: both have min 0, the lower index wins
  EXPECT_EQ(loc[1].triangle, 0);
}

TEST(Locate, TrianglesSmallerThanAPixelAreFoundByTheFallback) {
  const Net net = grid(50, 0.2, 3);
  const IdImage img = id_raster(net.points, net.triangles, 8);  // 8 px for 5000 triangles
  std::mt19937 rng{2};
  std::uniform_real_distribution<double> u(0, 1);
  Positions2 pts;
  for (int k = 0; k < 500; ++k) pts.emplace_back(u(rng), u(rng));
  const auto loc = locate_points(pts, net.points, net.triangles, img);
  int fallbacks = 0;
  for (size_t k = 0; k < pts.size(); ++k) {
    const Triangle& t = net.triangles[loc[k].triangle];
    EXPECT_GE(barycentric(pts[k], net.points[t[0]], net.points[t[1]], net.points[t[2]]).min(),
              -kInsideEps);
    fallbacks += loc[k].fallback;
  }
  EXPECT_GT(fallbacks, 0);
}

// The fallback lists candidates differently for a few points (only their cells) and for many
// (every cell): a point gets the same either way, inside the net, on its edges or outside it.
TEST(Locate, TheFallbackGivesAPointTheSameAloneOrAmongMany) {
  Net net = grid(40, 0.3, 5);
  net.points[20 * 41 + 20] += Vec2(2.0 / 40, 1.0 / 40);  // a fold: overlapping triangles
  const IdImage empty{1, {0}};  // no pixel names a triangle: every point falls back
  std::mt19937 rng{4};
  std::uniform_real_distribution<double> u(-0.05, 1.05);
  Positions2 pts;
  for (int k = 0; k < 1000; ++k) pts.emplace_back(u(rng), u(rng));
  for (int k = 0; k <= 40; ++k) pts.push_back(net.points[k * 41 + 7]);  // on nodes and edges
  ASSERT_GT(pts.size() * 16, net.triangles.size());  // all at once: the whole grid
  const auto many = locate_points(pts, net.points, net.triangles, empty);
  for (size_t k = 0; k < pts.size(); ++k) {
    const Location alone = locate_points({pts[k]}, net.points, net.triangles, empty)[0];
    EXPECT_EQ(many[k].triangle, alone.triangle) << k;
    EXPECT_EQ(many[k].weight, alone.weight) << k;
    EXPECT_TRUE(alone.fallback);
  }
}

TEST(Locate, APointOutsideTheNetTakesTheNearestTriangleClamped) {
  const Positions2 net{{0, 0}, {0.5, 0}, {0, 0.5}, {0.9, 0.9}, {1, 0.9}, {0.9, 1}};
  const std::vector<Triangle> tris{{0, 1, 2}, {3, 4, 5}};
  const IdImage img = id_raster(net, tris, 32);
  const auto loc = locate_points({{0.6, 0.1}, {0.99, 0.99}}, net, tris, img);
  EXPECT_TRUE(loc[0].fallback);
  EXPECT_EQ(loc[0].triangle, 0);
  for (double w : loc[0].weight) {
    EXPECT_GE(w, 0.0);
    EXPECT_LE(w, 1.0);
  }
  EXPECT_NEAR(loc[0].weight[1], 1.0, 1e-15);  // the closest point is corner (0.5, 0)
  EXPECT_EQ(loc[1].triangle, 1);
}

TEST(LocateTopology, NeighboursAcrossEachEdgeAndTrianglesAtEachCorner) {
  // Square 0-1-2-3 split by the diagonal 0-2, plus a triangle 1-4-2 on the right.
  const std::vector<Triangle> tris{{0, 1, 2}, {0, 2, 3}, {1, 4, 2}};
  const TriangleTopology topo = triangle_topology(tris, 5);
  EXPECT_EQ(topo.neighbour[0], (std::array<Index, 3>{2, 1, -1}));  // opposite 0: edge 1-2
  EXPECT_EQ(topo.neighbour[1], (std::array<Index, 3>{-1, -1, 0}));
  EXPECT_EQ(topo.neighbour[2], (std::array<Index, 3>{-1, 0, -1}));
  EXPECT_EQ(topo.corner_start, (std::vector<Index>{0, 2, 4, 7, 8, 9}));
  EXPECT_EQ(topo.corner_triangles, (std::vector<Index>{0, 1, 0, 2, 0, 1, 2, 1, 2}));
}

// The walk, from nodes far from the points, finds what the image finds wherever the image
// finds a triangle, and a triangle that holds the point everywhere.
TEST(LocateWalk, AgreesWithTheImageFromAnyStartNode) {
  const Net net = grid(40, 0.3, 5);
  const TriangleTopology topo = triangle_topology(net.triangles, Index(net.points.size()));
  const IdImage img = id_raster(net.points, net.triangles, 256);
  std::mt19937 rng{6};
  std::uniform_real_distribution<double> u(0, 1);
  std::uniform_int_distribution<Index> node(0, Index(net.points.size()) - 1);
  Positions2 pts;
  std::vector<Index> start;
  for (int k = 0; k < 3000; ++k) {
    pts.emplace_back(u(rng), u(rng));
    start.push_back(node(rng));
  }
  pts.push_back(net.points[100]);  // exactly on a node: six triangles hold it
  start.push_back(0);
  const auto walk = locate_points_by_walk(pts, start, net.points, net.triangles, topo, {});
  const auto image = locate_points(pts, net.points, net.triangles, img);
  int walked = 0;
  for (size_t k = 0; k < pts.size(); ++k) {
    const Triangle& t = net.triangles[walk[k].triangle];
    EXPECT_GE(barycentric(pts[k], net.points[t[0]], net.points[t[1]], net.points[t[2]]).min(),
              -kInsideEps);
    walked += !walk[k].fallback;
    if (!image[k].fallback) {
      EXPECT_EQ(walk[k].triangle, image[k].triangle) << k;
      EXPECT_EQ(walk[k].weight, image[k].weight) << k;
    }
  }
  EXPECT_EQ(walked, int(pts.size()));  // a convex net without folds: every walk arrives
}

// Three nodes on one side of the square make a zero-area triangle (a patch corner whose quad has
// three loop vertices): a flip in the reports, but it holds no point and covers nothing, so the
// walk keeps its shortcut and still agrees with the image.
TEST(LocateWalk, AZeroAreaTriangleOnTheBorderKeepsTheShortcutExact) {
  Net net = grid(30, 0.3, 7);
  net.triangles.push_back({0, 1, 2});  // (0, 0), (1/30, 0), (2/30, 0)
  const Folds folds = count_folds(net.points, net.triangles);
  EXPECT_EQ(folds.flipped, 1);
  EXPECT_TRUE(folds.reversed.empty());
  const TriangleTopology topo = triangle_topology(net.triangles, Index(net.points.size()));
  const IdImage img = id_raster(net.points, net.triangles, 256);
  std::mt19937 rng{8};
  std::uniform_real_distribution<double> u(0, 1);
  Positions2 pts;
  std::vector<Index> start;
  for (int k = 0; k < 2000; ++k) {
    pts.emplace_back(u(rng), 0.1 * u(rng));  // along the side with the sliver
    start.push_back(Index(k % 31) + 31);     // second row of nodes: not the sliver's
  }
  const auto walk =
      locate_points_by_walk(pts, start, net.points, net.triangles, topo, folds.reversed);
  const auto image = locate_points(pts, net.points, net.triangles, img);
  for (size_t k = 0; k < pts.size(); ++k) {
    EXPECT_NE(walk[k].triangle, Index(net.triangles.size()) - 1) << k;
    EXPECT_EQ(walk[k].triangle, image[k].triangle) << k;
    EXPECT_EQ(walk[k].weight, image[k].weight) << k;
  }
}

// The documented rule over every triangle: the holder with the largest smallest barycentric, then
// the lowest index.
std::optional<Location> best_of_all(const Vec2& p, const Net& net) {
  std::optional<Location> best;
  for (Index t = 0; t < Index(net.triangles.size()); ++t) {
    const Triangle& tri = net.triangles[t];
    const Barycentric w =
        barycentric(p, net.points[tri[0]], net.points[tri[1]], net.points[tri[2]]);
    if (w.ok && w.min() >= -kInsideEps &&
        (!best || w.min() > *std::min_element(best->weight.begin(), best->weight.end())))
      best = Location{t, w.w, false};
  }
  return best;
}

// A node pushed across its neighbours folds the net. Away from the reversed triangles the walk
// takes its shortcut: every point gets what the full search gives it, and away from the fold
// that is the triangle the rule picks among all triangles.
TEST(LocateWalk, InAFoldedNetTheShortcutChangesNoResult) {
  Net net = grid(30, 0.3, 9);
  net.points[15 * 31 + 15] += Vec2(1.6 / 30, 0.7 / 30);
  const Folds folds = count_folds(net.points, net.triangles);
  ASSERT_FALSE(folds.reversed.empty());
  const TriangleTopology topo = triangle_topology(net.triangles, Index(net.points.size()));
  std::mt19937 rng{10};
  std::uniform_real_distribution<double> u(0, 1), fold(0.5, 0.56);
  std::uniform_int_distribution<Index> node(0, Index(net.points.size()) - 1);
  Positions2 pts;
  std::vector<Index> start;
  for (int k = 0; k < 4000; ++k) {
    pts.push_back(k % 2 ? Vec2(u(rng), u(rng)) : Vec2(fold(rng), fold(rng)));
    start.push_back(node(rng));
  }
  const auto walk =
      locate_points_by_walk(pts, start, net.points, net.triangles, topo, folds.reversed);
  // Listing every triangle as reversed turns the shortcut off: the full search, as reference.
  std::vector<Index> every(net.triangles.size());
  for (size_t t = 0; t < every.size(); ++t) every[t] = Index(t);
  const auto full = locate_points_by_walk(pts, start, net.points, net.triangles, topo, every);
  int away = 0, overlapped = 0;
  for (size_t k = 0; k < pts.size(); ++k) {
    EXPECT_EQ(walk[k].triangle, full[k].triangle) << k;
    EXPECT_EQ(walk[k].weight, full[k].weight) << k;
    int holders = 0;
    for (const Triangle& t : net.triangles) {
      const Barycentric w =
          barycentric(pts[k], net.points[t[0]], net.points[t[1]], net.points[t[2]]);
      holders += w.ok && w.min() >= -kInsideEps;
    }
    overlapped += holders > 1 && walk[k].weight[0] > 0 && walk[k].weight[1] > 0 &&
                  walk[k].weight[2] > 0;  // covered twice, not on a shared edge or corner
    if ((pts[k] - Vec2(0.5, 0.5)).norm() < 0.15) continue;  // the fold and its overlaps
    ++away;
    const auto rule = best_of_all(pts[k], net);
    ASSERT_TRUE(rule);
    EXPECT_EQ(walk[k].triangle, rule->triangle) << k;
    EXPECT_EQ(walk[k].weight, rule->weight) << k;
  }
  EXPECT_GT(away, 1500);
  EXPECT_GT(overlapped, 20);  // the fold does cover some points more than once
}

TEST(LocateWalk, ABlockedWalkEndsInTheFallback) {
  // Two triangles that share no edge: the walk from the first cannot reach the second.
  const Positions2 net{{0, 0}, {0.5, 0}, {0, 0.5}, {0.9, 0.9}, {1, 0.9}, {0.9, 1}};
  const std::vector<Triangle> tris{{0, 1, 2}, {3, 4, 5}};
  const TriangleTopology topo = triangle_topology(tris, 6);
  const auto loc =
      locate_points_by_walk({{0.95, 0.95}, {0.1, 0.1}, {0.6, 0.1}}, {0, 0, 0}, net, tris, topo, {});
  EXPECT_TRUE(loc[0].fallback);
  EXPECT_EQ(loc[0].triangle, 1);
  EXPECT_FALSE(loc[1].fallback);
  EXPECT_EQ(loc[1].triangle, 0);
  EXPECT_TRUE(loc[2].fallback);  // outside the net: the nearest triangle, clamped
  EXPECT_NEAR(loc[2].weight[1], 1.0, 1e-15);
}

// A net with a square hole: walks from one side towards points behind the hole end at its
// border. The search around the walk's end then finds the triangle the rule picks among all.
TEST(LocateWalk, AWalkBlockedByAHoleIsFinishedNearby) {
  Net net = grid(20, 0.3, 7);
  std::vector<Triangle> kept;
  for (size_t t = 0; t < net.triangles.size(); ++t) {
    const int cell = static_cast<int>(t / 2), i = cell % 20, j = cell / 20;
    if (i < 6 || i > 13 || j < 6 || j > 13) kept.push_back(net.triangles[t]);
  }
  const Index nodes = static_cast<Index>(net.points.size());
  const TriangleTopology topo = triangle_topology(kept, nodes);
  // Points on a ring round the hole, each walked from the node diametrically opposite.
  Positions2 pts;
  std::vector<Index> start;
  for (int k = 0; k < 64; ++k) {
    const double a = 2 * M_PI * k / 64;
    pts.push_back(Vec2(0.5, 0.5) + 0.3 * Vec2(std::cos(a), std::sin(a)));
    const Vec2 opposite = Vec2(0.5, 0.5) - 0.36 * Vec2(std::cos(a), std::sin(a));
    const int i = std::clamp(static_cast<int>(std::lround(opposite.x() * 20)), 0, 20);
    const int j = std::clamp(static_cast<int>(std::lround(opposite.y() * 20)), 0, 20);
    start.push_back(j * 21 + i);
  }
  int finished_nearby = 0;
  for (size_t k = 0; k < pts.size(); ++k) {
    // One point a call: each walk starts from its own node, not from the point before.
    const Location walk =
        locate_points_by_walk({pts[k]}, {start[k]}, net.points, kept, topo, {})[0];
    // The rule over every triangle: the largest smallest barycentric, then the lower index.
    Index best = -1;
    double best_min = -INFINITY;
    for (size_t t = 0; t < kept.size(); ++t) {
      const Triangle& tri = kept[t];
      const Barycentric w =
          barycentric(pts[k], net.points[tri[0]], net.points[tri[1]], net.points[tri[2]]);
      if (w.ok && w.min() >= -kInsideEps && w.min() > best_min) {
        best_min = w.min();
        best = static_cast<Index>(t);
      }
    }
    ASSERT_GE(best, 0) << k;  // the ring lies in the net, outside the hole
    EXPECT_EQ(walk.triangle, best) << k;
    finished_nearby += walk.fallback;
  }
  EXPECT_GT(finished_nearby, 8);  // the hole does block walks
}

// Each walk may start from the triangle that held the point before: in any order, and in a
// folded net, every point gets what it gets when located alone from its own node.
TEST(LocateWalk, StartingFromThePreviousPointChangesNoResult) {
  Net net = grid(30, 0.3, 3);
  // Fold the net: one node pushed across its neighbours.
  net.points[15 * 31 + 15] += Vec2(2.5 / 30, 1.5 / 30);
  const TriangleTopology topo = triangle_topology(net.triangles, Index(net.points.size()));
  const Folds folds = count_folds(net.points, net.triangles);
  ASSERT_FALSE(folds.reversed.empty());
  std::mt19937 rng{11};
  std::uniform_real_distribution<double> u(0, 1);
  std::uniform_int_distribution<Index> node(0, Index(net.points.size()) - 1);
  Positions2 pts;
  std::vector<Index> start;
  for (int k = 0; k < 2000; ++k) {
    // Runs of neighbouring points (the chained start helps) broken by jumps (it must not hurt).
    const Vec2 p = k % 50 == 0 || pts.empty()
                       ? Vec2(u(rng), u(rng))
                       : Vec2(pts.back() + Vec2(0.01 * (u(rng) - 0.5), 0.01 * (u(rng) - 0.5)));
    pts.push_back(p.cwiseMax(Vec2(0, 0)).cwiseMin(Vec2(1, 1)));
    start.push_back(node(rng));
  }
  const auto chained =
      locate_points_by_walk(pts, start, net.points, net.triangles, topo, folds.reversed);
  for (size_t k = 0; k < pts.size(); ++k) {
    const Location alone = locate_points_by_walk({pts[k]}, {start[k]}, net.points, net.triangles,
                                                 topo, folds.reversed)[0];
    EXPECT_EQ(chained[k].triangle, alone.triangle) << k;
    EXPECT_EQ(chained[k].weight, alone.weight) << k;
  }
}

TEST(LocateWalk, InAFoldedNetTheBestOfTheOverlappingTrianglesWins) {
  // Triangle 1 is folded under triangle 0; its centroid (0.6, 0.15) has smallest barycentric
  // 1/3 there and 0.15 in triangle 0. The walk from node 2 arrives in triangle 0 first.
  const Positions2 net{{0, 0}, {1, 0}, {0, 1}, {0.8, 0.45}};
  const std::vector<Triangle> tris{{0, 1, 2}, {0, 3, 1}};
  const TriangleTopology topo = triangle_topology(tris, 4);
  const Vec2 p(0.6, 0.15);
  const auto folded = locate_points_by_walk({p}, {2}, net, tris, topo, {1});
  EXPECT_EQ(folded[0].triangle, 1);
  EXPECT_NEAR(folded[0].weight[0], 1.0 / 3.0, 1e-15);
}

TEST(Locate, ClosestPointOnADegenerateTriangleIsFinite) {
  const ClosestPoint cp = closest_point({1, 1}, {0, 0}, {0, 0}, {0, 0});
  EXPECT_DOUBLE_EQ(cp.distance2, 2.0);
  EXPECT_DOUBLE_EQ(cp.w[0] + cp.w[1] + cp.w[2], 1.0);
}

}  // namespace
}  // namespace skinslide
