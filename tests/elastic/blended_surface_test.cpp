// The blended surface the relaxation moves on with --blend (blended_surface.h): it passes through
// every frame vertex, is smooth (C1) across the chart's edges where the facets are not, has the
// Jacobian it reports, keeps the facets' own planes away from the bands; and a slide relaxed on it
// keeps every guarantee of the elastic method on the frame's facets.
#include "elastic/blended_surface.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "elastic/relax.h"
#include "elastic/surface_map.h"
#include "helpers/meshes.h"
#include "helpers/samples.h"
#include "pipeline/bind_setup.h"
#include "pipeline/slide_frame.h"

namespace skinslide {
namespace {

// A bumpy 6 x 6 grid of triangles (7 x 7 nodes): its chart, and a frame that bends and ripples it
// so that neighbouring facets meet at a crease everywhere. With `jitter` its inner nodes are moved
// at random by up to that share of the grid's spacing: needles and caps among its triangles.
struct Bumpy {
  Positions3 bind;
  std::vector<Triangle> triangles;
  Chart chart;
  Positions3 frame;
  explicit Bumpy(double jitter = 0, unsigned seed = 1) {
    const int n = 7;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> shift(-jitter, jitter);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const bool inner = i > 0 && j > 0 && i + 1 < n && j + 1 < n;
        const double dx = inner ? shift(rng) : 0, dy = inner ? shift(rng) : 0;
        bind.emplace_back(i + 0.2 * ((i * j) % 3 - 1) * (j % 2) + dx, j + dy, 0);
      }
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i) {
        const Index a = j * n + i, b = a + 1, c = a + n, d = c + 1;
        triangles.push_back({a, b, d});
        triangles.push_back({a, d, c});
      }
    std::vector<Index> loop;
    for (int i = 0; i < n; ++i) loop.push_back(i);
    for (int j = 1; j < n; ++j) loop.push_back(j * n + n - 1);
    for (int i = n - 2; i >= 0; --i) loop.push_back((n - 1) * n + i);
    for (int j = n - 2; j >= 1; --j) loop.push_back(j * n);
    chart = disk_chart(bind, triangles, {loop}, 0);
    for (const Vec3& p : bind)
      frame.emplace_back(p.x(), p.y(),
                         0.4 * std::sin(1.7 * p.x()) * std::cos(1.3 * p.y()) + 0.1 * p.x() * p.x());
  }
  // The smallest angle of any chart triangle, in degrees.
  double smallest_angle() const {
    double smallest = 180;
    for (const Triangle& t : chart.triangles)
      for (int k = 0; k < 3; ++k) {
        const Vec2 a = chart.uv[t[(k + 1) % 3]] - chart.uv[t[k]];
        const Vec2 b = chart.uv[t[(k + 2) % 3]] - chart.uv[t[k]];
        smallest = std::min(smallest, std::acos(a.dot(b) / (a.norm() * b.norm())) * 180 / M_PI);
      }
    return smallest;
  }
};

// A point inside chart triangle t at barycentrics (a, b, 1 - a - b).
Vec2 inside(const Chart& chart, Index t, double a, double b) {
  const Triangle& tri = chart.triangles[t];
  return a * chart.uv[tri[0]] + b * chart.uv[tri[1]] + (1 - a - b) * chart.uv[tri[2]];
}

void expect_through_every_frame_vertex(const Bumpy& m, double width_share) {
  const SurfaceBlend blend = surface_blend(m.chart, width_share);
  const FrameSurface surface = frame_surface(m.chart, m.frame, &blend);
  for (Index v = 0; v < static_cast<Index>(m.bind.size()); ++v)
    for (Index k = m.chart.corner_start[v]; k < m.chart.corner_start[v + 1]; ++k) {
      const Vec3 x = blended_point(surface, m.chart.corner_triangles[k], m.chart.uv[v]);
      ASSERT_LT((x - m.frame[v]).norm(), 1e-14) << "node " << v << ", blend " << width_share;
    }
}

