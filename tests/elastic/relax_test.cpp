// The elastic slide's guarantees on small meshes (README "The method, exactly", elastic): on the
// frame's surface, border and outside exact, no chart triangle turned over, no slid triangle
// turned against the frame, energy never up, rest frames unchanged, finite on bad frames.
#include "elastic/relax.h"

#include <cmath>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "helpers/meshes.h"
#include "helpers/samples.h"
#include "pipeline/bind_setup.h"
#include "pipeline/slide_frame.h"

namespace skinslide {
namespace {

using test::diagonal;
using test::distance_to_patch;

// A 10 x 10 grid with a 2 x 2 hole, bent like skin over a joint: the right part turned about the
// y axis by `angle`, the strip around the joint stretched on top.
PolyMesh bind_grid() { return test::quad_grid_with_holes(10, 10, {23, 24, 33, 34}); }

Positions3 bent(const Positions3& bind, double angle) {
  Positions3 out = bind;
  for (Vec3& p : out) {
    const double x = p.x() - 5;
    if (x <= 0) continue;
    // The skin over the joint stretches; the rest turns rigidly.
    const double r = 3.0;
    p = Vec3(5 + r * std::sin(angle * x / 5) * 5 / (r * angle) * (1 + 0.3 * std::exp(-x)), p.y(),
             r * (1 - std::cos(angle * x / 5)) * 5 / (r * angle));
  }
  return out;
}

std::vector<char> free_mask(const BindSetup& setup) {
  std::vector<char> free(setup.vertex_count, 0);
  for (const Patch& p : setup.patches)
    for (Index v : p.free_vertices) free[p.vertices[v]] = 1;
  return free;
}

double chart_area(const Positions2& uv, const Triangle& t) {
  const Vec2 e1 = uv[t[1]] - uv[t[0]], e2 = uv[t[2]] - uv[t[0]];
  return e1.x() * e2.y() - e1.y() * e2.x();
}

void expect_guarantees(const BindSetup& setup, const Positions3& frame, const FrameResult& r) {
  const Positions3 out = apply_slide(frame, r.slid);
  const std::vector<char> free = free_mask(setup);
  const double diag = diagonal(frame);
  for (size_t v = 0; v < out.size(); ++v) {
    ASSERT_TRUE(out[v].allFinite()) << "vertex " << v;
    if (!free[v]) {
      ASSERT_EQ(out[v], frame[v]) << "loops, pins and outside vertices: bit-exact";
    }
  }
  for (size_t k = 0; k < r.slid.vertex.size(); ++k) {
    const SurfaceSample& s = r.slid.sample[k];
    double sum = 0;
    for (double w : s.weight) {
      EXPECT_GE(w, 0);
      EXPECT_LE(w, 1);
      sum += w;
    }
    EXPECT_NEAR(sum, 1, 1e-15) << "a convex combination of one frame triangle";
  }
  for (size_t p = 0; p < setup.patches.size(); ++p) {
    const Patch& patch = setup.patches[p];
    const PatchFrameReport& rep = r.patches[p];
    if (patch.skipped) continue;
    EXPECT_LE(test::elastic(rep).energy_after, test::elastic(rep).energy_before)
        << "the energy never rises";
    EXPECT_EQ(test::elastic(rep).slid_flips, 0) << "no slid triangle turned against the frame";
    for (const Triangle& t : patch.triangles) {
      EXPECT_GT(chart_area(rep.frame_net, t), 0) << "no chart triangle turned over";
      const Vec3 nf = (frame[patch.vertices[t[1]]] - frame[patch.vertices[t[0]]])
                          .cross(frame[patch.vertices[t[2]]] - frame[patch.vertices[t[0]]]);
      const Vec3 ns = (out[patch.vertices[t[1]]] - out[patch.vertices[t[0]]])
                          .cross(out[patch.vertices[t[2]]] - out[patch.vertices[t[0]]]);
      if (!nf.isZero(0)) {
        EXPECT_GT(ns.dot(nf), 0);
      }
    }
    for (Index lv : patch.free_vertices)
      ASSERT_LT(distance_to_patch(patch, frame, out[patch.vertices[lv]]), 1e-12 * diag)
          << "on the frame's surface: vertex " << patch.vertices[lv];
  }
}

TEST(ElasticSlide, ABentGridSlidesOnItsSurfaceAndEvensTheStretch) {
  const PolyMesh mesh = bind_grid();
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{});
  ASSERT_EQ(setup.patches.size(), 1u);
  ASSERT_TRUE(test::elastic(setup).patches[0]);
  for (double angle : {0.5, 1.5, 3.0}) {
    const Positions3 frame = bent(mesh.positions, angle);
    const FrameResult r = slide_frame(setup, frame, {.edge_spread = true});
    expect_guarantees(setup, frame, r);
    const PatchFrameReport& rep = r.patches[0];
    EXPECT_GT(test::elastic(rep).iterations, 0);
    EXPECT_LT(test::elastic(rep).energy_after, 0.9 * test::elastic(rep).energy_before)
        << "angle " << angle;
    EXPECT_LT(rep.spread_slid, rep.spread_frame) << "angle " << angle;
    EXPECT_GT(rep.max_slide, 0);
  }
}

// --ease-in: the first fits aim part of the way from the frame's own stretch; the slide keeps
// every guarantee, evens the stretch as the default does, and is not the default's slide.
TEST(ElasticSlide, EasedTargetsKeepTheGuaranteesAndEvenTheStretch) {
  const PolyMesh mesh = bind_grid();
  ElasticOptions eased;
  eased.solver = ElasticSolver::Search;
  eased.ease_in = 1;
  eased.blend = 1;
  eased.tolerance = 1e-6;
  ElasticOptions blended = eased;
  blended.ease_in = 0;
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, eased);
  const BindSetup plain = bind_setup(mesh, {test::all_faces(mesh)}, blended);
  for (double angle : {0.5, 1.5, 3.0}) {
    const Positions3 frame = bent(mesh.positions, angle);
    const FrameResult r = slide_frame(setup, frame, {.edge_spread = true});
    expect_guarantees(setup, frame, r);
    const FrameResult p = slide_frame(plain, frame, {.edge_spread = true});
    const double e = test::elastic(r.patches[0]).energy_after;
    const double e_plain = test::elastic(p.patches[0]).energy_after;
    EXPECT_LT(e, 0.9 * test::elastic(r.patches[0]).energy_before) << "angle " << angle;
    EXPECT_LT(e, 1.05 * e_plain) << "the last fit aims fully: angle " << angle;
    EXPECT_LT(r.patches[0].spread_slid, r.patches[0].spread_frame) << "angle " << angle;
    EXPECT_NE(apply_slide(frame, r.slid), apply_slide(frame, p.slid)) << "angle " << angle;
  }
}

