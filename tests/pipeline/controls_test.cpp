// The animator's controls (README "Controls"): slide weights, strength, pins, corners, outer
// loops, and what each density does on the sample cases.
#include <algorithm>
#include <cmath>
#include <set>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "core/error.h"
#include "helpers/meshes.h"
#include "helpers/samples.h"
#include "pipeline/bind_setup.h"
#include "pipeline/slide_frame.h"
#include "mesh/measures.h"
#include "paper/square_boundary.h"

namespace skinslide {
namespace {

using test::diagonal;
using test::load_sample;

Positions3 slid(const BindSetup& setup, const Positions3& frame) {
  return apply_slide(frame, slide_frame(setup, frame).slid);
}

using test::distance_to_patch;

std::string usage_error(const PolyMesh& bind, const std::vector<Index>& faces,
                        const SlideControls& c) {
  try {
    bind_setup(bind, {faces}, test::paper_options(), c);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage) << e.what();
    return e.what();
  }
  return "";
}

// --- weights ---------------------------------------------------------------------------------

TEST(SlideWeights, ZeroLeavesEveryFrameBitIdentical) {
  const test::Sample c = load_sample("elbow");
  SlideControls controls;
  controls.weight.assign(c.bind.vertex_count(), 0.0);
  const BindSetup setup = bind_setup(c.bind, {c.faces}, test::paper_options(), controls);
  for (const Positions3& frame : c.frames) {
    const FrameResult r = slide_frame(setup, frame);
    EXPECT_TRUE(r.slid.vertex.empty());
    EXPECT_EQ(apply_slide(frame, r.slid), frame);
  }
}

TEST(SlideWeights, OneIsTheFullSlideBitForBit) {
  const test::Sample c = load_sample("elbow");
  SlideControls controls;
  controls.weight.assign(c.bind.vertex_count(), 1.0);
  const BindSetup plain = bind_setup(c.bind, {c.faces}, test::paper_options());
  const BindSetup weighted = bind_setup(c.bind, {c.faces}, test::paper_options(), controls);
  const Positions3& frame = c.frames.back();
  EXPECT_EQ(slid(weighted, frame), slid(plain, frame));
}

TEST(SlideWeights, HalfIsTheMidpointAndStrengthScales) {
  const test::Sample c = load_sample("elbow");
  const Positions3& frame = c.frames.back();
  const double diag = diagonal(frame);
  const Positions3 full = slid(bind_setup(c.bind, {c.faces}, test::paper_options()), frame);

  SlideControls half;
  half.weight.assign(c.bind.vertex_count(), 0.5);
  const Positions3 mid = slid(bind_setup(c.bind, {c.faces}, test::paper_options(), half), frame);
  size_t moved = 0;
  for (size_t v = 0; v < frame.size(); ++v) {
    EXPECT_LT((mid[v] - 0.5 * (frame[v] + full[v])).norm(), 1e-15 * diag) << v;
    moved += full[v] != frame[v];
  }
  EXPECT_GT(moved, 200u);

  SlideControls strength;  // strength alone = a uniform weight
  strength.strength = 0.5;
  EXPECT_EQ(slid(bind_setup(c.bind, {c.faces}, test::paper_options(), strength), frame), mid);
  half.strength = 2;  // 0.5 x 2 = the full slide
  EXPECT_EQ(slid(bind_setup(c.bind, {c.faces}, test::paper_options(), half), frame), full);
  half.strength = 0;
  EXPECT_EQ(slid(bind_setup(c.bind, {c.faces}, test::paper_options(), half), frame), frame);
}

TEST(SlideWeights, APaintedMaskMovesOnlyWhereItIsPainted) {
  const test::Sample c = load_sample("elbow");
  const Positions3& frame = c.frames.back();
  const Positions3 full = slid(bind_setup(c.bind, {c.faces}, test::paper_options()), frame);
  SlideControls controls;
  controls.weight.assign(c.bind.vertex_count(), 0.0);
  for (Index v = 0; v < c.bind.vertex_count(); v += 3) controls.weight[v] = 1.0;
  const Positions3 out =
      slid(bind_setup(c.bind, {c.faces}, test::paper_options(), controls), frame);
  for (Index v = 0; v < c.bind.vertex_count(); ++v)
    EXPECT_EQ(out[v], v % 3 == 0 ? full[v] : frame[v]) << v;
}

// A weighted vertex goes part of its way in the chart, its neighbours all of theirs: between them
// a slid triangle can turn over (README rule 11). Found by a random search: an 8x8 grid on a
// smooth, unfolded frame, one vertex at weight 1/4, turned two triangles against the frame's.
TEST(SlideWeights, APartialWeightTurnsNoTriangleOver) {
  constexpr int n = 8;
  const double k[3] = {-0.64427574384245934, 0.38322606558573158, 0.21795844587147295};
  const double phase = -0.73029391185158254, amp = 0.2;
  PolyMesh bind;
  Positions3 frame;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = double(i) / n, y = double(j) / n;
      const double bump = std::sin(M_PI * x) * std::sin(M_PI * y);
      bind.positions.emplace_back(x, y, 0);
      frame.emplace_back(x + 2 * amp * k[0] * bump, y + 2 * amp * k[1] * bump,
                         amp * k[2] * std::sin(3 * x + phase));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Index a = j * (n + 1) + i;
      bind.add_face({a, a + 1, a + n + 2});
      bind.add_face({a, a + n + 2, a + n + 1});
    }
  SlideControls controls;
  controls.weight.assign(bind.vertex_count(), 1.0);
  controls.weight[40] = 0.25;
  const BindSetup setup = bind_setup(bind, {test::all_faces(bind)}, ElasticOptions{}, controls);
  const FrameResult r = slide_frame(setup, frame);
  const Positions3 out = apply_slide(frame, r.slid);
  int turned = 0;
  for (Index f = 0; f < bind.face_count(); ++f) {
    const Index* t = bind.face_begin(f);
    const Vec3 nf = (frame[t[1]] - frame[t[0]]).cross(frame[t[2]] - frame[t[0]]);
    turned += turned_against((out[t[1]] - out[t[0]]).cross(out[t[2]] - out[t[0]]), nf);
  }
  EXPECT_EQ(turned, 0);
  EXPECT_GT(r.slid.vertex.size(), 40u);  // the grid's 49 inner vertices slide, a few held
}

