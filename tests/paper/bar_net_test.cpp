#include "paper/bar_net.h"

#include <random>

#include <gtest/gtest.h>

#include "core/error.h"

namespace skinslide {
namespace {

BarNet star() {  // four fixed corners, one free centre
  BarNet net;
  net.node_count = 5;
  net.bars = {{0, 4}, {1, 4}, {2, 4}, {3, 4}, {0, 1}};
  net.fixed = {1, 1, 1, 1, 0};
  return net;
}

Positions2 corners() { return {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {7, 7}}; }

TEST(BarNet, OneFreeNodeSitsAtTheQWeightedMeanOfItsNeighbours) {
  const Positions2 x = solve_bar_net(star(), {3, 1, 1, 1, 5}, corners());
  EXPECT_NEAR(x[4].x(), 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(x[4].y(), 1.0 / 3.0, 1e-15);
  EXPECT_EQ(x[0], Vec2(0, 0));  // fixed nodes as given
}

TEST(BarNet, ChainOfTwoFreeNodesMatchesTheHandSolution) {
  BarNet net;
  net.node_count = 4;
  net.bars = {{0, 1}, {1, 2}, {2, 3}};
  net.fixed = {1, 0, 0, 1};
  const Positions2 x = solve_bar_net(net, {1, 2, 1}, {{0, 0}, {0, 0}, {0, 0}, {3, 0}});
  EXPECT_NEAR(x[1].x(), 1.2, 1e-14);
  EXPECT_NEAR(x[2].x(), 1.8, 1e-14);
}

TEST(BarNet, TwoBarsBetweenTheSameFreeNodesActAsOneWithTheSumOfTheirQ) {
  BarNet doubled;
  doubled.node_count = 4;
  doubled.bars = {{0, 1}, {1, 2}, {2, 1}, {2, 3}};
  doubled.fixed = {1, 0, 0, 1};
  const Positions2 start = {{0, 0}, {0, 0}, {0, 0}, {3, 0}};
  const Positions2 x = solve_bar_net(doubled, {1, 0.5, 1.5, 1}, start);
  EXPECT_NEAR(x[1].x(), 1.2, 1e-14);  // the chain above: q = 1, 2, 1
  EXPECT_NEAR(x[2].x(), 1.8, 1e-14);
  const FrameNetSolver solver(doubled, start, FrameNetMethod::Cholesky);
  const FrameNetSolution s = solver.solve({1, 0.5, 1.5, 1}, FrameNetOptions{});
  EXPECT_NEAR(s.positions[1].x(), 1.2, 1e-14);
  EXPECT_NEAR(s.positions[2].x(), 1.8, 1e-14);
}

TEST(BarNet, AFreeNodeWithNoPathToAFixedOneIsANumericError) {
  BarNet net;
  net.node_count = 3;
  net.bars = {{0, 1}};
  net.fixed = {1, 0, 0};
  try {
    solve_bar_net(net, {1}, {{0, 0}, {0, 0}, {0, 0}});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Numeric);
  }
}

// A random grid net, border fixed on the unit square, seeded.
struct GridNet {
  BarNet net;
  Positions2 start;
};
GridNet grid_net(int n) {
  GridNet g;
  g.net.node_count = (n + 1) * (n + 1);
  g.net.fixed.assign(g.net.node_count, 0);
  g.start.assign(g.net.node_count, Vec2(0.5, 0.5));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const Index v = j * (n + 1) + i;
      if (i == 0 || j == 0 || i == n || j == n) {
        g.net.fixed[v] = 1;
        g.start[v] = Vec2(double(i) / n, double(j) / n);
      }
      if (i < n) g.net.bars.push_back({v, v + 1});
      if (j < n) g.net.bars.push_back({v, v + n + 1});
    }
  return g;
}

// max over free nodes of |sum_j q_ij (x_j - x_i)|: the net force, zero at equilibrium.
double net_force(const BarNet& net, const std::vector<double>& q, const Positions2& x) {
  Positions2 f(net.node_count, Vec2::Zero());
  for (size_t i = 0; i < net.bars.size(); ++i) {
    const auto [a, b] = net.bars[i];
    f[a] += q[i] * (x[b] - x[a]);
    f[b] += q[i] * (x[a] - x[b]);
  }
  double worst = 0;
  for (Index v = 0; v < net.node_count; ++v)
    if (!net.fixed[v]) worst = std::max(worst, f[v].norm());
  return worst;
}

TEST(BarNet, DirectAndWarmStartedCgReachEquilibriumOnRandomNets) {
  std::mt19937 rng{0};
  std::uniform_real_distribution<double> uq(1e-3, 1.0);
  const GridNet g = grid_net(30);
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<double> q(g.net.bars.size());
    for (double& v : q) v = uq(rng);
    const Positions2 direct = solve_bar_net(g.net, q, g.start);
    EXPECT_LT(net_force(g.net, q, direct), 1e-12);

    // warm start at the exact answer: 0 iterations
    const FrameNetSolver solver(g.net, direct, FrameNetMethod::Cg);
    const FrameNetSolution same = solver.solve(q, {1e-12, 1000});
    EXPECT_EQ(same.iterations, 0);
    EXPECT_FALSE(same.direct);

    std::vector<double> q2 = q;
    for (double& v : q2) v *= 1.0 + 0.2 * (uq(rng) - 0.5);
    const FrameNetSolution cg = solver.solve(q2, {1e-12, 1000});
    EXPECT_FALSE(cg.direct);
    EXPECT_GT(cg.iterations, 0);
    EXPECT_LE(cg.residual, 1e-12);
    EXPECT_LT(net_force(g.net, q2, cg.positions), 1e-10);
    const Positions2 exact = solve_bar_net(g.net, q2, g.start);
    for (Index v = 0; v < g.net.node_count; ++v)
      EXPECT_NEAR((cg.positions[v] - exact[v]).norm(), 0, 1e-9);
  }
}