TEST(ElasticSlide, EaseInMustLeaveAFitThatAimsFully) {
  const PolyMesh mesh = bind_grid();
  ElasticOptions o;
  o.rotation_fits = 3;
  o.ease_in = 2;
  EXPECT_NO_THROW(check_rules(option_table<ElasticOptions>(), o));
  o.ease_in = 3;
  try {
    bind_setup(mesh, {test::all_faces(mesh)}, o);
    FAIL() << "--ease-in 3 with 3 fits";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("--ease-in 3 leaves no rotation fit"), std::string::npos)
        << e.what();
  }
}

TEST(ElasticSlide, RestFramesComeBackUnchanged) {
  const PolyMesh mesh = bind_grid();
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{});
  // The bind itself, a rigid motion of it, and a uniformly scaled copy.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (int kind = 0; kind < 3; ++kind) {
    Positions3 frame = mesh.positions;
    for (Vec3& p : frame) {
      if (kind == 1) p = R * p + Vec3(3, -2, 5);
      if (kind == 2) p = 1.7 * p;
    }
    const FrameResult r = slide_frame(setup, frame);
    EXPECT_EQ(test::elastic(r.patches[0]).stop, "at rest") << kind;
    EXPECT_EQ(apply_slide(frame, r.slid), frame) << kind;
  }
}

TEST(ElasticSlide, TheSameFrameGivesTheSameBits) {
  const PolyMesh mesh = bind_grid();
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{});
  const Positions3 frame = bent(mesh.positions, 2.0);
  const Positions3 a = apply_slide(frame, slide_frame(setup, frame).slid);
  slide_frame(setup, bent(mesh.positions, 1.0));  // nothing carries over between frames
  const Positions3 b = apply_slide(frame, slide_frame(setup, frame).slid);
  EXPECT_EQ(a, b);
}

