// Bind set-up across threads: patches are set up in parallel, one per thread, with the same
// result as one after another.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"
#include "helpers/meshes.h"
#include "helpers/samples.h"
#include "pipeline/bind_setup.h"
#include "pipeline/slide_frame.h"

namespace skinslide {
namespace {

// Three 4 x 4 blocks of a 14 x 4 quad grid, one column apart: three patches of one selection.
struct Blocks {
  PolyMesh mesh = test::quad_grid(14, 4);
  std::vector<Index> faces;
  Blocks() {
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 14; ++i)
        if (i % 5 != 4) faces.push_back(j * 14 + i);
  }
  static Index vertex(int i, int j) { return j * 15 + i; }
};

// The grid bent about the line x = 7 (between the second and third block) and creased along y.
Positions3 bent(const PolyMesh& mesh) {
  Positions3 out;
  for (const Vec3& p : mesh.positions) {
    const double a = p.x() > 7 ? 0.8 * (p.x() - 7) / 7 : 0.0;
    out.emplace_back(7 + (p.x() - 7) * std::cos(a), p.y(),
                     (p.x() - 7) * std::sin(a) + 0.1 * p.y() * p.y());
  }
  return out;
}

TEST(BindSetup, PatchesSetUpInParallelEqualTheSerialSetUp) {
  const Blocks b;
  const BindSetup one = bind_setup(b.mesh, {b.faces}, SlideOptions{}, SlideControls{}, {}, 1);
  ASSERT_EQ(one.patches.size(), 3u);
  const Positions3 frame = bent(b.mesh);
  const SlidVertices slid_one = slide_frame(one, frame).slid;
  ASSERT_FALSE(slid_one.vertex.empty());
  for (unsigned threads : {2u, 3u, 8u}) {
    const BindSetup many =
        bind_setup(b.mesh, {b.faces}, SlideOptions{}, SlideControls{}, {}, threads);
    ASSERT_EQ(many.patches.size(), one.patches.size());
    for (size_t p = 0; p < one.patches.size(); ++p) {
      EXPECT_EQ(many.patches[p].vertices, one.patches[p].vertices) << threads;
      EXPECT_EQ(many.patches[p].bind_net, one.patches[p].bind_net) << threads;  // bit for bit
    }
    const SlidVertices slid_many = slide_frame(many, frame).slid;
    EXPECT_EQ(slid_many.vertex, slid_one.vertex);
    EXPECT_EQ(slid_many.position, slid_one.position);
  }
}

// One multigrid patch and two threads: the frame nets' hierarchy is built beside the bind net's
// solve. The set-up and every slid bit are those of one thread.
TEST(BindSetup, AMultigridPatchSetUpOnTwoThreadsEqualsTheSerialSetUp) {
  const Blocks b;
  PaperOptions options;
  options.frame_solver = FrameSolver::Multigrid;
  const BindSetup one = bind_setup(b.mesh, {b.faces}, options, SlideControls{}, {}, 1);
  const BindSetup two = bind_setup(b.mesh, {b.faces}, options, SlideControls{}, {}, 8);
  ASSERT_EQ(two.patches.size(), one.patches.size());
  for (size_t p = 0; p < one.patches.size(); ++p) {
    ASSERT_EQ(test::paper(one).patches[p].solver->method(), FrameNetMethod::Multigrid);
    EXPECT_EQ(test::paper(two).patches[p].solver->method(), FrameNetMethod::Multigrid);
    EXPECT_EQ(two.patches[p].bind_net, one.patches[p].bind_net);
  }
  const Positions3 frame = bent(b.mesh);
  const FrameResult a = slide_frame(one, frame), c = slide_frame(two, frame);
  for (size_t p = 0; p < one.patches.size(); ++p)
    EXPECT_EQ(test::paper(c.patches[p]).cg_iterations, test::paper(a.patches[p]).cg_iterations);
  EXPECT_EQ(c.slid.vertex, a.slid.vertex);
  EXPECT_EQ(c.slid.position, a.slid.position);
}

TEST(BindSetup, AutoSolvesByMultigridFromTheThresholdOn) {
  EXPECT_EQ(frame_net_method(FrameSolver::Auto, kMultigridFreeNodes - 1), FrameNetMethod::Cholesky);
  EXPECT_EQ(frame_net_method(FrameSolver::Auto, kMultigridFreeNodes), FrameNetMethod::Multigrid);
  EXPECT_EQ(frame_net_method(FrameSolver::Cholesky, 1 << 30), FrameNetMethod::Cholesky);
  EXPECT_EQ(frame_net_method(FrameSolver::Multigrid, 10), FrameNetMethod::Multigrid);
  EXPECT_EQ(frame_net_method(FrameSolver::Cg, 10), FrameNetMethod::Cg);
}

// A 40 x 40 grid (1521 free nodes: four multigrid levels) bent at its middle.
TEST(BindSetup, MultigridNetsAndSlidFramesAgreeWithCholeskyWithinTheTolerance) {
  const PolyMesh mesh = test::quad_grid(40, 40);
  std::vector<Index> faces(1600);
  for (Index f = 0; f < 1600; ++f) faces[f] = f;
  Positions3 frame;
  for (const Vec3& p : mesh.positions) {
    const double a = p.x() > 20 ? 0.6 * (p.x() - 20) / 20 : 0.0;
    frame.emplace_back(20 + (p.x() - 20) * std::cos(a), p.y(), (p.x() - 20) * std::sin(a));
  }
  PaperOptions options;
  options.frame_solver = FrameSolver::Cholesky;
  const BindSetup cholesky = bind_setup(mesh, {faces}, options, SlideControls{}, {}, 1);
  options.frame_solver = FrameSolver::Multigrid;
  const BindSetup multigrid = bind_setup(mesh, {faces}, options, SlideControls{}, {}, 1);
  ASSERT_EQ(multigrid.patches.size(), 1u);
  EXPECT_EQ(test::paper(multigrid).patches[0].solver->method(), FrameNetMethod::Multigrid);
  EXPECT_EQ(test::paper(cholesky).patches[0].solver->method(), FrameNetMethod::Cholesky);
  const Positions2& a = cholesky.patches[0].bind_net;
  const Positions2& b = multigrid.patches[0].bind_net;
  ASSERT_EQ(a.size(), b.size());
  for (size_t v = 0; v < a.size(); ++v) EXPECT_NEAR((a[v] - b[v]).norm(), 0, 1e-10) << v;
  const FrameResult ra = slide_frame(cholesky, frame), rb = slide_frame(multigrid, frame);
  ASSERT_EQ(ra.slid.vertex, rb.slid.vertex);
  ASSERT_FALSE(ra.slid.vertex.empty());
  EXPECT_GT(test::paper(rb.patches[0]).cg_iterations, 0);
  EXPECT_FALSE(test::paper(rb.patches[0]).direct_solve);
  double moved = 0;
  for (size_t k = 0; k < ra.slid.position.size(); ++k) {
    EXPECT_NEAR((ra.slid.position[k] - rb.slid.position[k]).norm(), 0, 1e-9) << k;
    moved = std::max(moved, (ra.slid.position[k] - frame[ra.slid.vertex[k]]).norm());
  }
  EXPECT_GT(moved, 0.05);  // the bend slides the skin: the comparison is not of two no-ops
}

TEST(BindSetup, TheFirstFailingPatchInOrderNamesTheErrorWhateverTheThreads) {
  const Blocks b;
  SlideControls bad;
  // Blocks 1 and 2 get their corners out of walking order; block 0 is fine.
  for (int x0 : {5, 10})
    bad.corners.push_back({Blocks::vertex(x0, 0), Blocks::vertex(x0 + 4, 4),
                           Blocks::vertex(x0 + 4, 0), Blocks::vertex(x0, 4)});
  for (unsigned threads : {1u, 2u, 3u}) {
    try {
      bind_setup(b.mesh, {b.faces}, test::paper_options(), bad, {}, threads);
      FAIL() << threads;
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Usage);
      EXPECT_EQ(std::string(e.what()).rfind("patch 1 (face 5, 16 faces): --corners 5,", 0), 0u)
          << threads << ": " << e.what();
    }
  }
}

}  // namespace
}  // namespace skinslide