TEST(BarNet, CholeskyReachesEquilibriumOnRandomNetsWhateverTheWarmStart) {
  std::mt19937 rng{1};
  std::uniform_real_distribution<double> uq(1e-3, 1.0);
  const GridNet g = grid_net(40);
  // free nodes start at (0.5, 0.5): ignored
  const FrameNetSolver solver(g.net, g.start, FrameNetMethod::Cholesky);
  const FrameNetSolver cg_solver(g.net, g.start, FrameNetMethod::Cg);
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<double> q(g.net.bars.size());
    for (double& v : q) v = uq(rng);
    const FrameNetSolution s = solver.solve(q, {1e-12, 1});
    // a warm start that meets the tolerance
    const FrameNetSolver at_answer(g.net, s.positions, FrameNetMethod::Cholesky);
    EXPECT_EQ(at_answer.solve(q, {}).positions, s.positions);
    EXPECT_FALSE(s.direct);
    EXPECT_EQ(s.iterations, 0);
    EXPECT_LT(net_force(g.net, q, s.positions), 1e-12);
    for (Index v = 0; v < g.net.node_count; ++v) {
      if (g.net.fixed[v]) {
        EXPECT_EQ(s.positions[v], g.start[v]);
      }
    }
    const FrameNetSolution cg = cg_solver.solve(q, {1e-13, 5000});
    for (Index v = 0; v < g.net.node_count; ++v)
      EXPECT_NEAR((cg.positions[v] - s.positions[v]).norm(), 0, 1e-10);
  }
}

TEST(BarNet, ANetWithAnUnanchoredPartIsANumericErrorForCholeskyAndMultigrid) {
  BarNet net;
  net.node_count = 5;
  net.bars = {{0, 1}, {1, 2}, {3, 4}};  // nodes 3 and 4 reach no fixed node
  net.fixed = {1, 0, 1, 0, 0};
  for (FrameNetMethod method : {FrameNetMethod::Cholesky, FrameNetMethod::Multigrid}) {
    const FrameNetSolver solver(net, {{1, 0}, {0, 0}, {0, 1}, {0, 0}, {0, 0}}, method);
    try {
      solver.solve({1, 1, 1}, {});
      FAIL();
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Numeric);
      EXPECT_NE(std::string(e.what()).find("singular"), std::string::npos) << e.what();
    }
  }
}