TEST(SlideWeights, BadWeightsAreUsageErrors) {
  const PolyMesh bind = test::quad_grid(3, 3);
  SlideControls c;
  c.weight.assign(5, 1.0);
  EXPECT_EQ(usage_error(bind, test::all_faces(bind), c),
            "there are 5 slide weights; the bind has 16 vertices");
  c.weight.assign(16, 1.0);
  c.weight[7] = 1.5;
  EXPECT_EQ(usage_error(bind, test::all_faces(bind), c),
            "vertex 7: slide weight 1.500000 is outside [0, 1]");
  c.weight.clear();
  c.strength = -1;
  EXPECT_EQ(usage_error(bind, test::all_faces(bind), c), "--strength must be a finite number >= 0");
}

// --- pins ------------------------------------------------------------------------------------

TEST(Pins, StayAtTheFramePositionWhileTheirNeighboursSlide) {
  const test::Sample c = load_sample("elbow");
  SlideControls controls;
  controls.pins = {500, 501, 502, 600, 0 /* outside the patch */, 352 /* on the border */};
  const BindSetup setup = bind_setup(c.bind, {c.faces}, test::paper_options(), controls);
  const Patch& patch = setup.patches.at(0);
  EXPECT_EQ(patch.pinned.size(), 4u);
  EXPECT_EQ(setup.pins_ignored, 2);
  EXPECT_EQ(patch.free_vertices.size(), 288u - 4u);
  EXPECT_EQ(flipped_triangles(patch.bind_net, patch.triangles), 0);

  const std::set<Index> pins{500, 501, 502, 600};
  std::set<Index> neighbours;
  for (const auto& [a, b] : patch.bars) {
    const Index u = patch.vertices[a], v = patch.vertices[b];
    if (pins.count(u) && !pins.count(v)) neighbours.insert(v);
    if (pins.count(v) && !pins.count(u)) neighbours.insert(u);
  }
  ASSERT_GE(neighbours.size(), 8u);
  for (size_t f = 2; f < c.frames.size(); ++f) {
    const Positions3& frame = c.frames[f];
    const double diag = diagonal(frame);
    const FrameResult r = slide_frame(setup, frame);
    EXPECT_EQ(flipped_triangles(r.patches[0].frame_net, patch.triangles), 0) << f;
    for (Index lv : patch.pinned) EXPECT_EQ(r.patches[0].frame_net[lv], patch.bind_net[lv]);
    const Positions3 out = apply_slide(frame, r.slid);
    for (Index v : pins) EXPECT_EQ(out[v], frame[v]) << "pin " << v << ", frame " << f;
    double moved = 0;
    for (Index v : neighbours) {
      moved = std::max(moved, (out[v] - frame[v]).norm());
      EXPECT_LT(distance_to_patch(patch, frame, out[v]), 1e-9 * diag) << v;
    }
    EXPECT_GT(moved, 1e-3 * diag) << "the skin around the pins still slides, frame " << f;
  }
}

