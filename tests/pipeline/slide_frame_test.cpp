// Properties of the whole pipeline on the shipped sample cases (data/) and hand-built meshes.
#include "pipeline/slide_frame.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <random>

#include <gtest/gtest.h>

#include "core/error.h"
#include "helpers/meshes.h"
#include "helpers/samples.h"
#include "io/obj_read.h"
#include "io/patch_file.h"
#include "mesh/measures.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

using test::diagonal;
using test::distance_to_patch;
using test::edge_log_spread;

struct Mode {
  Density density;
  Holes holes;
};

class SampleCases : public ::testing::TestWithParam<std::string> {};

TEST_P(SampleCases, DefaultSlideKeepsTheInvariants) {
  const test::Sample c = test::load_sample(GetParam());
  const BindSetup setup = bind_setup(c.bind, {c.faces}, SlideOptions{});
  ASSERT_FALSE(setup.patches.empty());
  for (const Patch& p : setup.patches) EXPECT_EQ(flipped_triangles(p.bind_net, p.triangles), 0);
  for (size_t f = 0; f < c.frames.size(); ++f) {
    const Positions3& frame = c.frames[f];
    const FrameResult r = slide_frame(setup, frame);
    const Positions3 out = apply_slide(frame, r.slid);
    const double diag = diagonal(frame);
    std::vector<char> free(frame.size(), 0);
    for (const Patch& p : setup.patches)
      for (Index v : p.free_vertices) free[p.vertices[v]] = 1;
    for (size_t v = 0; v < frame.size(); ++v) {
      ASSERT_TRUE(out[v].allFinite());
      if (!free[v]) {
        EXPECT_EQ(out[v], frame[v]) << "border, hole and outside vertices stay";
      }
    }
    EXPECT_TRUE(std::is_sorted(r.slid.vertex.begin(), r.slid.vertex.end()));
    for (size_t p = 0; p < setup.patches.size(); ++p) {
      const Patch& patch = setup.patches[p];
      EXPECT_EQ(flipped_triangles(r.patches[p].frame_net, patch.triangles), 0) << "frame " << f;
      EXPECT_LE(test::elastic(r.patches[p]).energy_after,
                test::elastic(r.patches[p]).energy_before);
      // Every slid vertex lies on the frame's patch surface.
      for (Index lv : patch.free_vertices)
        ASSERT_LT(distance_to_patch(patch, frame, out[patch.vertices[lv]]), 1e-9 * diag)
            << "vertex " << patch.vertices[lv];
    }
  }
}

TEST_P(SampleCases, AnIdentityFrameComesOutUnchanged) {
  const test::Sample c = test::load_sample(GetParam());
  std::vector<std::pair<std::string, SlideOptions>> methods = {{"elastic", ElasticOptions{}}};
  for (Mode m : {Mode{Density::Inverse, Holes::Fill}, Mode{Density::Uniform, Holes::Fill},
                 Mode{Density::Paper, Holes::Fill}}) {
    PaperOptions o;
    o.density = m.density;
    o.holes = m.holes;
    methods.emplace_back("paper, density " + to_string(m.density), o);
  }
  for (const auto& [name, options] : methods) {
    const BindSetup setup = bind_setup(c.bind, {c.faces}, options);
    const FrameResult r = slide_frame(setup, c.bind.positions);
    const Positions3 out = apply_slide(c.bind.positions, r.slid);
    const double diag = diagonal(c.bind.positions);
    for (size_t v = 0; v < out.size(); ++v)
      ASSERT_LT((out[v] - c.bind.positions[v]).norm(), 1e-12 * diag) << name;
  }
}

TEST_P(SampleCases, TheSameInputsGiveTheSameBits) {
  const test::Sample c = test::load_sample(GetParam());
  const BindSetup a = bind_setup(c.bind, {c.faces}, SlideOptions{});
  const BindSetup b = bind_setup(c.bind, {c.faces}, SlideOptions{});
  const Positions3& frame = c.frames.back();
  const FrameResult ra = slide_frame(a, frame);
  const FrameResult rb = slide_frame(b, frame);
  const FrameResult ra2 = slide_frame(a, frame);
  EXPECT_EQ(ra.slid.vertex, rb.slid.vertex);
  EXPECT_EQ(ra.slid.position, rb.slid.position);
  EXPECT_EQ(ra.slid.position, ra2.slid.position);
}

INSTANTIATE_TEST_SUITE_P(Data, SampleCases, ::testing::Values("elbow", "face"));

TEST(SlideFrame, SlidingEvensOutTheElbowsStretch) {
  // Frames 3..5 bend the elbow 45, 67.5 and 90 degrees. (At 22.5 degrees, frame 2, the default
  // setting leaves the spread 1.8% wider than the frame's: README "Choosing the defaults".)
  const test::Sample c = test::load_sample("elbow");
  const BindSetup setup = bind_setup(c.bind, {c.faces}, SlideOptions{});
  const Patch& patch = setup.patches.at(0);
  for (size_t f = 2; f < c.frames.size(); ++f) {
    const Positions3 out = apply_slide(c.frames[f], slide_frame(setup, c.frames[f]).slid);
    const double before = edge_log_spread(patch, c.bind.positions, c.frames[f]);
    const double after = edge_log_spread(patch, c.bind.positions, out);
    EXPECT_LT(after, before) << "frame " << f;
  }
}