TEST(ElasticSlide, BadFramesGiveFiniteOutputOnTheSurface) {
  const PolyMesh mesh = bind_grid();
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{});
  std::mt19937 rng(0);
  std::normal_distribution<double> noise(0, 0.4);
  std::vector<Positions3> frames;
  frames.push_back(Positions3(mesh.positions.size(), Vec3(1, 2, 3)));  // crushed to a point
  Positions3 line = mesh.positions;  // crushed to a line: every triangle without area
  for (Vec3& p : line) p = Vec3(p.x(), 0, 0);
  frames.push_back(line);
  Positions3 folded = bent(mesh.positions, M_PI);  // a 180 degree bend: the sheets touch
  frames.push_back(folded);
  Positions3 crumpled = mesh.positions;  // folded before sliding: many triangles turned over
  for (Vec3& p : crumpled) p += Vec3(noise(rng), noise(rng), noise(rng));
  frames.push_back(crumpled);
  Positions3 zero_edges = bent(mesh.positions, 1.0);  // zero-length edges in the frame
  zero_edges[12] = zero_edges[13];
  zero_edges[45] = zero_edges[46] = zero_edges[56];
  frames.push_back(zero_edges);
  for (size_t f = 0; f < frames.size(); ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    const FrameResult r = slide_frame(setup, frames[f]);
    const Positions3 out = apply_slide(frames[f], r.slid);
    for (const Vec3& p : out) ASSERT_TRUE(p.allFinite());
    for (size_t k = 0; k < r.slid.vertex.size(); ++k) {
      double sum = 0;
      for (double w : r.slid.sample[k].weight) {
        ASSERT_GE(w, 0);
        sum += w;
      }
      ASSERT_NEAR(sum, 1, 1e-15);
    }
    EXPECT_LE(test::elastic(r.patches[0]).energy_after, test::elastic(r.patches[0]).energy_before);
    EXPECT_EQ(test::elastic(r.patches[0]).slid_flips, 0) << "no fold the frame did not have";
  }
}

TEST(ElasticSlide, DegenerateBindTrianglesAndOneFreeVertex) {
  // A 2 x 2 grid: one free vertex. Two bind vertices on one point: zero-length edge, zero-area
  // triangles.
  PolyMesh mesh = test::quad_grid(2, 2);
  mesh.positions[1] = mesh.positions[0];
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{});
  ASSERT_EQ(setup.patches[0].free_vertices.size(), 1u);
  Positions3 frame = mesh.positions;
  for (Vec3& p : frame) p.x() *= 1 + 0.5 * p.x();  // stretched more on the right
  const FrameResult r = slide_frame(setup, frame);
  expect_guarantees(setup, frame, r);
  ASSERT_EQ(r.slid.vertex.size(), 1u);
  EXPECT_EQ(r.slid.vertex[0], 4);
  EXPECT_GT(r.slid.position[0].x(), frame[4].x()) << "the centre moves to the stretched side";
}

TEST(ElasticSlide, WeightsActInTheChartAndZeroHolds) {
  const PolyMesh mesh = bind_grid();
  SlideControls controls;
  controls.weight.assign(mesh.positions.size(), 1.0);
  controls.weight[60] = 0;    // held
  controls.weight[62] = 0.5;  // half way in the chart
  const BindSetup weighted = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{}, controls);
  const BindSetup plain = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{});
  const Positions3 frame = bent(mesh.positions, 2.0);
  const FrameResult r = slide_frame(weighted, frame);
  expect_guarantees(weighted, frame, r);
  const Positions3 out = apply_slide(frame, r.slid);
  EXPECT_EQ(out[60], frame[60]) << "weight 0: held at the frame";
  EXPECT_NE(out[61], frame[61]) << "the skin around it slides";
  const Positions3 full = apply_slide(frame, slide_frame(plain, frame).slid);
  const double half = (out[62] - frame[62]).norm(), whole = (full[62] - frame[62]).norm();
  EXPECT_GT(half, 0);
  EXPECT_LT(half, whole);
}

TEST(ElasticSlide, PinsAreHeldAndOptionsOfThePaperAreNotUsed) {
  const PolyMesh mesh = bind_grid();
  SlideControls controls;
  controls.pins = {61};
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{}, controls);
  EXPECT_TRUE(std::holds_alternative<ElasticMethod>(setup.method))
      << "no bar nets for the elastic method";
  const Positions3 frame = bent(mesh.positions, 2.0);
  const FrameResult r = slide_frame(setup, frame);
  expect_guarantees(setup, frame, r);
  EXPECT_EQ(apply_slide(frame, r.slid)[61], frame[61]);
}

TEST(ElasticSlide, EnergyOfTheBindIsZeroAndOfAStretchIsItsSquaredStrain) {
  const PolyMesh mesh = test::quad_grid(3, 3);
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{});
  const ElasticSetup& e = *test::elastic(setup).patches[0];
  Positions3 local(setup.patches[0].vertices.size());
  for (size_t i = 0; i < local.size(); ++i) local[i] = mesh.positions[setup.patches[0].vertices[i]];
  EXPECT_LT(elastic_energy(e, local, 1.0), 1e-28);
  // x stretched by 1.2: each triangle's singular values are 1.2 and 1, so e = 0.04 against s = 1;
  // 18 triangles of weight 0.5.
  for (Vec3& p : local) p.x() *= 1.2;
  EXPECT_NEAR(elastic_energy(e, local, 1.0), 18 * 0.5 * 0.04, 1e-12);
}

