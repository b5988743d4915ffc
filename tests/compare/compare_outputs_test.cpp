#include "compare/compare_outputs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "compare/compare_report.h"
#include "core/error.h"
#include "helpers/meshes.h"
#include "helpers/temp_dir.h"
#include "io/atomic_write.h"
#include "io/obj_read.h"
#include "io/point_cache.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

const std::string kElbowFrames = test::source_path("data/elbow/frames");

// A copy of data/elbow's five frames in `dir`/`name`: stands for a slid output folder.
std::string elbow_copy(const test::TempDir& dir, const std::string& name) {
  const std::string to = dir / name;
  fs::create_directories(to);
  for (const auto& e : fs::directory_iterator(kElbowFrames))
    fs::copy_file(e.path(), fs::path(to) / e.path().filename());
  return to;
}

// Replaces line `line` (1-based) of `path` with `text`.
void replace_line(const std::string& path, int line, const std::string& text) {
  std::istringstream in(read_file(path));
  std::string out, l;
  for (int n = 1; std::getline(in, l); ++n) out += (n == line ? text : l) + "\n";
  write_file_atomic(path, out);
}

std::string line_of(const std::string& path, int line) {
  std::istringstream in(read_file(path));
  std::string l;
  for (int n = 1; std::getline(in, l) && n < line; ++n) {
  }
  return l;
}

// The message of the Error compare_outputs throws, checking its kind.
std::string refusal(const std::string& a, const std::string& b, ErrorKind kind,
                    const CompareOptions& options = {}) {
  try {
    compare_outputs(a, b, options);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), kind) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "not refused";
  return "";
}

TEST(CompareOutputs, TwoCopiesOfAShotAreTheSame) {
  const test::TempDir dir("compare_same");
  const std::string a = elbow_copy(dir, "a"), b = elbow_copy(dir, "b");
  fs::create_directories(fs::path(a) / "dumps");  // neither a subfolder nor a dot-file is a frame
  write_file_atomic(a + "/.elbow.0001.obj.tmp.x", "junk");
  std::vector<std::string> seen;
  const CompareResult r =
      compare_outputs(a, b, {}, [&](const ComparedFrame& f) { seen.push_back(f.a); });
  ASSERT_EQ(r.frames.size(), 5u);
  EXPECT_EQ(seen.size(), 5u);
  EXPECT_EQ(r.frames[2].a, a + "/elbow.0003.obj");
  EXPECT_EQ(r.frames[2].b, b + "/elbow.0003.obj");
  EXPECT_EQ(r.differing(), 0u);
  EXPECT_TRUE(r.faces_checked);
  EXPECT_EQ(r.diagonal_from, "");  // no bind: each frame's distances in its own diagonal
  EXPECT_NEAR(r.frames[0].diagonal, std::sqrt(2 * 2 + 2 * 2 + 8 * 8), 1e-6);  // tube r 1, length 8
  const ObjMesh bent = read_obj(a + "/elbow.0005.obj");
  EXPECT_EQ(r.frames[4].diagonal, bounding_box_diagonal(bent.mesh.positions));
  EXPECT_LT(r.frames[4].diagonal, r.frames[0].diagonal);  // the bent tube's box is shorter
  for (const ComparedFrame& f : r.frames) EXPECT_EQ(f.difference.vertex, -1);
}