TEST(SlideFrame, AHalfStretchedSheetSlidesTowardsTheStretchedSide) {
  // An 8x8 grid whose right half is stretched 2x in x: interior vertices slide right (towards
  // the stretch), stay in the plane, and the spread of edge lengths shrinks; the border stays.
  const PolyMesh bind = test::quad_grid(8, 8);
  Positions3 frame = bind.positions;
  for (Vec3& p : frame)
    if (p.x() > 4) p.x() = 4 + 2 * (p.x() - 4);
  const BindSetup setup = bind_setup(bind, {test::all_faces(bind)}, SlideOptions{});
  const FrameResult r = slide_frame(setup, frame);
  ASSERT_EQ(r.slid.vertex.size(), 49u);
  for (size_t k = 0; k < r.slid.vertex.size(); ++k) {
    const Index v = r.slid.vertex[k];
    if (bind.positions[v].x() == 4) {
      EXPECT_GT(r.slid.position[k].x(), frame[v].x()) << v;
    }
    EXPECT_EQ(r.slid.position[k].z(), 0.0);
  }
  const Positions3 out = apply_slide(frame, r.slid);
  EXPECT_LT(edge_log_spread(setup.patches[0], bind.positions, out),
            edge_log_spread(setup.patches[0], bind.positions, frame));
}

// Runs `frame` through `setup` and checks what degenerate input must never break: every output
// finite, outside and border vertices untouched, every slid vertex on the frame's patch surface.
void expect_finite_and_on_surface(const BindSetup& setup, const Positions3& frame,
                                  const std::string& what) {
  SCOPED_TRACE(what);
  const FrameResult r = slide_frame(setup, frame);
  const Positions3 out = apply_slide(frame, r.slid);
  const double diag = diagonal(frame);
  for (const Vec3& x : out) ASSERT_TRUE(x.allFinite());
  for (const Patch& patch : setup.patches) {
    if (patch.skipped) continue;
    std::vector<char> free(patch.vertices.size(), 0);
    for (Index lv : patch.free_vertices) free[lv] = 1;
    for (size_t lv = 0; lv < patch.vertices.size(); ++lv)
      if (!free[lv]) {
        EXPECT_EQ(out[patch.vertices[lv]], frame[patch.vertices[lv]]);
      }
    for (Index lv : patch.free_vertices)
      ASSERT_LE(distance_to_patch(patch, frame, out[patch.vertices[lv]]), 1e-9 * diag)
          << "vertex " << patch.vertices[lv];
  }
}

TEST(SlideFrame, DegenerateFramesGiveFiniteVerticesOnTheFrameSurface) {
  // 6x6 quads, vertex (i, j) = 7 j + i; all faces slide, the 25 interior vertices are free.
  const PolyMesh bind = test::quad_grid(6, 6);
  const BindSetup setup = bind_setup(bind, {test::all_faces(bind)}, SlideOptions{});
  auto id = [](int i, int j) { return static_cast<Index>(7 * j + i); };

  Positions3 frame = bind.positions;
  frame[id(3, 3)] = frame[id(4, 3)];  // a zero-length edge, four zero-area fan triangles
  expect_finite_and_on_surface(setup, frame, "one edge collapsed");

  frame = bind.positions;
  for (int i = 0; i <= 6; ++i) frame[id(i, 3)].y() = frame[id(i, 2)].y();  // a row of flat quads
  expect_finite_and_on_surface(setup, frame, "a row of faces of zero area");

  frame = bind.positions;
  frame[id(3, 3)] = Vec3(5.5, 1.5, 0.3);  // pulled across its neighbours: folded triangles
  expect_finite_and_on_surface(setup, frame, "a vertex pulled across its neighbours");

  frame = bind.positions;
  for (int j = 0; j <= 6; ++j)
    for (int i = 0; i <= 3; ++i) frame[id(i, j)] = Vec3(1, 1, 1);  // half the sheet on a point
  expect_finite_and_on_surface(setup, frame, "half the sheet collapsed to a point");

  frame = bind.positions;
  for (int j = 1; j <= 5; ++j)
    for (int i = 1; i <= 5; ++i) frame[id(i, j)] = frame[id(6 - i, 6 - j)];  // interior turned
  expect_finite_and_on_surface(setup, frame,
                               "the interior rotated half a turn (folded inside out)");

  std::mt19937 rng(0);
  std::uniform_real_distribution<double> jitter(-0.9, 0.9);
  frame = bind.positions;
  for (Vec3& p : frame) p += Vec3(jitter(rng), jitter(rng), jitter(rng));
  for (int k = 0; k < 10; ++k) frame[id(1 + k % 5, 1 + k / 5)] = frame[id(2, 2)];
  expect_finite_and_on_surface(setup, frame, "seeded jitter with ten vertices on one point");
}