TEST(Pins, APinOnAHalfStretchedSheetHoldsTheSheet) {
  // The sheet of slide_frame_test: without pins vertex (4,4) slides right; pinned it stays.
  const PolyMesh bind = test::quad_grid(8, 8);
  Positions3 frame = bind.positions;
  for (Vec3& p : frame)
    if (p.x() > 4) p.x() = 4 + 2 * (p.x() - 4);
  const Index centre = 4 * 9 + 4;
  SlideControls controls;
  controls.pins = {centre};
  const Positions3 free_out =
      slid(bind_setup(bind, {test::all_faces(bind)}, test::paper_options()), frame);
  const Positions3 out =
      slid(bind_setup(bind, {test::all_faces(bind)}, test::paper_options(), controls), frame);
  EXPECT_GT(free_out[centre].x(), frame[centre].x());
  EXPECT_EQ(out[centre], frame[centre]);
  EXPECT_GT(out[centre + 9].x(), frame[centre + 9].x()) << "the vertex above still slides right";
}

TEST(Pins, AnIdPastTheLastVertexIsAUsageError) {
  const PolyMesh bind = test::quad_grid(3, 3);
  SlideControls c;
  c.pins = {16};
  EXPECT_EQ(usage_error(bind, test::all_faces(bind), c),
            "--pin: vertex 16 is out of range (the bind has 16 vertices, numbered 0 to 15)");
}

// --- corners and the outer loop ----------------------------------------------------------------

TEST(ChosenCorners, SquarePositionsFollowTheChosenCorners) {
  // A 4 x 4 square walked from (0,0): corners at loop positions 1, 5, 9, 13, sides of length 4.
  const PolyMesh grid = test::quad_grid(4, 4);
  const std::vector<Index> loop{0, 1, 2, 3, 4, 9, 14, 19, 24, 23, 22, 21, 20, 15, 10, 5};
  Positions3 points;
  for (Index v : loop) points.push_back(grid.positions[v]);
  const SquareBoundary s = square_positions(points, {1, 5, 9, 13});
  EXPECT_EQ(s.positions[1], Vec2(0, 0));
  EXPECT_EQ(s.positions[3], Vec2(0.5, 0));
  EXPECT_EQ(s.positions[5], Vec2(1, 0));
  EXPECT_EQ(s.positions[9], Vec2(1, 1));
  EXPECT_EQ(s.positions[13], Vec2(0, 1));
  EXPECT_EQ(s.positions[0], Vec2(0, 0.25));  // 3/4 along the side from (0,1) back to (0,0)
  EXPECT_THROW(square_positions(points, {1, 9, 5, 13}), Error);
  EXPECT_THROW(square_positions(points, {1, 1, 5, 13}), Error);
}

