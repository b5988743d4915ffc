// --window: the sequence's order, the weights, the store of relaxations, and what a windowed frame
// writes (pipeline/frame_window.h, elastic/window_mean.h).
#include "pipeline/frame_window.h"

#include <atomic>
#include <thread>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "core/error.h"
#include "elastic/elastic_method.h"
#include "elastic/line_search.h"
#include "elastic/window_mean.h"
#include "helpers/samples.h"
#include "mesh/measures.h"

namespace skinslide {
namespace {

std::vector<std::pair<std::size_t, double>> pairs(const std::vector<WindowWeight>& w) {
  std::vector<std::pair<std::size_t, double>> out;
  for (const WindowWeight& m : w) out.emplace_back(m.frame, m.weight);
  return out;
}

TEST(FrameWindow, WeightsFallFromTheFrameAndAreRenormalisedWhereTheSequenceEnds) {
  const WindowPlan plan = ordered_window_plan(2, 10);
  using P = std::vector<std::pair<std::size_t, double>>;
  EXPECT_EQ(pairs(window_of(plan, 5)),
            (P{{3, 1 / 9.0}, {4, 2 / 9.0}, {5, 3 / 9.0}, {6, 2 / 9.0}, {7, 1 / 9.0}}));
  EXPECT_EQ(pairs(window_of(plan, 0)), (P{{0, 3 / 6.0}, {1, 2 / 6.0}, {2, 1 / 6.0}}));
  EXPECT_EQ(pairs(window_of(plan, 9)), (P{{7, 1 / 6.0}, {8, 2 / 6.0}, {9, 3 / 6.0}}));
  EXPECT_EQ(pairs(window_of(ordered_window_plan(3, 1), 0)), (P{{0, 1.0}}));
}

TEST(FrameWindow, ACycleWrapsTheWindowsAroundTheSequencesEnds) {
  WindowPlan plan = ordered_window_plan(2, 10);
  plan.cycle = true;
  using P = std::vector<std::pair<std::size_t, double>>;
  EXPECT_EQ(pairs(window_of(plan, 5)),
            (P{{3, 1 / 9.0}, {4, 2 / 9.0}, {5, 3 / 9.0}, {6, 2 / 9.0}, {7, 1 / 9.0}}));
  EXPECT_EQ(pairs(window_of(plan, 0)),
            (P{{8, 1 / 9.0}, {9, 2 / 9.0}, {0, 3 / 9.0}, {1, 2 / 9.0}, {2, 1 / 9.0}}));
  EXPECT_EQ(pairs(window_of(plan, 9)),
            (P{{7, 1 / 9.0}, {8, 2 / 9.0}, {9, 3 / 9.0}, {0, 2 / 9.0}, {1, 1 / 9.0}}));
  // A loop shorter than the window: each frame counted once, its weights summed.
  WindowPlan short_loop = ordered_window_plan(2, 2);
  short_loop.cycle = true;
  EXPECT_EQ(pairs(window_of(short_loop, 0)), (P{{0, 5 / 9.0}, {1, 4 / 9.0}}));
  // Files ordered by number: the loop closes from the highest number to the lowest.
  WindowPlan files = files_window_plan(1, {"a.0003.obj", "a.0001.obj", "a.0002.obj"});
  files.cycle = true;
  EXPECT_EQ(pairs(window_of(files, 0)), (P{{2, 1 / 4.0}, {0, 2 / 4.0}, {1, 1 / 4.0}}));
}

TEST(FrameWindow, FilesAreOrderedByTheirFrameNumbersNotTheOrderGiven) {
  const WindowPlan plan = files_window_plan(1, {"s/a.0010.obj", "s/a.0002.obj", "s/a.0007.obj"});
  EXPECT_EQ(plan.order, (std::vector<std::size_t>{1, 2, 0}));
  using P = std::vector<std::pair<std::size_t, double>>;
  // frame 7 (index 2) lies between frames 2 and 10
  EXPECT_EQ(pairs(window_of(plan, 2)), (P{{1, 0.25}, {2, 0.5}, {0, 0.25}}));
}

// files_window_plan's usage error for these paths ("" when it plans them).
std::string refusal(int reach, const std::vector<std::string>& paths) {
  try {
    files_window_plan(reach, paths);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    return e.what();
  }
  return "";
}

TEST(FrameWindow, FilesWithoutNumbersOrWithOneNumberTwiceAreRefused) {
  EXPECT_EQ(refusal(2, {"a.0001.obj", "rest.obj"}),
            "--window 2: rest.obj has no frame number (name.0042.obj), and a window takes each "
            "frame's neighbours by their numbers");
  EXPECT_EQ(refusal(1, {"x/a.0001.obj", "y/b.0001.obj"}),
            "--window 1: x/a.0001.obj and y/b.0001.obj are both frame 1: a window takes each "
            "frame's neighbours by their numbers");
}

TEST(FrameWindow, TheStoreRelaxesEachFrameOnceWhateverTheThreadsAndKeepsItsErrors) {
  constexpr std::size_t kFrames = 12;
  std::vector<std::size_t> chosen;
  for (std::size_t f = 0; f < kFrames; ++f) chosen.push_back(f);
  std::atomic<int> calls[kFrames] = {};
  RelaxationStore store(ordered_window_plan(3, kFrames), chosen, [&](std::size_t f) {
    ++calls[f];
    if (f == 4) throw Error(ErrorKind::Input, "frame 4 is broken");
    FrameRelaxations r;
    r.patches.resize(1);
    r.patches[0].uv = {Vec2(static_cast<double>(f), 0)};
    r.seconds = {0};
    return r;
  });
  std::atomic<std::size_t> next{0};
  std::atomic<int> failed_windows{0};
  auto worker = [&] {
    for (std::size_t f; (f = next++) < kFrames;) {
      const auto window = store.window(f);
      bool failed = false;
      for (const auto& m : window) {
        failed |= m.error != nullptr;
        EXPECT_EQ(m.error != nullptr, m.frame == 4);
        if (!m.error) {
          EXPECT_EQ(m.relaxations->patches[0].uv[0].x(), static_cast<double>(m.frame));
        }
      }
      failed_windows += failed;
      store.done(f);
    }
  };
  std::thread a(worker), b(worker), c(worker);
  a.join();
  b.join();
  c.join();
  for (std::size_t f = 0; f < kFrames; ++f) EXPECT_EQ(calls[f], 1) << "frame " << f;
  EXPECT_EQ(failed_windows, 7) << "frames 1-7 hold frame 4";
}

// The data/elbow sample relaxed in each frame, for the windowed slides below.
struct ElbowRun {
  test::Sample sample = test::load_sample("elbow");
  // The search's relaxations: its slides differ most from frame to frame (the window's cases).
  BindSetup setup = bind_setup(sample.bind, {sample.faces}, SlideOptions{test::search_options()});
  std::vector<FrameRelaxations> relaxed;
  ElbowRun() {
    for (const Positions3& f : sample.frames) relaxed.push_back(relax_frame(setup, f));
  }
  // Frame f's positions of the patch's vertices (local ids): what window_mean reads.
  Positions3 patch_points(std::size_t f) const {
    const Patch& patch = setup.patches[0];
    Positions3 points(patch.vertices.size());
    for (size_t i = 0; i < points.size(); ++i) points[i] = sample.frames[f][patch.vertices[i]];
    return points;
  }
  const ElasticSetup& elastic() const { return *test::elastic(setup).patches[0]; }
};

TEST(FrameWindow, AWindowOfOneFrameWritesItsOwnSlide) {
  const ElbowRun run;
  const std::size_t f = 2;
  const FrameResult plain = slide_frame(run.setup, run.sample.frames[f]);
  WindowedFrame own;
  own.own = &run.relaxed[f];
  own.mean = {run.relaxed[f].patches[0].uv};
  const FrameResult windowed = slide_frame(run.setup, run.sample.frames[f], {}, &own);
  ASSERT_EQ(windowed.slid.vertex, plain.slid.vertex);
  const double diag = test::diagonal(run.sample.frames[f]);
  for (std::size_t k = 0; k < plain.slid.position.size(); ++k)
    EXPECT_LE((windowed.slid.position[k] - plain.slid.position[k]).norm(), 1e-12 * diag);
  EXPECT_EQ(test::elastic(windowed.patches[0]).window_returned, 0);
}

TEST(FrameWindow, AWindowedFrameKeepsEveryPromiseOfAFrameAlone) {
  const ElbowRun run;
  const std::size_t f = 2;
  const Positions3& frame = run.sample.frames[f];
  // The mean of the neighbours, with one triangle folded in the chart: a corner pushed past
  // another.
  WindowedFrame window;
  window.own = &run.relaxed[f];
  window.mean = {chart_point_mean(
      {{&run.relaxed[1].patches[0].uv, 0.5}, {&run.relaxed[3].patches[0].uv, 0.5}})};
  Positions2& mean = window.mean[0];
  const ElasticSetup& elastic = *test::elastic(run.setup).patches[0];
  const Triangle t = elastic.chart.triangles[elastic.chart.patch_triangle_count / 2];
  const Index a = elastic.movable_slot[t[0]], b = elastic.movable_slot[t[1]];
  ASSERT_GE(a, 0);
  ASSERT_GE(b, 0);
  mean[a] = mean[b] + 0.5 * (mean[b] - mean[a]);
  const FrameResult r = slide_frame(run.setup, frame, {.edge_spread = true}, &window);
  const Patch& patch = run.setup.patches[0];
  const ElasticReport& report = test::elastic(r.patches[0]);
  EXPECT_GT(report.window_returned, 0);
  EXPECT_LT(report.window_returned, static_cast<int>(elastic.movable.size()) / 10)
      << "the fold's corners and a few around it go back, not the whole patch";
  const std::string line = frame_summary(
      run.setup.patches, [&](std::size_t) -> const ElasticReport& { return report; }, "");
  EXPECT_NE(
      line.find(", " + std::to_string(report.window_returned) + " vertices off the window's mean"),
      std::string::npos)
      << line;
  EXPECT_EQ(report.slid_flips, 0);
  EXPECT_EQ(flipped_triangles(r.patches[0].frame_net, patch.triangles), 0);
  EXPECT_LE(report.energy_after, report.energy_before);
  const Positions3 out = apply_slide(frame, r.slid);
  const double diag = test::diagonal(frame);
  std::vector<char> free(frame.size(), 0);
  for (Index v : patch.free_vertices) free[patch.vertices[v]] = 1;
  for (std::size_t v = 0; v < frame.size(); ++v) {
    if (!free[v]) {
      EXPECT_EQ(out[v], frame[v]) << "border and outside vertices stay";
    } else {
      EXPECT_LE(test::distance_to_patch(patch, frame, out[v]), 1e-12 * diag) << "on the surface";
    }
  }
}

TEST(FrameWindow, AMeanThatCostsTheFrameMuchEnergyIsToldOnItsLine) {
  const ElbowRun run;
  ElasticReport report;
  report.stop = "converged";
  report.energy_before = 1;
  report.energy_own = 0.2;
  const auto line = [&](double written) {
    report.energy_after = written;
    return frame_summary(
        run.setup.patches, [&](std::size_t) -> const ElasticReport& { return report; }, "");
  };
  const std::string told = ", 20% without the window (its frames differ too much to share a mean)";
  EXPECT_NE(line(0.5).find(told), std::string::npos) << line(0.5);
  EXPECT_EQ(line(0.29).find("without the window"), std::string::npos)
      << "nine points of energy left are not told: " << line(0.29);
  EXPECT_EQ(line(0.2).find("without the window"), std::string::npos) << "no window, or no cost";
}

// The run counts a frame as costly (its summary, the report's window_costly) exactly when its
// line tells the window's cost: one threshold for both.
TEST(FrameWindow, AFrameIsCountedCostlyExactlyWhenItsLineSaysSo) {
  const ElbowRun run;
  ElasticReport report;
  report.stop = "converged";
  report.energy_before = 1;
  report.energy_own = 0.2;
  std::vector<PatchFrameReport> patches(run.setup.patches.size());
  for (double written : {0.2, 0.29, 0.299, 0.301, 0.31, 0.5, 1.0}) {
    report.energy_after = written;
    for (PatchFrameReport& p : patches) p.method = report;
    const std::string line = frame_summary(
        run.setup.patches, [&](std::size_t) -> const ElasticReport& { return report; }, "");
    EXPECT_EQ(window_costly(run.setup, patches),
              line.find("without the window") != std::string::npos)
        << written << ": " << line;
  }
  patches.front().at_rest = true;  // a frame at rest has no figures, so no such line
  EXPECT_FALSE(window_costly(run.setup, patches));
}

// window_mean's inputs for data/elbow's frame 2: its patch positions, set-up and own relaxation.
class WindowMeanOfFrame2 : public ::testing::Test {
 protected:
  const ElbowRun run;
  const std::size_t f = 2;
  const Positions3 points = run.patch_points(f);
  const ElasticSetup& elastic = run.elastic();
  const ElasticResult& own = run.relaxed[f].patches[0];
};

TEST_F(WindowMeanOfFrame2, AFoldStartingInTheMeanMovesTheWrittenSlideByNoJump) {
  const Positions2 neighbours = chart_point_mean(
      {{&run.relaxed[1].patches[0].uv, 0.5}, {&run.relaxed[3].patches[0].uv, 0.5}});
  // Corner a of one triangle driven in small steps across its opposite edge: the triangle folds
  // part of the way along, and the written points must follow the mean without a jump.
  const Triangle t = elastic.chart.triangles[elastic.chart.patch_triangle_count / 2];
  const Index a = elastic.movable_slot[t[0]], b = elastic.movable_slot[t[1]];
  ASSERT_GE(a, 0);
  ASSERT_GE(b, 0);
  const Vec2 from = neighbours[a], to = neighbours[b] + 0.5 * (neighbours[b] - neighbours[a]);
  constexpr int kSteps = 400;
  const double step = (to - from).norm() / kSteps;
  Positions2 mean = neighbours;
  ElasticResult before = window_mean(elastic, points, own, mean);
  EXPECT_EQ(before.window_returned, 0) << "the neighbours' mean alone folds nothing";
  int returned_steps = 0;
  for (int k = 1; k <= kSteps; ++k) {
    mean[a] = from + (static_cast<double>(k) / kSteps) * (to - from);
    const ElasticResult r = window_mean(elastic, points, own, mean);
    ASSERT_LE(r.energy_after, own.energy_before);
    if (r.window_returned > 0) ++returned_steps;
    for (size_t i = 0; i < r.uv.size(); ++i)
      EXPECT_LE((r.uv[i] - before.uv[i]).norm(), 2 * step)
          << "vertex " << i << " jumps at step " << k << " of " << kSteps;
    for (Index u = 0; u < elastic.chart.patch_triangle_count; ++u) {
      Positions3 x = points;
      for (size_t i = 0; i < r.uv.size(); ++i) x[elastic.movable[i]] = r.position[i];
      ASSERT_FALSE(slid_triangle_folds(elastic.chart, elastic.movable_slot, r.uv, points, x,
                                       elastic.chart.triangles[u]))
          << "triangle " << u << " at step " << k;
    }
    before = r;
  }
  EXPECT_GT(returned_steps, kSteps / 4) << "the fold is met on the way";
}

TEST_F(WindowMeanOfFrame2, AMeanRisingAboveTheFramesEnergyIsLeftByNoJump) {
  // The mean driven away from the frame's own slide along a neighbour's difference, until its
  // energy is above the frame's: the patch must then go back towards its own slide by as much
  // as the energy needs, not all at once.
  const Positions2& neighbour = run.relaxed[0].patches[0].uv;
  constexpr int kSteps = 200;
  constexpr double kFar = 6;  // how many neighbour differences the mean ends away
  Positions2 mean = own.uv;
  ElasticResult before = window_mean(elastic, points, own, mean);
  int above_steps = 0;
  for (int k = 1; k <= kSteps; ++k) {
    const double reach = kFar * k / kSteps;
    for (size_t i = 0; i < mean.size(); ++i)
      mean[i] = own.uv[i] + reach * (neighbour[i] - own.uv[i]);
    const ElasticResult r = window_mean(elastic, points, own, mean);
    ASSERT_LE(r.energy_after, own.energy_before) << "step " << k;
    if (r.window_returned == static_cast<int>(own.uv.size())) ++above_steps;
    for (size_t i = 0; i < r.uv.size(); ++i) {
      const double step = kFar / kSteps * (neighbour[i] - own.uv[i]).norm();
      EXPECT_LE((r.uv[i] - before.uv[i]).norm(), 2 * step + 1e-9)
          << "vertex " << i << " jumps at step " << k << " of " << kSteps;
    }
    before = r;
  }
  EXPECT_GT(above_steps, kSteps / 4) << "the mean rises above the frame's energy on the way";
}

TEST(FrameWindow, ARigidCopyOfTheBindAmongMovingNeighboursComesBackAsItIs) {
  const ElbowRun run;
  Positions3 rigid = run.sample.frames[0];
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (Vec3& p : rigid) p = 2.0 * (turn * p) + Vec3(0.5, -1, 2);
  const FrameRelaxations own = relax_frame(run.setup, rigid);
  ASSERT_EQ(test::elastic(run.setup).patches.size(), 1u);
  ASSERT_EQ(own.patches[0].stop, ElasticStop::AtRest);
  WindowedFrame window;
  window.own = &own;
  window.mean = {chart_point_mean(
      {{&run.relaxed[2].patches[0].uv, 0.5}, {&run.relaxed[3].patches[0].uv, 0.5}})};
  const FrameResult r = slide_frame(run.setup, rigid, {}, &window);
  EXPECT_EQ(apply_slide(rigid, r.slid), rigid);
  EXPECT_EQ(test::elastic(r.patches[0]).window_returned, 0) << "at rest, not sent back";
}

}  // namespace
}  // namespace skinslide