TEST(SlideFrame, DegenerateBindsGiveFiniteVerticesOnTheFrameSurface) {
  const PolyMesh grid = test::quad_grid(6, 6);
  auto id = [](int i, int j) { return static_cast<Index>(7 * j + i); };
  Positions3 frame = grid.positions;
  for (Vec3& p : frame) p = Vec3(1.5 * p.x(), p.y(), 0.1 * p.x() * p.x());  // stretched and bent

  PolyMesh bind = grid;
  bind.positions[id(3, 3)] = bind.positions[id(4, 3)];  // a zero-length edge in the bind
  expect_finite_and_on_surface(bind_setup(bind, {test::all_faces(bind)}, SlideOptions{}), frame,
                               "bind with a zero-length edge");

  bind = grid;
  for (int i = 0; i <= 6; ++i) bind.positions[id(i, 3)].y() = bind.positions[id(i, 2)].y();
  expect_finite_and_on_surface(bind_setup(bind, {test::all_faces(bind)}, SlideOptions{}), frame,
                               "bind with a row of zero-area faces");

  bind = grid;
  for (Vec3& p : bind.positions) p.y() = 0;  // the whole bind on a line
  expect_finite_and_on_surface(bind_setup(bind, {test::all_faces(bind)}, SlideOptions{}), frame,
                               "bind collapsed to a line");
}

// Two patches side by side on a row-major grid: their vertex ids interleave row by row. The slid
// list still comes out ascending, each vertex with its own sample and position.
TEST(SlideFrame, InterleavedPatchesGiveOneAscendingList) {
  const int n = 12, m = 8;
  const PolyMesh grid = test::quad_grid(n, m);
  std::vector<Index> left, right;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) (i < n / 2 ? left : right).push_back(j * n + i);
  const BindSetup setup = bind_setup(grid, {left, right}, SlideOptions{});
  ASSERT_EQ(setup.patches.size(), 2u);
  Positions3 frame = grid.positions;
  for (Vec3& p : frame) p = Vec3(p[0] * (1 + 0.05 * p[1]), p[1], 0.1 * p[0] * p[0]);
  const FrameResult r = slide_frame(setup, frame);
  ASSERT_EQ(r.slid.vertex.size(),
            setup.patches[0].free_vertices.size() + setup.patches[1].free_vertices.size());
  EXPECT_TRUE(std::adjacent_find(r.slid.vertex.begin(), r.slid.vertex.end(),
                                 std::greater_equal<Index>()) == r.slid.vertex.end());
  for (size_t k = 0; k < r.slid.vertex.size(); ++k)
    EXPECT_EQ(surface_point(grid, frame, r.slid.sample[k]), r.slid.position[k])
        << "vertex " << r.slid.vertex[k];
}

TEST(SlideFrame, AWrongVertexCountIsAnInputError) {
  const PolyMesh bind = test::quad_grid(3, 3);
  const BindSetup setup = bind_setup(bind, {test::all_faces(bind)}, SlideOptions{});
  Positions3 frame = bind.positions;
  frame.pop_back();
  EXPECT_THROW(slide_frame(setup, frame), Error);
}

TEST(SlideFrame, APatchWithOnlyBoundaryVerticesIsSkipped) {
  const PolyMesh bind = test::quad_grid(3, 1);
  const BindSetup setup = bind_setup(bind, {test::all_faces(bind)}, SlideOptions{});
  ASSERT_EQ(setup.patches.size(), 1u);
  EXPECT_TRUE(setup.patches[0].skipped);
  EXPECT_TRUE(slide_frame(setup, bind.positions).slid.vertex.empty());
}

TEST(SlideFrame, AStrayTriangleBesideAPatchReportsItsSpreads) {
  // A selection of one face has every vertex on its loop: nothing slides there, and its edge
  // spreads are the frame's, for either method (they read the bind's bar lengths).
  const test::Sample c = test::load_sample("elbow");
  std::vector<std::pair<std::string, SlideOptions>> methods = {{"elastic", ElasticOptions{}},
                                                               {"paper", PaperOptions{}}};
  for (const auto& [name, options] : methods) {
    const BindSetup setup = bind_setup(c.bind, {c.faces, {1000}}, options);
    ASSERT_EQ(setup.patches.size(), 2u) << name;
    ASSERT_TRUE(setup.patches[1].skipped) << name;
    const Positions3& frame = c.frames.back();
    const FrameResult r = slide_frame(setup, frame, {.edge_spread = true});
    ASSERT_EQ(r.patches.size(), 2u) << name;
    const Patch& stray = setup.patches[1];
    EXPECT_EQ(stray.bind_lengths.size(), stray.bars.size()) << name;
    EXPECT_EQ(r.patches[1].moved, 0) << name;
    const double spread = edge_log_spread(stray, c.bind.positions, frame);
    EXPECT_NEAR(r.patches[1].spread_frame, spread, 1e-12) << name;
    EXPECT_NEAR(r.patches[1].spread_slid, spread, 1e-12) << name;
    EXPECT_GT(r.patches[0].spread_frame, r.patches[0].spread_slid) << name;
  }
}

}  // namespace
}  // namespace skinslide
