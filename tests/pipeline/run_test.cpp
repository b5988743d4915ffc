#include "pipeline/run.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <mutex>

#include <gtest/gtest.h>

#include "helpers/meshes.h"
#include "helpers/temp_dir.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

RunOptions frames_run(std::vector<std::string> frames, const std::string& output = "out") {
  RunOptions o;
  o.bind = "shot/bind.obj";
  o.patches = {"shot/arm.txt"};
  o.frames = std::move(frames);
  o.output = output;
  return o;
}

// The Usage message plan_frames refuses `o` with; "" when it does not.
std::string refusal(const RunOptions& o) {
  try {
    plan_frames(o);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    return e.what();
  }
  return "";
}

TEST(PlanFrames, OneOutputPerFrameNamedLikeIt) {
  const FramePlan plan = plan_frames(frames_run({"shot/a/f.0001.obj", "shot/b/f.0002.glb"}));
  EXPECT_EQ(plan.outputs, (std::vector<std::string>{"out/f.0001.obj", "out/f.0002.glb"}));
  EXPECT_EQ(plan.chosen, (std::vector<std::size_t>{0, 1}));
}

TEST(PlanFrames, RefusesTwoFramesWithOneFileName) {
  EXPECT_EQ(refusal(frames_run({"shot/a/f.0001.obj", "shot/b/f.0001.obj"})),
            "two frames are named 'f.0001.obj'; their outputs in out would collide");
}

TEST(PlanFrames, RefusesAnOutputThatIsAnInput) {
  EXPECT_EQ(refusal(frames_run({"shot/f.0001.obj"}, "shot")),
            "output shot/f.0001.obj would overwrite input shot/f.0001.obj; choose another "
            "--output folder");
  RunOptions o = frames_run({"shot/f.0001.obj"}, "shot/pins");
  o.pin = "shot/pins/f.0001.obj";
  EXPECT_EQ(refusal(o),
            "output shot/pins/f.0001.obj would overwrite input shot/pins/f.0001.obj; choose "
            "another --output folder");
  // One file spelled two ways: told apart by identity.
  const test::TempDir dir("plan_frames");
  fs::create_directories(dir.path() / "sub");
  std::ofstream(dir / "f.0001.obj") << "v 0 0 0\n";
  EXPECT_NE(refusal(frames_run({dir / "f.0001.obj"}, dir / "sub/..")).find("would overwrite input"),
            std::string::npos);
}

// Two paths that cannot be looked at are not one file (the overwrite check once compared their
// two failed lookups, both empty): the first input on the way is named, "cannot read".
TEST(PlanFrames, APathThatCannotBeLookedAtIsAnInputErrorNotAnOverwrite) {
  const test::TempDir dir("plan_frames_loop");
  fs::create_symlink(dir / "d", dir / "d");  // a loop of links: every lookup through it fails
  RunOptions o = frames_run({dir / "d/frames/elbow.0002.obj"}, dir / "d/out");
  o.bind = dir / "d/bind.obj";
  o.patches = {dir / "d/patch.txt"};
  try {
    plan_frames(o);
    ADD_FAILURE() << "planned";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_EQ(std::string(e.what()),
              dir / "d/frames/elbow.0002.obj" + ": cannot read: Too many levels of symbolic links");
  }
}

// -o names a folder: a mesh file's name is refused; a cache's name is the cache to write.
TEST(PlanFrames, RefusesAnOutputNamedLikeAMesh) {
  EXPECT_EQ(refusal(frames_run({"shot/f.0001.obj"}, "slid/shot.obj")),
            "-o slid/shot.obj: -o is a folder, not a mesh file: the slid frames keep their own "
            "names in it (-o slid/); one file for a shot is a point cache (-o shot.pc2)");
  EXPECT_NE(refusal(frames_run({"shot/f.0001.obj"}, "shot.GLTF")).find("-o is a folder"),
            std::string::npos);
  EXPECT_EQ(refusal(frames_run({"shot/f.0001.obj"}, "slid.v2")), "");
  EXPECT_EQ(cache_format_named_by("slid/shot.pc2"), "pc2");
  EXPECT_EQ(cache_format_named_by("shot.MDD"), "mdd");
  EXPECT_EQ(cache_format_named_by("slid"), "");
  EXPECT_EQ(cache_format_named_by("slid/.pc2"), "");
}

