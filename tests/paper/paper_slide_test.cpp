// The paper method on its own (paper/paper_slide.h): its set-up and its slide of one hand-made
// patch, the 2 x 2 grid of unit quads, whose one free vertex has nets solvable by hand.
#include "paper/paper_slide.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"

namespace skinslide {
namespace {

// The 2 x 2 grid of unit quads (vertex j*3+i at (i, j, 0), quads counter-clockwise from +z) as
// the shared set-up makes it a patch: the middle vertex 4 free, the border the loop
// 0 1 2 5 8 7 6 3 (from its smallest vertex, the way its faces run it), every bar of length 1.
Patch grid_patch() {
  Patch p;
  p.faces = {0, 1, 2, 3};
  p.vertices = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  p.bars = {{0, 1}, {0, 3}, {1, 2}, {1, 4}, {2, 5}, {3, 4},
            {3, 6}, {4, 5}, {4, 7}, {5, 8}, {6, 7}, {7, 8}};
  p.triangles = {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4},
                 {3, 4, 7}, {3, 7, 6}, {4, 5, 8}, {4, 8, 7}};
  p.triangle_face = {0, 0, 1, 1, 2, 2, 3, 3};
  p.triangle_fan = {0, 1, 0, 1, 0, 1, 0, 1};
  p.loops = {{0, 1, 2, 5, 8, 7, 6, 3}};
  p.free_vertices = {4};
  p.bind_lengths.assign(p.bars.size(), 1.0);
  p.bind_diagonal = std::sqrt(8.0);
  return p;
}

Positions3 grid_points() {
  Positions3 points;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) points.emplace_back(i, j, 0);
  return points;
}

// The grid with its right column (vertices 2, 5, 8) moved from x = 2 to x = 3: the bars 1-2, 4-5
// and 7-8 stretched to length 2.
Positions3 stretched_points() {
  Positions3 points = grid_points();
  for (Index v : {2, 5, 8}) points[v].x() = 3;
  return points;
}

TEST(PaperSetup, TheBorderGoesOnTheSquareAtItsQuarterLengthsAndTheMiddleInEquilibrium) {
  Patch patch = grid_patch();
  const PaperSetup setup = paper_setup(patch, grid_points(), PaperOptions{}, {}, false);
  // Loop 0 1 2 5 8 7 6 3 of eight unit edges: the corners at arc lengths 0, 2, 4, 6.
  EXPECT_EQ(setup.corners, (std::array<Index, 4>{0, 2, 8, 6}));
  EXPECT_FALSE(setup.corners_chosen);
  const Positions2 square{{0, 0},   {0.5, 0}, {1, 0},   {0, 0.5}, {0.5, 0.5},
                          {1, 0.5}, {0, 1},   {0.5, 1}, {1, 1}};
  ASSERT_EQ(patch.bind_net.size(), 9u);
  for (Index v = 0; v < 9; ++v) EXPECT_EQ(patch.bind_net[v], square[v]) << "vertex " << v;
  EXPECT_EQ(patch.bind_net_flips, 0);
  ASSERT_TRUE(setup.solver);
  EXPECT_EQ(setup.solver->method(), FrameNetMethod::Cholesky);  // 1 free node: auto's Cholesky
  EXPECT_EQ(setup.solver->free_node_count(), 1);
}

TEST(PaperSetup, ChosenCornersGoWhereTheyAreNamedAndMustFollowTheLoop) {
  Patch patch = grid_patch();
  const CornerChoice turned{true, {2, 8, 6, 0}, "--corners 2,8,6,0"};
  const PaperSetup setup = paper_setup(patch, grid_points(), PaperOptions{}, turned, false);
  EXPECT_EQ(setup.corners, (std::array<Index, 4>{2, 8, 6, 0}));
  EXPECT_TRUE(setup.corners_chosen);
  EXPECT_EQ(patch.bind_net[2], Vec2(0, 0));
  EXPECT_EQ(patch.bind_net[8], Vec2(1, 0));
  EXPECT_EQ(patch.bind_net[4], Vec2(0.5, 0.5));
  Patch again = grid_patch();
  const CornerChoice backwards{true, {0, 6, 8, 2}, "--corners 0,6,8,2"};
  try {
    paper_setup(again, grid_points(), PaperOptions{}, backwards, false);
    FAIL() << "corners against the loop's walking order";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("--corners 0,6,8,2: the corners are not in the loop's "
                                         "walking order; walking from 0 the loop meets them as "
                                         "0,2,8,6"),
              std::string::npos)
        << e.what();
  }
}

TEST(PaperSlide, TheBindAsAFrameKeepsTheBindNetAndSlidesNothing) {
  Patch patch = grid_patch();
  const Positions3 bind = grid_points();
  const PaperSetup setup = paper_setup(patch, bind, PaperOptions{}, {}, false);
  const PaperSlide s = paper_slide(setup, patch, bind, {}, PaperOptions{});
  EXPECT_EQ(s.slid.net, patch.bind_net) << "the warm start meets the tolerance: kept";
  EXPECT_EQ(s.report.cg_iterations, 0);
  EXPECT_FALSE(s.report.direct_solve);
  EXPECT_EQ(s.report.located_in_image, 1);
  EXPECT_EQ(s.report.located_fallback, 0);
  EXPECT_EQ(s.report.frame_net_flips, 0);
  ASSERT_EQ(s.slid.vertex, std::vector<Index>{4});
  EXPECT_EQ(s.slid.position[0], bind[4]);
  EXPECT_EQ(s.slid.placed, 1);
}