TEST(BarNet, CgFallsBackToADirectSolveWhenItRunsOutOfIterations) {
  const GridNet g = grid_net(20);
  const std::vector<double> q(g.net.bars.size(), 1.0);
  const FrameNetSolver solver(g.net, g.start, FrameNetMethod::Cg);
  const FrameNetSolution s = solver.solve(q, {1e-14, 2});
  EXPECT_TRUE(s.direct);
  EXPECT_LT(net_force(g.net, q, s.positions), 1e-12);
}

TEST(BarNet, MultigridAgreesWithCholeskyOnRandomNetsAndKeepsAnExactWarmStart) {
  std::mt19937 rng{2};
  std::uniform_real_distribution<double> uq(1e-3, 1.0);
  const GridNet g = grid_net(40);
  const FrameNetSolver cholesky(g.net, g.start, FrameNetMethod::Cholesky);
  const FrameNetSolver multigrid(g.net, g.start, FrameNetMethod::Multigrid);
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<double> q(g.net.bars.size());
    for (double& v : q) v = uq(rng);
    const FrameNetSolution exact = cholesky.solve(q, {});
    const FrameNetSolution mg = multigrid.solve(q, {1e-12, 200});
    EXPECT_FALSE(mg.direct);
    EXPECT_GT(mg.iterations, 0);
    EXPECT_LE(mg.residual, 1e-12);
    EXPECT_LT(net_force(g.net, q, mg.positions), 1e-10);
    for (Index v = 0; v < g.net.node_count; ++v)
      EXPECT_NEAR((mg.positions[v] - exact.positions[v]).norm(), 0, 1e-10);
    const FrameNetSolver at_answer(g.net, exact.positions, FrameNetMethod::Multigrid);
    const FrameNetSolution kept = at_answer.solve(q, {});
    EXPECT_EQ(kept.iterations, 0);
    EXPECT_EQ(kept.positions, exact.positions);
  }
}

// A solver built before its warm start was known (as a spare thread builds one during the
// set-up) and then started at it solves bit for bit as one built with it, by either method.
TEST(BarNet, ASolverStartedLaterSolvesTheSameBits) {
  std::mt19937 rng{5};
  std::uniform_real_distribution<double> uq(1e-3, 1.0);
  const GridNet g = grid_net(30);
  std::vector<double> q(g.net.bars.size());
  for (double& v : q) v = uq(rng);
  const Positions2 elsewhere(g.start.size(), Vec2(0.25, 0.75));
  for (FrameNetMethod method : {FrameNetMethod::Multigrid, FrameNetMethod::Cholesky}) {
    SCOPED_TRACE(static_cast<int>(method));
    const FrameNetSolver own(g.net, g.start, method);
    const FrameNetSolver later = FrameNetSolver(g.net, elsewhere, method).starting_at(g.start);
    EXPECT_EQ(later.method(), method);
    const FrameNetSolution a = own.solve(q, {1e-12, 200}), b = later.solve(q, {1e-12, 200});
    if (method == FrameNetMethod::Multigrid) {
      EXPECT_GT(a.iterations, 0);
    }
    EXPECT_EQ(a.iterations, b.iterations);
    EXPECT_EQ(a.positions, b.positions);
  }
  // With nothing to solve, the solution is the positions it was started at.
  BarNet all_fixed = g.net;
  all_fixed.fixed.assign(all_fixed.node_count, 1);
  const FrameNetSolver fixed =
      FrameNetSolver(all_fixed, elsewhere, FrameNetMethod::Multigrid).starting_at(g.start);
  EXPECT_EQ(fixed.solve(q, {}).positions, g.start);
}

TEST(BarNet, MultigridFallsBackToADirectSolveWhenItRunsOutOfIterations) {
  const GridNet g = grid_net(20);
  const std::vector<double> q(g.net.bars.size(), 1.0);
  const FrameNetSolver solver(g.net, g.start, FrameNetMethod::Multigrid);
  const FrameNetSolution s = solver.solve(q, {1e-14, 1});
  EXPECT_TRUE(s.direct);
  EXPECT_LT(net_force(g.net, q, s.positions), 1e-12);
}

}  // namespace
}  // namespace skinslide