TEST(CompareOutputs, ALastDigitChangedIsWithinTheTolerance) {
  const test::TempDir dir("compare_last_digit");
  const std::string a = elbow_copy(dir, "a"), b = elbow_copy(dir, "b");
  // Line 4 is vertex 1's `v` line, "v 0.98078528 0.195090322 0.0" (vertex v on line v + 3): the
  // last digit of its x one up, 1e-8.
  const std::string v = line_of(b + "/elbow.0003.obj", 4);
  ASSERT_EQ(v.rfind("v 0.98078528 ", 0), 0u) << v;
  replace_line(b + "/elbow.0003.obj", 4, "v 0.98078529" + v.substr(12));
  const CompareResult r = compare_outputs(a, b, {});
  EXPECT_EQ(r.differing(), 0u);
  const FrameDifference& d = r.frames[2].difference;
  EXPECT_EQ(d.vertex, 1);
  EXPECT_NEAR(d.max_distance, 1e-8 / r.frames[2].diagonal, 1e-15);  // 1.2e-9 of the diagonal
  EXPECT_EQ(r.largest(), 2);
  // At tolerance 0 the frame differs: vertex 0, on line 3 of A's file.
  CompareOptions exact;
  exact.tolerance = 0;
  const CompareResult r0 = compare_outputs(a, b, exact);
  EXPECT_EQ(r0.differing(), 1u);
  EXPECT_TRUE(r0.frames[2].differs);
  EXPECT_EQ(r0.frames[2].vertex_at, a + "/elbow.0003.obj:4");
}

TEST(CompareOutputs, ARealDifferenceNamesTheFrameAndVertex) {
  const test::TempDir dir("compare_real");
  const std::string a = elbow_copy(dir, "a"), b = elbow_copy(dir, "b");
  // elbow.0004.obj's vertex 500 (line 503) a hundredth of the radius off.
  const ObjMesh frame = read_obj(b + "/elbow.0004.obj");
  const Vec3 p = frame.mesh.positions[500] + Vec3(0.01, 0, 0);
  std::ostringstream v;
  v.precision(17);
  v << "v " << p.x() << " " << p.y() << " " << p.z();
  replace_line(b + "/elbow.0004.obj", 503, v.str());
  const CompareResult r = compare_outputs(a, b, {});
  EXPECT_EQ(r.differing(), 1u);
  EXPECT_TRUE(r.frames[3].differs);
  EXPECT_EQ(r.frames[3].difference.vertex, 500);
  EXPECT_EQ(r.frames[3].vertex_at, a + "/elbow.0004.obj:503");
  EXPECT_NEAR(r.frames[3].difference.max_distance, 0.01 / r.frames[3].diagonal, 1e-12);
  EXPECT_EQ(r.largest(), 3);
}

TEST(CompareOutputs, AMissingFrameIsRefusedNamingIt) {
  const test::TempDir dir("compare_missing");
  const std::string a = elbow_copy(dir, "a"), b = elbow_copy(dir, "b");
  fs::remove(b + "/elbow.0004.obj");
  const std::string m = refusal(a, b, ErrorKind::Input);
  EXPECT_NE(m.find(a + " has 5 frames, " + b + " 4; missing from " + b + ": elbow.0004.obj"),
            std::string::npos)
      << m;
  // And one only B has.
  fs::copy_file(b + "/elbow.0005.obj", b + "/elbow.0006.obj");
  const std::string both = refusal(a, b, ErrorKind::Input);
  EXPECT_NE(both.find("missing from " + a + ": elbow.0006.obj"), std::string::npos) << both;
  EXPECT_NE(both.find("(--common compares the frames both hold)"), std::string::npos) << both;
}

TEST(CompareOutputs, CommonComparesTheFramesBothHoldNamingTheRest) {
  const test::TempDir dir("compare_common");
  const std::string a = elbow_copy(dir, "a"), b = elbow_copy(dir, "b");
  fs::remove(b + "/elbow.0001.obj");  // a chunk: frames 2-4 and one A lacks
  fs::remove(b + "/elbow.0005.obj");
  fs::copy_file(b + "/elbow.0004.obj", b + "/elbow.0006.obj");
  CompareOptions common;
  common.common = true;
  const CompareResult r = compare_outputs(a, b, common);
  ASSERT_EQ(r.frames.size(), 3u);
  EXPECT_EQ(r.frames[0].a, a + "/elbow.0002.obj");
  EXPECT_EQ(r.differing(), 0u);
  EXPECT_EQ(r.only_in_a, (std::vector<std::string>{a + "/elbow.0001.obj", a + "/elbow.0005.obj"}));
  EXPECT_EQ(r.only_in_b, (std::vector<std::string>{b + "/elbow.0006.obj"}));
  // Nothing in common is still refused.
  const std::string c = dir / "c";
  fs::create_directories(c);
  fs::copy_file(b + "/elbow.0006.obj", c + "/elbow.0007.obj");
  const std::string m = refusal(a, c, ErrorKind::Input, common);
  EXPECT_NE(m.find("have no frame in common"), std::string::npos) << m;
}