TEST(ChosenCorners, PutTheNamedVerticesOnTheSquaresCorners) {
  const PolyMesh bind = test::quad_grid(4, 4);
  SlideControls c;
  c.corners = {{1, 9, 23, 15}};
  const BindSetup setup = bind_setup(bind, {test::all_faces(bind)}, test::paper_options(), c);
  const Patch& p = setup.patches.at(0);
  const PaperSetup& paper = test::paper(setup).patches.at(0);
  EXPECT_TRUE(paper.corners_chosen);
  const Vec2 square[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int j = 0; j < 4; ++j) {
    EXPECT_EQ(p.vertices[paper.corners[j]], c.corners[0][j]);
    EXPECT_EQ(p.bind_net[paper.corners[j]], square[j]);
  }
  EXPECT_EQ(p.bind_net[0], Vec2(0, 0.25));
  // Corners off the mesh's own corners lay two fan triangles, (3,4,9) and (15,21,20), flat along
  // a side of the square: zero area, counted by flipped_triangles; nothing else folds.
  EXPECT_EQ(flipped_triangles(p.bind_net, p.triangles), 2);
  // The automatic choice differs: vertex 0 is its (0,0), and nothing is flat.
  const BindSetup automatic = bind_setup(bind, {test::all_faces(bind)}, test::paper_options());
  EXPECT_EQ(automatic.patches[0].bind_net[0], Vec2(0, 0));
  EXPECT_EQ(flipped_triangles(automatic.patches[0].bind_net, automatic.patches[0].triangles), 0);
}

TEST(ChosenCorners, ErrorsNameTheBadVertex) {
  const PolyMesh bind = test::quad_grid(4, 4);
  const std::vector<Index> faces = test::all_faces(bind);
  SlideControls c;
  c.corners = {{1, 15, 23, 9}};
  EXPECT_EQ(usage_error(bind, faces, c),
            "patch 0 (face 0, 16 faces): --corners 1,15,23,9: the corners are not in the loop's "
            "walking order; walking from 1 the loop meets them as 1,9,23,15");
  c.corners = {{1, 9, 12, 15}};
  EXPECT_EQ(usage_error(bind, faces, c),
            "--corners 1,9,12,15: vertex 12 is not on the boundary loop through vertex 1; the four "
            "corners go on one loop");
  c.corners = {{6, 9, 23, 15}};
  EXPECT_EQ(usage_error(bind, faces, c),
            "--corners 6,9,23,15: vertex 6 is not on a boundary loop of any patch");
  c.corners = {{1, 9, 99, 15}};
  EXPECT_EQ(usage_error(bind, faces, c),
            "--corners 1,9,99,15: vertex 99 is out of range (the bind has 25 vertices, numbered 0 "
            "to 24)");
  c.corners = {{1, 9, 9, 15}};
  EXPECT_EQ(usage_error(bind, faces, c), "--corners 1,9,9,15: vertex 9 is named twice");
  c.corners = {{1, 9, 23, 15}, {0, 4, 24, 20}};
  EXPECT_EQ(usage_error(bind, faces, c),
            "patch 0: --corners 1,9,23,15 and --corners 0,4,24,20 choose different outer loops or "
            "corners for it");
}

TEST(ChosenOuterLoop, TheElbowsOtherEndOnTheSquareSlidesWithoutFolds) {
  const test::Sample c = load_sample("elbow");
  SlideControls controls;
  controls.outer_loop_vertices = {680};  // on the ring 672..703, the automatic choice is 352..383
  const BindSetup automatic = bind_setup(c.bind, {c.faces}, test::paper_options());
  const BindSetup setup = bind_setup(c.bind, {c.faces}, test::paper_options(), controls);
  const Patch& p = setup.patches.at(0);
  EXPECT_TRUE(p.outer_loop_chosen);
  EXPECT_EQ(p.vertices[automatic.patches[0].loops[automatic.patches[0].outer_loop].front()], 352);
  EXPECT_EQ(p.vertices[p.loops[p.outer_loop].front()], 672);
  EXPECT_EQ(p.vertices[test::paper(setup).patches[0].corners[0]], 672);
  EXPECT_EQ(flipped_triangles(p.bind_net, p.triangles), 0);
  for (const Positions3& frame : c.frames) {
    const FrameResult r = slide_frame(setup, frame);
    EXPECT_EQ(flipped_triangles(r.patches[0].frame_net, p.triangles), 0);
    const Positions3 out = apply_slide(frame, r.slid);
    for (Index lv : p.free_vertices)
      ASSERT_LT(distance_to_patch(p, frame, out[p.vertices[lv]]), 1e-9 * diagonal(frame));
  }
  controls.outer_loop_vertices = {400};
  EXPECT_EQ(usage_error(c.bind, c.faces, controls),
            "--outer-loop-vertex 400: vertex 400 is not on a boundary loop of any patch");
  controls.outer_loop_vertices = {680};
  controls.corners = {{356, 364, 372, 380}};
  EXPECT_EQ(usage_error(c.bind, c.faces, controls),
            "patch 0: --outer-loop-vertex 680 and --corners 356,364,372,380 choose different outer "
            "loops or corners for it");
}