TEST(BlendedSurface, PassesThroughEveryFrameVertex) {
  expect_through_every_frame_vertex(Bumpy(), 1.0);
}

// A needle's or a cap's band lines meet far beyond its sharp corners: its weight must still be 0
// at every node it does not touch, or the surface leaves the frame's vertices there.
TEST(BlendedSurface, PassesThroughEveryFrameVertexAmongNeedlesAndCaps) {
  double sharpest = 180;
  for (unsigned seed = 1; seed <= 40; ++seed) {
    const Bumpy m(0.42, seed);
    sharpest = std::min(sharpest, m.smallest_angle());
    for (double width_share : {0.5, 1.0, 2.0}) expect_through_every_frame_vertex(m, width_share);
  }
  EXPECT_LT(sharpest, 1.0) << "the jittered grids hold needles or caps";
}

// Seen from either side of every inner edge, the same point and the same Jacobian; returns the
// number of inner edges.
int expect_smooth_across_edges(const Bumpy& m, double width_share, bool creased = true) {
  const SurfaceBlend blend = surface_blend(m.chart, width_share);
  const FrameSurface surface = frame_surface(m.chart, m.frame, &blend);
  int inner_edges = 0;
  for (Index t = 0; t < m.chart.patch_triangle_count; ++t)
    for (int k = 0; k < 3; ++k) {
      const Index across = m.chart.neighbour[t][k];
      if (across < 0 || across >= m.chart.patch_triangle_count) continue;
      ++inner_edges;
      const Triangle& tri = m.chart.triangles[t];
      // A third of the way along the edge opposite corner k, seen from either side.
      const Vec2 u = (2 * m.chart.uv[tri[(k + 1) % 3]] + m.chart.uv[tri[(k + 2) % 3]]) / 3;
      Mat32 J_here, J_there;
      const Vec3 here = blended_point(surface, t, u, &J_here);
      const Vec3 there = blended_point(surface, across, u, &J_there);
      EXPECT_LT((here - there).norm(), 1e-14);
      EXPECT_LT((J_here - J_there).norm(), 1e-12 * J_here.norm()) << "triangle " << t;
      // The facets' own slopes jump there: the blend is what makes it smooth.
      if (creased) {
        EXPECT_GT((surface_jacobian(surface, t) - surface_jacobian(surface, across)).norm(),
                  1e-3 * J_here.norm());
      }
    }
  return inner_edges;
}

TEST(BlendedSurface, IsSmoothAcrossEdgesWhereTheFacetsCrease) {
  EXPECT_GT(expect_smooth_across_edges(Bumpy(), 1.0), 100);
}

// Its Jacobian against central differences at random points inside the triangles.
void expect_jacobian_is_derivative(const Bumpy& m, double width_share, unsigned seed) {
  const SurfaceBlend blend = surface_blend(m.chart, width_share);
  const FrameSurface surface = frame_surface(m.chart, m.frame, &blend);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.02, 0.96);
  const double h = 1e-7;
  for (int trial = 0; trial < 200; ++trial) {
    const Index t = static_cast<Index>(rng() % m.chart.patch_triangle_count);
    const double a = unit(rng), b = unit(rng) * (1 - a);
    const Vec2 u = inside(m.chart, t, a, b);
    Mat32 J;
    blended_point(surface, t, u, &J);
    Mat32 numeric;
    for (int c = 0; c < 2; ++c) {
      const Vec2 du = h * Vec2::Unit(c);
      numeric.col(c) =
          (blended_point(surface, t, u + du) - blended_point(surface, t, u - du)) / (2 * h);
    }
    EXPECT_LT((J - numeric).norm(), 1e-6 * (1 + J.norm())) << "triangle " << t;
  }
}

TEST(BlendedSurface, ItsJacobianIsItsDerivative) { expect_jacobian_is_derivative(Bumpy(), 1.0, 7); }