TEST(CompareOutputs, EachMeshOfAFolderInItsOwnDiagonal) {
  // A folder holding two meshes' frames: the elbow's and a copy scaled by 10. The same vertex
  // moved by the same share of each mesh's size reads the same distance in each.
  const test::TempDir dir("compare_two_meshes");
  const std::string a = elbow_copy(dir, "a"), b = elbow_copy(dir, "b");
  const std::string frame = read_file(a + "/elbow.0003.obj");
  // elbow.0003.obj's text with its `v` lines scaled, vertex 9's x then moved by nudge x scale.
  const auto write_scaled = [&](const std::string& path, double scale, double nudge) {
    std::istringstream in(frame);
    std::ostringstream obj;
    obj.precision(17);
    int v = 0;
    for (std::string l; std::getline(in, l);) {
      if (l.rfind("v ", 0) != 0) {
        obj << l << "\n";
        continue;
      }
      std::istringstream xyz(l.substr(2));
      double x = 0, y = 0, z = 0;
      xyz >> x >> y >> z;
      obj << "v " << scale * x + (v++ == 9 ? nudge * scale : 0) << " " << scale * y << " "
          << scale * z << "\n";
    }
    write_file_atomic(path, obj.str());
  };
  write_scaled(a + "/big.0003.obj", 10, 0);
  write_scaled(b + "/big.0003.obj", 10, 0.01);
  write_scaled(a + "/elbow.0003.obj", 1, 0);
  write_scaled(b + "/elbow.0003.obj", 1, 0.01);
  const CompareResult r = compare_outputs(a, b, {});
  ASSERT_EQ(r.frames.size(), 6u);
  EXPECT_EQ(r.frames[0].a, a + "/big.0003.obj");  // the first frame: the big mesh's
  EXPECT_EQ(r.frames[3].a, a + "/elbow.0003.obj");
  EXPECT_NEAR(r.frames[0].diagonal, 10 * r.frames[3].diagonal, 1e-9);
  EXPECT_NEAR(r.frames[0].difference.max_distance, r.frames[3].difference.max_distance, 1e-12);
  EXPECT_NEAR(r.frames[3].difference.max_distance, 0.01 / r.frames[3].diagonal, 1e-12);
}

TEST(CompareOutputs, VertexAndFaceCountsMustMatch) {
  const test::TempDir dir("compare_counts");
  const std::string a = elbow_copy(dir, "a"), b = elbow_copy(dir, "b");
  const PolyMesh grid = test::quad_grid(2, 2);
  std::string obj;
  for (const Vec3& p : grid.positions) obj += "v " + std::to_string(p.x()) + " 0 0\n";
  obj += "f 1 2 5 4\n";
  write_file_atomic(b + "/elbow.0002.obj", obj);
  std::string m = refusal(a, b, ErrorKind::Input);
  EXPECT_NE(m.find(b + "/elbow.0002.obj: has 9 vertices; " + a + "/elbow.0002.obj has 1056"),
            std::string::npos)
      << m;
  // The same vertices, one face fewer: the file cut after its last `v` line and a face.
  const std::string text = read_file(a + "/elbow.0002.obj");
  write_file_atomic(b + "/elbow.0002.obj", text.substr(0, text.rfind("\nf ") + 1));
  m = refusal(a, b, ErrorKind::Input);
  EXPECT_NE(m.find(b + "/elbow.0002.obj: has 1023 faces; " + a + "/elbow.0002.obj has 1024"),
            std::string::npos)
      << m;
}