TEST(PlanFrames, RefusesAReportThatIsAnInputOrAnOutput) {
  RunOptions o = frames_run({"shot/f.0001.obj"});
  o.report = "shot/bind.obj";
  EXPECT_EQ(refusal(o), "--report shot/bind.obj would overwrite input shot/bind.obj");
  o.report = "out/f.0001.obj";
  EXPECT_EQ(refusal(o), "--report out/f.0001.obj is also the output of a frame");
}

TEST(PlanFrames, FramesSelectsByTheNumberInTheFileName) {
  std::vector<std::string> frames;
  for (int f = 1; f <= 5; ++f) frames.push_back("shot/arm.000" + std::to_string(f) + ".obj");
  RunOptions o = frames_run(frames);
  o.frame_ranges = "2-3,5";
  EXPECT_EQ(plan_frames(o).chosen, (std::vector<std::size_t>{1, 2, 4}));
  o.frame_ranges = "4-100";  // a farm's last chunk runs past the shot's end
  EXPECT_EQ(plan_frames(o).chosen, (std::vector<std::size_t>{3, 4}));
  EXPECT_EQ(plan_frames(o).outputs.size(), 5u);
  o.frame_ranges = "9-20";
  EXPECT_EQ(refusal(o), "--frames 9-20 selects none of the 5 frames (numbered 1 to 5)");
  o.frame_ranges = "5-3";
  EXPECT_NE(refusal(o).find("'5-3' runs backwards"), std::string::npos);
  o.frames.push_back("shot/rest.obj");
  o.frame_ranges = "1";
  EXPECT_EQ(refusal(o),
            "--frames: shot/rest.obj has no frame number in its file name (expected e.g. "
            "name.0042.obj); drop --frames or rename the frames");
}

TEST(PlanRigFrames, NamesAndFormatAndSelection) {
  RunOptions o = frames_run({});
  o.rig = RigOptions{};
  o.format = "obj";
  const std::vector<std::string> names = {"Rig.0000", "Rig.0001", "Rig.0002"};
  FramePlan plan = plan_rig_frames(o, names);
  EXPECT_EQ(plan.outputs,
            (std::vector<std::string>{"out/Rig.0000.obj", "out/Rig.0001.obj", "out/Rig.0002.obj"}));
  EXPECT_EQ(plan.chosen, (std::vector<std::size_t>{0, 1, 2}));
  o.frame_ranges = "1-9";
  EXPECT_EQ(plan_rig_frames(o, names).chosen, (std::vector<std::size_t>{1, 2}));
  o.patches = {"out/Rig.0002.obj"};
  try {
    plan_rig_frames(o, names);
    ADD_FAILURE() << "an output that is a patch file was not refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_EQ(std::string(e.what()),
              "output out/Rig.0002.obj would overwrite input out/Rig.0002.obj; choose another "
              "--output folder");
  }
}

// What a run told, gathered from its worker threads.
struct Told {
  std::mutex mutex;
  std::vector<LogLine> log;
  std::vector<std::size_t> begun;
  std::vector<std::pair<std::size_t, std::vector<LogLine>>> frames;
  int ended = 0;

  RunEvents events() {
    RunEvents e;
    e.log = [this](const LogLine& l) { log.push_back(l); };
    e.frames_begin = [this](std::size_t n) { begun.push_back(n); };
    e.frame_done = [this](std::size_t j, std::vector<LogLine> lines) {
      std::lock_guard<std::mutex> lock(mutex);
      frames.emplace_back(j, std::move(lines));
    };
    e.frames_end = [this] { ++ended; };
    return e;
  }
};

RunOptions elbow_run(const std::string& output) {
  RunOptions o;
  o.bind = test::source_path("data/elbow/bind.obj");
  o.patches = {test::source_path("data/elbow/patch.txt")};
  for (int f = 1; f <= 3; ++f)
    o.frames.push_back(
        test::source_path("data/elbow/frames/elbow.000" + std::to_string(f) + ".obj"));
  o.output = output;
  o.threads = 2;
  return o;
}