// Where the weights of needles and caps fade with the distance from them, it stays one smooth
// function with the Jacobian it reports.
TEST(BlendedSurface, StaysSmoothAmongNeedlesAndCaps) {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const Bumpy m(0.42, seed);
    for (double width_share : {1.0, 2.0}) {
      expect_smooth_across_edges(m, width_share, false);
      expect_jacobian_is_derivative(m, width_share, seed);
    }
  }
}

TEST(BlendedSurface, AwayFromItsBandsATriangleKeepsItsOwnPlane) {
  const Bumpy m;
  const SurfaceBlend narrow = surface_blend(m.chart, 0.2);
  const FrameSurface surface = frame_surface(m.chart, m.frame, &narrow);
  for (Index t = 0; t < m.chart.patch_triangle_count; ++t) {
    // The incentre is an inradius from every edge, beyond bands of a fifth of it.
    const Triangle& tri = m.chart.triangles[t];
    double side[3];
    for (int k = 0; k < 3; ++k)
      side[k] = (m.chart.uv[tri[(k + 1) % 3]] - m.chart.uv[tri[(k + 2) % 3]]).norm();
    const double p = side[0] + side[1] + side[2];
    const Vec2 incentre = (side[0] * m.chart.uv[tri[0]] + side[1] * m.chart.uv[tri[1]] +
                           side[2] * m.chart.uv[tri[2]]) /
                          p;
    Mat32 J;
    const Vec3 x = blended_point(surface, t, incentre, &J);
    const ChartPoint where{t, chart_barycentric(m.chart, t, incentre)};
    EXPECT_LT((x - surface_point(surface, where)).norm(), 1e-14);
    EXPECT_LT((J - surface_jacobian(surface, t)).norm(), 1e-14 * J.norm());
  }
}

// The grid of relax_test, bent over a joint, relaxed on the blended surface.
TEST(BlendedSurface, ASlideRelaxedOnItIsWrittenOnTheFramesFacets) {
  const PolyMesh mesh = test::quad_grid_with_holes(10, 10, {23, 24, 33, 34});
  ElasticOptions options = test::search_options();
  options.blend = 1;
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{options});
  const BindSetup facets =
      bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{test::search_options()});
  // relax_test's bend: the right half turned about the y axis, the skin over the joint stretched.
  Positions3 frame = mesh.positions;
  const double angle = 1.5, radius = 3.0;
  for (Vec3& p : frame) {
    const double x = p.x() - 5;
    if (x <= 0) continue;
    p = Vec3(5 + radius * std::sin(angle * x / 5) * 5 / (radius * angle) * (1 + 0.3 * std::exp(-x)),
             p.y(), radius * (1 - std::cos(angle * x / 5)) * 5 / (radius * angle));
  }
  const FrameResult r = slide_frame(setup, frame, {.edge_spread = true});
  const FrameResult on_facets = slide_frame(facets, frame, {.edge_spread = true});
  const Positions3 out = apply_slide(frame, r.slid);
  const Patch& patch = setup.patches[0];
  const PatchFrameReport& rep = r.patches[0];
  EXPECT_LE(test::elastic(rep).energy_after, test::elastic(rep).energy_before);
  EXPECT_LT(rep.spread_slid, rep.spread_frame);
  EXPECT_EQ(test::elastic(rep).slid_flips, 0);
  EXPECT_NE(out, apply_slide(frame, on_facets.slid)) << "another surface, another slide";
  for (Index lv : patch.free_vertices)
    ASSERT_LT(test::distance_to_patch(patch, frame, out[patch.vertices[lv]]),
              1e-12 * test::diagonal(frame))
        << "on the frame's facets: vertex " << patch.vertices[lv];
  for (size_t v = 0; v < out.size(); ++v) {
    bool free = false;
    for (Index lv : patch.free_vertices) free = free || patch.vertices[lv] == static_cast<Index>(v);
    if (!free) {
      EXPECT_EQ(out[v], frame[v]) << "vertex " << v;
    }
  }
}

}  // namespace
}  // namespace skinslide