TEST(ChosenOuterLoop, AHoleOfASheetCanCarryTheSquare) {
  const PolyMesh bind = test::quad_grid_with_holes(6, 6, {14, 15, 20, 21});  // a 2x2 hole
  SlideControls controls;
  controls.outer_loop_vertices = {16};  // a corner of the hole
  const BindSetup setup =
      bind_setup(bind, {test::all_faces(bind)}, test::paper_options(), controls);
  const Patch& p = setup.patches.at(0);
  const auto& outer = p.loops[p.outer_loop];
  EXPECT_EQ(outer.size(), 8u);
  const Index local16 = static_cast<Index>(
      std::lower_bound(p.vertices.begin(), p.vertices.end(), 16) - p.vertices.begin());
  EXPECT_NE(std::find(outer.begin(), outer.end(), local16), outer.end());
  EXPECT_EQ(flipped_triangles(p.bind_net, p.triangles), 0);
}

// --- density ---------------------------------------------------------------------------------

// Frame-net folds per density on the samples, as README "Choosing the defaults" reports them:
// `paper` folds the elbow once it bends (its longest bars sit on the q floor), every other
// setting is fold-free on both samples.
TEST(Density, FoldFreeFrameNetsWhereReadmeSaysSo) {
  for (const std::string name : {"elbow", "face"}) {
    const test::Sample c = load_sample(name);
    for (Density d : {Density::Paper, Density::Inverse, Density::Uniform}) {
      PaperOptions o;
      o.density = d;
      const BindSetup setup = bind_setup(c.bind, {c.faces}, o);
      for (const Patch& p : setup.patches) EXPECT_EQ(flipped_triangles(p.bind_net, p.triangles), 0);
      int folds_in_bent_frames = 0;
      for (size_t f = 0; f < c.frames.size(); ++f) {
        const FrameResult r = slide_frame(setup, c.frames[f]);
        for (size_t p = 0; p < setup.patches.size(); ++p) {
          const int flips = flipped_triangles(r.patches[p].frame_net, setup.patches[p].triangles);
          if (f > 0) folds_in_bent_frames += flips > 0;
          if (f == 0) {
            EXPECT_EQ(flips, 0) << name << " " << to_string(d) << ": the first frame is the bind";
          }
        }
      }
      const bool folds = name == std::string("elbow") && d == Density::Paper;
      if (folds)
        EXPECT_EQ(folds_in_bent_frames, static_cast<int>(c.frames.size()) - 1) << name;
      else
        EXPECT_EQ(folds_in_bent_frames, 0) << name << " " << to_string(d);
    }
  }
}

// The report's spreads, checked against a direct computation of std log(L / L_bind).
TEST(Spread, PatchReportMatchesADirectComputation) {
  const test::Sample c = load_sample("elbow");
  const BindSetup setup = bind_setup(c.bind, {c.faces}, test::paper_options());
  const Patch& patch = setup.patches[0];
  auto spread = [&](const Positions3& x) {
    std::vector<double> r;
    for (const auto& [a, b] : patch.bars) {
      const Index u = patch.vertices[a], v = patch.vertices[b];
      r.push_back(
          std::log((x[u] - x[v]).norm() / (c.bind.positions[u] - c.bind.positions[v]).norm()));
    }
    double mean = 0, var = 0;
    for (double v : r) mean += v;
    mean /= static_cast<double>(r.size());
    for (double v : r) var += (v - mean) * (v - mean);
    return std::sqrt(var / static_cast<double>(r.size()));
  };
  const Positions3& frame = c.frames.back();
  const FrameResult r = slide_frame(setup, frame, {.edge_spread = true});
  EXPECT_NEAR(r.patches[0].spread_frame, spread(frame), 1e-12);
  EXPECT_NEAR(r.patches[0].spread_slid, spread(apply_slide(frame, r.slid)), 1e-12);
  EXPECT_LT(r.patches[0].spread_slid, r.patches[0].spread_frame);
  EXPECT_EQ(r.patches[0].moved, 288);
}

}  // namespace
}  // namespace skinslide