TEST(PaperSlide, AStretchedBarPullsTheMiddleWhereTheHandSolutionPutsIt) {
  Patch patch = grid_patch();
  const PaperSetup setup = paper_setup(patch, grid_points(), PaperOptions{}, {}, false);
  const Positions3 frame = stretched_points();
  const PaperSlide s = paper_slide(setup, patch, frame, {}, PaperOptions{});
  // Inverse density, q = Lmin / L: the stretched bar 4-5 has q = 1/2, the others around the
  // middle 1. The middle of the frame net sits at the q-weighted mean of 1 (0.5, 0), 3 (0, 0.5),
  // 5 (1, 0.5), 7 (0.5, 1): x = (0.5 + 0 + 0.5 * 1 + 0.5) / 3.5 = 3/7, y = 1/2.
  EXPECT_NEAR(s.slid.net[4].x(), 3.0 / 7.0, 1e-15);
  EXPECT_NEAR(s.slid.net[4].y(), 0.5, 1e-15);
  for (Index v : patch.loops[0]) EXPECT_EQ(s.slid.net[v], patch.bind_net[v]) << "border fixed";
  // The middle's bind point (0.5, 0.5) lies on the frame net's edge 4-5, 1/8 of the way from 4:
  // on the frame, 7/8 (1, 1, 0) + 1/8 (3, 1, 0).
  ASSERT_EQ(s.slid.vertex, std::vector<Index>{4});
  EXPECT_NEAR(s.slid.position[0].x(), 1.25, 1e-14);
  EXPECT_NEAR(s.slid.position[0].y(), 1.0, 1e-14);
  EXPECT_EQ(s.slid.position[0].z(), 0.0);
  EXPECT_EQ(s.report.frame_net_flips, 0);
  EXPECT_EQ(s.report.located_fallback, 0);
}

TEST(PaperSlide, AWeightGoesThatShareOfTheWayAndZeroWritesNothing) {
  Patch patch = grid_patch();
  const PaperSetup setup = paper_setup(patch, grid_points(), PaperOptions{}, {}, false);
  const Positions3 frame = stretched_points();
  std::vector<double> weight(9, 1.0);
  weight[4] = 0.5;
  const PaperSlide half = paper_slide(setup, patch, frame, weight, PaperOptions{});
  ASSERT_EQ(half.slid.vertex.size(), 1u);
  EXPECT_NEAR(half.slid.position[0].x(), 1.125, 1e-14) << "halfway from (1, 1, 0) to (1.25, 1, 0)";
  weight[4] = 0;
  const PaperSlide none = paper_slide(setup, patch, frame, weight, PaperOptions{});
  EXPECT_TRUE(none.slid.vertex.empty()) << "weight 0: the frame's own position, not rewritten";
  EXPECT_EQ(none.slid.placed, 1) << "placed all the same: the mean slide counts it";
}

TEST(PaperSlide, UniformDensityIgnoresLengthsSoTheGridSlidesNothing) {
  PaperOptions uniform;
  uniform.density = Density::Uniform;
  Patch patch = grid_patch();
  const PaperSetup setup = paper_setup(patch, grid_points(), uniform, {}, false);
  const Positions3 frame = stretched_points();
  const PaperSlide s = paper_slide(setup, patch, frame, {}, uniform);
  EXPECT_EQ(s.slid.net, patch.bind_net);
  ASSERT_EQ(s.slid.vertex, std::vector<Index>{4});
  EXPECT_EQ(s.slid.position[0], frame[4]);
}

TEST(PaperSlide, TheImageAndTheWalkLocateTheSamePoint) {
  PaperOptions by_image;
  by_image.locate = Locate::Image;
  by_image.lookup_size = 64;
  Patch patch = grid_patch();
  const PaperSetup setup = paper_setup(patch, grid_points(), by_image, {}, false);
  const Positions3 frame = stretched_points();
  const PaperSlide image = paper_slide(setup, patch, frame, {}, by_image, 64);
  const PaperSlide walk = paper_slide(setup, patch, frame, {}, PaperOptions{});
  ASSERT_EQ(image.slid.vertex, walk.slid.vertex);
  EXPECT_NEAR((image.slid.position[0] - walk.slid.position[0]).norm(), 0.0, 1e-14);
  EXPECT_EQ(image.report.located_in_image, 1);
  EXPECT_EQ(image.slid.id_image.size, 64) << "kept when asked for";
}

TEST(PaperSlide, EveryFrameSolverFindsTheHandSolution) {
  for (FrameSolver solver : {FrameSolver::Cholesky, FrameSolver::Cg, FrameSolver::Multigrid}) {
    PaperOptions options;
    options.frame_solver = solver;
    Patch patch = grid_patch();
    const PaperSetup setup = paper_setup(patch, grid_points(), options, {}, false);
    const PaperSlide s = paper_slide(setup, patch, stretched_points(), {}, options);
    EXPECT_NEAR(s.slid.net[4].x(), 3.0 / 7.0, 1e-12) << to_string(solver);
    EXPECT_NEAR(s.slid.net[4].y(), 0.5, 1e-12) << to_string(solver);
  }
}

TEST(PaperSlide, AutoTakesMultigridFromTheThresholdOn) {
  EXPECT_EQ(frame_net_method(FrameSolver::Auto, kMultigridFreeNodes - 1), FrameNetMethod::Cholesky);
  EXPECT_EQ(frame_net_method(FrameSolver::Auto, kMultigridFreeNodes), FrameNetMethod::Multigrid);
  EXPECT_EQ(frame_net_method(FrameSolver::Cg, 1), FrameNetMethod::Cg);
}

}  // namespace
}  // namespace skinslide