TEST(CompareOutputs, KindsThatDoNotPairAreUsageErrors) {
  const test::TempDir dir("compare_kinds");
  const std::string a = elbow_copy(dir, "a");
  EXPECT_NE(refusal(a, a + "/elbow.0001.obj", ErrorKind::Usage).find("are not alike"),
            std::string::npos);
  EXPECT_NE(refusal(a, dir / "none", ErrorKind::Input).find("no such file or folder"),
            std::string::npos);
  write_file_atomic(dir / "notes.txt", "x");
  EXPECT_NE(refusal(dir / "notes.txt", dir / "notes.txt", ErrorKind::Usage).find("neither"),
            std::string::npos);
  CompareOptions negative;
  negative.tolerance = -1;
  EXPECT_NE(refusal(a, a, ErrorKind::Usage, negative).find("--tolerance -1"), std::string::npos);
  fs::create_directories(dir / "empty");
  EXPECT_NE(refusal(dir / "empty", a, ErrorKind::Input).find("holds no frame"), std::string::npos);
}

// A PC2 of data/elbow's first `samples` frames (float32), sample 0 at `start_frame`; `nudge`
// moves sample 1's vertex 7 along z.
void write_elbow_pc2(const std::string& path, float start_frame, int samples, float nudge = 0) {
  CacheHeader h;
  h.points = 1056;
  h.samples = samples;
  h.start_frame = start_frame;
  CacheWriter w(path, h);
  for (int k = 0; k < samples; ++k) {
    const ObjMesh f = read_obj(kElbowFrames + "/elbow.000" + std::to_string(k + 1) + ".obj");
    CacheSample s;
    for (const Vec3& p : f.mesh.positions)
      for (int i = 0; i < 3; ++i) s.push_back(static_cast<float>(p[i]));
    if (k == 1) s[3 * 7 + 2] += nudge;  // sample 1, vertex 7, z
    w.write_sample(k, s);
  }
  w.commit();
}

TEST(CompareOutputs, CachesSampleBySample) {
  const test::TempDir dir("compare_caches");
  write_elbow_pc2(dir / "a.pc2", 1, 3);
  write_elbow_pc2(dir / "b.pc2", 1, 3);
  const CompareResult same = compare_outputs(dir / "a.pc2", dir / "b.pc2", {});
  ASSERT_EQ(same.frames.size(), 3u);
  EXPECT_EQ(same.frames[1].a, dir / "a.pc2" + " sample 1 (frame 2)");
  EXPECT_EQ(same.differing(), 0u);
  EXPECT_FALSE(same.faces_checked);  // a cache has no faces
  EXPECT_EQ(same.diagonal_from, "");
  // A real difference, and the bind's faces and diagonal with --bind.
  write_elbow_pc2(dir / "b.pc2", 1, 3, 0.05f);
  CompareOptions with_bind;
  with_bind.bind = test::source_path("data/elbow/bind.obj");
  const CompareResult r = compare_outputs(dir / "a.pc2", dir / "b.pc2", with_bind);
  EXPECT_TRUE(r.faces_checked);
  EXPECT_EQ(r.diagonal_from, with_bind.bind);
  EXPECT_EQ(r.differing(), 1u);
  EXPECT_EQ(r.frames[1].difference.vertex, 7);
  EXPECT_NEAR(r.frames[1].difference.max_distance * r.diagonal, 0.05, 1e-6);
  EXPECT_EQ(r.frames[1].diagonal, r.diagonal);
}