// A 64 x 64 grid wrapped over most of a ball, stretched towards the rim (the tangent planes
// turn all across, which the bind's factor does not see); `roughness`: every vertex that much
// off the ball at random, so that neighbouring planes turn too.
Positions3 on_a_ball(const PolyMesh& mesh, const Patch& patch, int n, double roughness) {
  Positions3 frame(patch.vertices.size());
  std::mt19937 random(30);
  std::uniform_real_distribution<double> bump(-roughness, roughness);
  const double radius = n / 3.0;
  for (size_t i = 0; i < frame.size(); ++i) {
    const Vec3& b = mesh.positions[patch.vertices[i]];
    const Vec2 c(b.x() - n / 2.0, b.y() - n / 2.0);
    const double r = c.norm(), phi = std::atan2(c.y(), c.x());
    const double theta = r / radius * (1 + 0.3 * r / n);
    const Vec3 out(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                   -std::cos(theta));
    frame[i] = (radius + bump(random)) * out;
  }
  return frame;
}

// Rule 10's escalation: a frame the measure finds short of stationary, whose directions went
// unsolved at their budget of 8 iterations, is relaxed again with 4x (then 16x) the budget, from
// where the first pass ended; a frame found stationary, or whose directions were nearly solved,
// is not.
TEST(ElasticRelax, AFrameShortOfStationaryIsRelaxedAgainWithALargerBudget) {
  const int n = 64;
  const PolyMesh mesh = test::quad_grid(n, n);
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{});
  const ElasticSetup& e = *test::elastic(setup).patches[0];
  const Positions3 rough = on_a_ball(mesh, setup.patches[0], n, 0.4);
  ElasticOptions lenient = test::search_options();
  lenient.convergence = 1.0;
  const ElasticResult first = relax_patch(e, rough, lenient);
  EXPECT_EQ(first.stop, ElasticStop::Converged);
  EXPECT_EQ(first.escalations, 0);
  EXPECT_LE(first.solver_iterations, 8 * first.solves);
  EXPECT_GT(first.solver_iterations, 7 * first.solves) << "the directions reach their budget";

  ElasticOptions strict = test::search_options();
  strict.convergence = 0.0;
  const ElasticResult escalated = relax_patch(e, rough, strict);
  EXPECT_NE(escalated.stop, ElasticStop::Converged);
  EXPECT_GE(escalated.escalations, 1);
  EXPECT_LE(escalated.escalations, 2);  // 8 -> 32 -> 128, the largest
  EXPECT_GT(escalated.solver_iterations, 8 * escalated.solves);
  EXPECT_GT(escalated.iterations, first.iterations);
  // The first pass is the same: the escalated one only goes on from where it ended.
  EXPECT_LT(escalated.energy_after, first.energy_after);
  EXPECT_LT(escalated.gain_left, first.gain_left);

  // On the smooth ball the directions are nearly solved at 8: nothing to escalate.
  const ElasticResult smooth = relax_patch(e, on_a_ball(mesh, setup.patches[0], n, 0.0), strict);
  EXPECT_NE(smooth.stop, ElasticStop::Converged);
  EXPECT_EQ(smooth.escalations, 0);
  EXPECT_LE(smooth.solver_iterations, 8 * smooth.solves);
}

// A round that ran to --max-iterations with its directions unsolved is escalated as a stall is:
// its steps were too short to count however many it took.
TEST(ElasticRelax, ARoundAtItsStepLimitWithUnsolvedDirectionsIsRelaxedAgain) {
  const int n = 64;
  const PolyMesh mesh = test::quad_grid(n, n);
  const BindSetup setup = bind_setup(mesh, {test::all_faces(mesh)}, SlideOptions{});
  const ElasticSetup& e = *test::elastic(setup).patches[0];
  ElasticOptions capped = test::search_options();
  capped.convergence = 0.0;
  capped.tolerance = 0.0;
  capped.max_iterations = 2;
  const ElasticResult rough = relax_patch(e, on_a_ball(mesh, setup.patches[0], n, 0.4), capped);
  EXPECT_EQ(rough.stop, ElasticStop::IterationLimit);
  EXPECT_GE(rough.escalations, 1);
  EXPECT_GT(rough.solver_iterations, 8 * rough.solves);
  EXPECT_LE(rough.iterations,
            (1 + rough.escalations) * capped.rotation_fits * capped.max_iterations);

  // The smooth ball's directions are nearly solved at 8: its limit stop stays as it is.
  const ElasticResult smooth = relax_patch(e, on_a_ball(mesh, setup.patches[0], n, 0.0), capped);
  EXPECT_EQ(smooth.stop, ElasticStop::IterationLimit);
  EXPECT_EQ(smooth.escalations, 0);
  EXPECT_LE(smooth.solver_iterations, 8 * smooth.solves);
}

}  // namespace
}  // namespace skinslide