TEST(Run, TellsTheBindEachChosenFrameAndWritesThem) {
  const test::TempDir dir("run_tells");
  RunOptions o = elbow_run(dir / "slid");
  o.frame_ranges = "2-3";
  Told told;
  const RunResult result = run(o, told.events());
  EXPECT_EQ(result.frames, 2u);
  EXPECT_TRUE(result.failures.empty());
  ASSERT_FALSE(told.log.empty());
  EXPECT_EQ(told.log[0].level, LogLevel::Info);
  EXPECT_EQ(told.log[0].text,
            "skinslide: " + o.bind + ": 1 patch, 288 sliding vertices (method elastic)");
  EXPECT_EQ(told.log.back().level, LogLevel::Detail);
  EXPECT_EQ(told.log.back().text, "  2 frames, 2 at a time");
  EXPECT_EQ(told.begun, (std::vector<std::size_t>{2}));
  EXPECT_EQ(told.ended, 1);
  ASSERT_EQ(told.frames.size(), 2u);
  std::sort(told.frames.begin(), told.frames.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t j = 0; j < 2; ++j) {
    const auto& [index, lines] = told.frames[j];
    EXPECT_EQ(index, j);
    ASSERT_EQ(lines.size(), 2u);  // the frame, then its one patch
    const std::string out = dir / ("slid/elbow.000" + std::to_string(j + 2) + ".obj");
    EXPECT_EQ(lines[0].level, LogLevel::Info);
    EXPECT_EQ(lines[0].text.rfind("skinslide: " + o.frames[j + 1] + ": 1 patch, elastic ", 0), 0u);
    EXPECT_TRUE(lines[0].text.ends_with(" -> " + out)) << lines[0].text;
    EXPECT_EQ(lines[1].level, LogLevel::Detail);
    EXPECT_EQ(lines[1].text.rfind("  patch 0: elastic ", 0), 0u) << lines[1].text;
    EXPECT_TRUE(fs::exists(out));
  }
  EXPECT_FALSE(fs::exists(dir / "slid/elbow.0001.obj"));
}

TEST(Run, ABadFrameStopsTheRunOrWithKeepGoingIsNamed) {
  const test::TempDir dir("run_bad_frame");
  RunOptions o = elbow_run(dir / "slid");
  o.frames[1] = test::source_path("data/face/frames/face.0002.obj");  // another mesh
  o.threads = 1;
  try {
    run(o);
    ADD_FAILURE() << "a frame of another mesh was slid";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_EQ(std::string(e.what()).rfind(o.frames[1] + ": has ", 0), 0u) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "slid/elbow.0003.obj"));  // one thread: stopped before it

  o.keep_going = true;
  o.output = dir / "kept";
  Told told;
  const RunResult result = run(o, told.events());
  EXPECT_EQ(result.frames, 3u);
  ASSERT_EQ(result.failures.size(), 1u);
  EXPECT_EQ(result.failures[0].kind(), ErrorKind::Input);
  EXPECT_EQ(told.log.back().level, LogLevel::Error);
  EXPECT_EQ(told.log.back().text, std::string("skinslide: error: ") + result.failures[0].what());
  ASSERT_EQ(told.frames.size(), 3u);
  EXPECT_EQ(told.frames[1].first, 1u);
  EXPECT_TRUE(told.frames[1].second.empty());  // the failed frame: told, with no lines
  EXPECT_TRUE(fs::exists(dir / "kept/elbow.0001.obj"));
  EXPECT_FALSE(fs::exists(dir / "kept/face.0002.obj"));
  EXPECT_TRUE(fs::exists(dir / "kept/elbow.0003.obj"));
}

TEST(Run, AFirstFrameThatFailsIsTheErrorWithPreviewsAsked) {
  // The preview folder is made with the first preview: when no frame got that far, the run's
  // error is still the frame's (it was "preview: cannot write", exit 4, from flushing a folder
  // never made; found by tests/property).
  const test::TempDir dir("run_bad_first_frame");
  RunOptions o = elbow_run(dir / "slid");
  o.frames = {test::source_path("data/face/frames/face.0002.obj")};  // another mesh
  o.preview_dir = dir / "preview";
  o.threads = 1;
  try {
    run(o);
    ADD_FAILURE() << "a frame of another mesh was slid";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind(o.frames[0] + ": has ", 0), 0u) << e.what();
  }
  o.keep_going = true;
  const RunResult result = run(o);
  ASSERT_EQ(result.failures.size(), 1u);
  EXPECT_EQ(result.failures[0].kind(), ErrorKind::Input);
  EXPECT_FALSE(fs::exists(dir / "slid/face.0002.obj"));
}

}  // namespace
}  // namespace skinslide