TEST(CompareOutputs, CommonPairsCacheSamplesByFrameNumber) {
  const test::TempDir dir("compare_cache_common");
  write_elbow_pc2(dir / "a.pc2", 1, 4);        // frames 1-4
  write_elbow_pc2(dir / "chunk.pc2", 3, 2);    // frames 3-4, data/elbow's first two
  write_elbow_pc2(dir / "same.pc2", 1, 2);     // the chunk's positions at frames 1-2
  CompareOptions common;
  common.common = true;
  const CompareResult r = compare_outputs(dir / "a.pc2", dir / "chunk.pc2", common);
  ASSERT_EQ(r.frames.size(), 2u);
  EXPECT_EQ(r.frames[0].a, dir / "a.pc2" + " sample 2 (frame 3)");
  EXPECT_EQ(r.frames[0].b, dir / "chunk.pc2" + " sample 0 (frame 3)");
  EXPECT_EQ(r.differing(), 2u);  // frame 3 of A against elbow.0001's positions
  EXPECT_EQ(r.only_in_a, (std::vector<std::string>{dir / "a.pc2" + " sample 0 (frame 1)",
                                                    dir / "a.pc2" + " sample 1 (frame 2)"}));
  EXPECT_TRUE(r.only_in_b.empty());
  const CompareResult s = compare_outputs(dir / "same.pc2", dir / "a.pc2", common);
  EXPECT_EQ(s.frames.size(), 2u);
  EXPECT_EQ(s.differing(), 0u);
  EXPECT_EQ(s.only_in_b.size(), 2u);
  write_elbow_pc2(dir / "later.pc2", 7, 2);
  const std::string m = refusal(dir / "a.pc2", dir / "later.pc2", ErrorKind::Input, common);
  EXPECT_NE(m.find("no sample in common"), std::string::npos) << m;
}

TEST(CompareOutputs, CachesOfOtherFramesAreRefused) {
  const test::TempDir dir("compare_cache_frames");
  write_elbow_pc2(dir / "a.pc2", 1, 3);
  write_elbow_pc2(dir / "b.pc2", 1, 2);
  std::string m = refusal(dir / "a.pc2", dir / "b.pc2", ErrorKind::Input);
  EXPECT_NE(m.find(dir / "b.pc2" + ": has 2 samples; " + dir / "a.pc2" + " has 3"),
            std::string::npos)
      << m;
  write_elbow_pc2(dir / "b.pc2", 0, 3);
  m = refusal(dir / "a.pc2", dir / "b.pc2", ErrorKind::Input);
  EXPECT_NE(m.find("sample 0 is frame 0; in " + dir / "a.pc2" + " frame 1"), std::string::npos)
      << m;
  CompareOptions grid_bind;
  write_file_atomic(dir / "grid.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  grid_bind.bind = dir / "grid.obj";
  m = refusal(dir / "a.pc2", dir / "a.pc2", ErrorKind::Input, grid_bind);
  EXPECT_NE(m.find("has 1056 vertices; the bind (" + dir / "grid.obj" + ") has 4"),
            std::string::npos)
      << m;
}

TEST(CompareReport, JsonWithEveryFrameAndTheTotals) {
  const test::TempDir dir("compare_report");
  const std::string a = elbow_copy(dir, "a\"q"), b = elbow_copy(dir, "b");
  const std::string json = compare_report_json(compare_outputs(a, b, {}));
  EXPECT_EQ(json, compare_report_json(compare_outputs(a, b, {})));  // no timings: same bytes
  EXPECT_NE(json.find("\"a\": \"" + dir.path().string() + "/a\\\"q\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"tolerance\": 1e-06"), std::string::npos);
  EXPECT_NE(json.find("\"differing_frames\": 0,\n  \"largest\": {\"frame\": 0, \"max_distance\": "
                      "0},\n  \"same\": true\n}\n"),
            std::string::npos)
      << json;
  const std::string empty = compare_report_json(CompareResult{});
  EXPECT_NE(empty.find("\"frames\": [],"), std::string::npos) << empty;
  EXPECT_NE(empty.find("\"diagonal\": null,\n  \"diagonal_from\": null"), std::string::npos)
      << empty;
  EXPECT_NE(empty.find("\"only_in_a\": [],\n  \"only_in_b\": [],"), std::string::npos) << empty;
  EXPECT_NE(empty.find("\"largest\": null"), std::string::npos) << empty;
}

}  // namespace
}  // namespace skinslide
