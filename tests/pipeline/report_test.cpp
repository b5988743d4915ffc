#include "pipeline/report.h"

#include <gtest/gtest.h>

#include "helpers/meshes.h"
#include "helpers/samples.h"

namespace skinslide {
namespace {

RunReport two_frames(const BindSetup& setup, const Positions3& frame) {
  RunReport run;
  run.bind = "bind \"a\".obj";
  run.patch_files = {"p.txt"};
  for (int k = 0; k < 2; ++k) {
    ReportFrame f;
    f.path = k == 0 ? "f0.obj" : "f1.obj";
    f.output = k == 0 ? "slid/f0.obj" : "slid/f1.obj";
    f.patches = slide_frame(setup, frame).patches;
    run.frames.push_back(f);
  }
  return run;
}

TEST(Report, TheElasticMethodsFiguresInAFixedOrder) {
  const PolyMesh bind = test::quad_grid(4, 4);
  Positions3 frame = bind.positions;
  for (Vec3& p : frame) p.x() *= 1 + 0.1 * p.x();
  const BindSetup setup = bind_setup(bind, {test::all_faces(bind)}, SlideOptions{});
  const RunReport run = two_frames(setup, frame);
  const std::string a = report_json(setup, run);
  size_t at = 0;
  for (const char* key :
       {"\"options\"", "\"method\": \"elastic\"", "\"max_iterations\": 100", "\"patches\"",
        "\"moving\": 9", "\"chart_weights\": \"mean value\"", "\"frames\"", "\"energy_before\"",
        "\"energy_after\"", "\"iterations\"", "\"solves\"", "\"solve_iterations\"",
        "\"stop\": \"converged\"", "\"held\"", "\"flips\": 0", "\"totals\"", "\"moved\": 18",
        "\"flips\": 0"}) {
    const size_t found = a.find(key, at);
    ASSERT_NE(found, std::string::npos) << key << "\n" << a;
    at = found;
  }
  EXPECT_EQ(a.find("cg_iterations"), std::string::npos) << "no paper figures";
  EXPECT_EQ(a.find("density"), std::string::npos) << "no paper options";
}

TEST(Report, KeysInAFixedOrderAndTimingsApart) {
  const PolyMesh bind = test::quad_grid(4, 4);
  Positions3 frame = bind.positions;
  for (Vec3& p : frame) p.x() *= 1 + 0.1 * p.x();
  const BindSetup setup = bind_setup(bind, {test::all_faces(bind)}, test::paper_options());
  RunReport run = two_frames(setup, frame);
  const std::string a = report_json(setup, run);
  size_t at = 0;
  for (const char* key :
       {"\"skinslide\"", "\"bind\": \"bind \\\"a\\\".obj\"", "\"patch_files\"", "\"options\"",
        "\"density\": \"inverse\"", "\"controls\"", "\"patches\"", "\"corners\": [0, 4, 24, 20]",
        "\"frames\"", "\"path\": \"f0.obj\"", "\"cg_iterations\"", "\"spread_slid\"",
        "\"path\": \"f1.obj\"", "\"totals\"", "\"frames\": 2", "\"moved\": 18", "\"timings\"",
        "\"wall\""}) {
    const size_t found = a.find(key, at);
    ASSERT_NE(found, std::string::npos) << key << "\n" << a;
    at = found;
  }
  run.timings = false;
  const std::string b = report_json(setup, run);
  EXPECT_EQ(b.find("timings"), std::string::npos);
  RunReport again = two_frames(setup, frame);
  again.timings = false;
  again.bind_seconds = 123;  // timings are not written
  EXPECT_EQ(b, report_json(setup, again))
      << "without timings the report depends on the inputs only";
  EXPECT_EQ(b.back(), '\n');
}

}  // namespace
}  // namespace skinslide
