// Point caches as a run's frames and output (pipeline/cache_frames.h through pipeline/run.h),
// against the same frames given as OBJ files: the slide must not depend on where a frame comes
// from, and a cache's unslid coordinates come back bit for bit.

#include "pipeline/cache_frames.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "helpers/meshes.h"
#include "helpers/shared_data.h"
#include "helpers/temp_dir.h"
#include "io/atomic_write.h"
#include "io/cache_chunks.h"
#include "io/gltf/gltf.h"
#include "io/mesh_formats.h"
#include "io/obj_read.h"
#include "io/obj_rewrite.h"
#include "pipeline/run.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

const int kFrames = 5;  // data/elbow/frames

std::string elbow(const std::string& relative) {
  return test::source_path("data/elbow/" + relative);
}

// data/elbow's frames rounded to float32 (a cache's precision), as one sample each.
std::vector<CacheSample> elbow_samples() {
  std::vector<CacheSample> samples;
  for (int f = 1; f <= kFrames; ++f)
    samples.push_back(positions_sample(
        read_mesh_file(elbow("frames/elbow.000" + std::to_string(f) + ".obj")).mesh.positions));
  return samples;
}

// Writes `samples` as a cache (PC2: frames 1.., MDD: 1/24 s apart) at `path`.
void write_cache(const std::string& path, const std::vector<CacheSample>& samples) {
  CacheHeader h;
  h.format = *cache_format(path);
  h.points = static_cast<std::int32_t>(samples[0].size() / 3);
  h.samples = static_cast<std::int32_t>(samples.size());
  h.start_frame = 1;
  for (std::size_t k = 0; k < samples.size(); ++k) h.times.push_back(float(k) / 24);
  if (h.format == CacheFormat::Pc2) h.times.clear();
  CacheWriter w(path, h);
  for (std::size_t k = 0; k < samples.size(); ++k) w.write_sample(k, samples[k]);
  w.commit();
}

// The same samples as OBJ frames: the bind's file with every vertex at its float32 position.
std::vector<std::string> write_obj_frames(const test::TempDir& dir,
                                          const std::vector<CacheSample>& samples) {
  const ObjMesh bind = read_obj(elbow("bind.obj"));
  std::vector<std::string> paths;
  fs::create_directories(dir / "objs");
  for (std::size_t k = 0; k < samples.size(); ++k) {
    paths.push_back(dir / ("objs/elbow.000" + std::to_string(k + 1) + ".obj"));
    write_file_atomic(paths.back(),
                      rewrite_obj(bind.text, bind.mesh.positions, sample_positions(samples[k])));
  }
  return paths;
}

RunOptions cache_run(const std::string& cache, const std::string& output) {
  RunOptions o;
  o.bind = elbow("bind.obj");
  o.patches = {elbow("patch.txt")};
  o.frames = {cache};
  o.output = output;
  o.threads = 2;
  return o;
}

std::uint32_t bits(float x) { return std::bit_cast<std::uint32_t>(x); }

// The slid cache holds, for every vertex, the OBJ run's slid position rounded once to float32;
// and each vertex the slide left where it was keeps the input's bits.
TEST(CacheFrames, SlideAsTheSameFramesGivenAsObjFiles) {
  const test::TempDir dir("cache_vs_obj");
  const std::vector<CacheSample> samples = elbow_samples();
  const std::vector<std::string> objs = write_obj_frames(dir, samples);
  RunOptions o = cache_run(dir / "elbow.pc2", dir / "slid_obj");
  o.frames = objs;
  run(o);
  for (const std::string ext : {"pc2", "mdd"}) {
    write_cache(dir / ("elbow." + ext), samples);
    run(cache_run(dir / ("elbow." + ext), dir / "slid_cache"));
    const CacheReader in(dir / ("elbow." + ext));
    const CacheReader out(dir / ("slid_cache/elbow." + ext));
    EXPECT_EQ(read_file(dir / ("slid_cache/elbow." + ext)).substr(0, header_bytes(in.header())),
              read_file(dir / ("elbow." + ext)).substr(0, header_bytes(in.header())));
    std::size_t moved = 0;
    for (int k = 0; k < kFrames; ++k) {
      const Positions3 slid =
          read_mesh_file(dir / ("slid_obj/elbow.000" + std::to_string(k + 1) + ".obj"))
              .mesh.positions;
      const CacheSample got = out.sample(k), before = in.sample(k);
      ASSERT_EQ(got.size(), 3 * slid.size());
      for (std::size_t i = 0; i < got.size(); ++i) {
        EXPECT_EQ(bits(got[i]), bits(static_cast<float>(slid[i / 3][i % 3]))) << k << " " << i;
        if (slid[i / 3][i % 3] == double(before[i])) {
          EXPECT_EQ(bits(got[i]), bits(before[i]));
        }
      }
      for (std::size_t v = 0; v < slid.size(); ++v) moved += slid[v] != sample_positions(before)[v];
    }
    EXPECT_GT(moved, 100u);  // the elbow's patch slides: the comparison is not of copies
  }
}

// One file a frame from a cache: the bind's own OBJ text with the frame's positions, which is
// what sliding that frame's OBJ file writes, byte for byte.
TEST(CacheFrames, FormatObjWritesTheFramesAnObjRunWrites) {
  const test::TempDir dir("cache_to_obj");
  const std::vector<CacheSample> samples = elbow_samples();
  RunOptions o = cache_run(dir / "elbow.pc2", dir / "a");
  o.frames = write_obj_frames(dir, samples);
  run(o);
  write_cache(dir / "elbow.pc2", samples);
  o = cache_run(dir / "elbow.pc2", dir / "b");
  o.format = "obj";
  o.frame_ranges = "2-4";
  run(o);
  for (int f = 1; f <= kFrames; ++f) {
    const std::string name = "elbow.000" + std::to_string(f) + ".obj";
    if (f < 2 || f > 4) {
      EXPECT_FALSE(fs::exists(dir / ("b/" + name)));
      continue;
    }
    EXPECT_EQ(read_file(dir / ("b/" + name)), read_file(dir / ("a/" + name))) << name;
  }
}

// The farm's case: any thread count, and chunks joined, give the one-task bytes.
TEST(CacheFrames, ThreadsAndChunksGiveTheSameBytes) {
  const test::TempDir dir("cache_chunks_run");
  write_cache(dir / "elbow.mdd", elbow_samples());
  RunOptions o = cache_run(dir / "elbow.mdd", dir / "one");
  o.threads = 1;
  run(o);
  o.output = dir / "chunks";
  o.threads = 2;
  std::vector<std::string> chunks;
  for (const char* range : {"3-99", "0-2"}) {  // MDD frames are sample indices from 0
    o.frame_ranges = range;
    run(o);
  }
  EXPECT_TRUE(fs::exists(dir / "chunks/elbow.0000-0002.mdd"));
  EXPECT_TRUE(fs::exists(dir / "chunks/elbow.0003-0004.mdd"));  // clamped to the cache's end
  join_cache_chunks({dir / "chunks/elbow.0003-0004.mdd", dir / "chunks/elbow.0000-0002.mdd"},
                    dir / "joined");
  EXPECT_EQ(read_file(dir / "joined/elbow.mdd"), read_file(dir / "one/elbow.mdd"));
}

TEST(CacheFrames, NoSlideCopiesTheCacheByteForByte) {
  const test::TempDir dir("cache_no_slide");
  write_cache(dir / "elbow.pc2", elbow_samples());
  RunOptions o = cache_run(dir / "elbow.pc2", dir / "out");
  o.no_slide = true;
  run(o);
  EXPECT_EQ(read_file(dir / "out/elbow.pc2"), read_file(dir / "elbow.pc2"));
}

// The Error(kind) message running `o` gives; "" when it runs.
std::string refusal(const RunOptions& o, ErrorKind kind) {
  try {
    run(o);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), kind) << e.what();
    return e.what();
  }
  return "";
}

TEST(CacheFrames, Refusals) {
  const test::TempDir dir("cache_refusals");
  std::vector<CacheSample> samples = elbow_samples();
  write_cache(dir / "elbow.pc2", samples);
  RunOptions o = cache_run(dir / "elbow.pc2", dir / "out");
  o.frame_ranges = "1-5:2";
  EXPECT_TRUE(refusal(o, ErrorKind::Usage)
                  .starts_with("--frames selects samples with gaps between them (frames 1 to 5, "
                               "3 samples): a cache holds one run of samples"));
  o.frame_ranges = "9-20";
  EXPECT_EQ(refusal(o, ErrorKind::Usage),
            "--frames 9-20 selects none of the cache's 5 samples (frames 1 to 5)");
  o.frame_ranges = "";
  o.format = "mdd";
  EXPECT_TRUE(refusal(o, ErrorKind::Usage)
                  .starts_with("--format mdd: " + dir / "elbow.pc2" + " is a pc2 cache"));
  o.format = "";
  // -o named as a cache of the other format: refused, not made a folder of that name.
  o.output = dir / "shot.mdd";
  EXPECT_EQ(refusal(o, ErrorKind::Usage),
            "-o " + dir / "shot.mdd" + ": names a mdd cache, but " + dir / "elbow.pc2" +
                " is a pc2 cache, written in its own format (PC2 frames and MDD times do not "
                "convert without a frame rate)");
  EXPECT_FALSE(std::filesystem::exists(dir / "shot.mdd"));
  o.output = dir / "out";
  o.frames.push_back(elbow("frames/elbow.0001.obj"));
  EXPECT_TRUE(refusal(o, ErrorKind::Usage).starts_with("a point cache is a whole shot"));
  o.frames = {dir / "elbow.pc2"};
  o.output = dir.path().string();
  EXPECT_EQ(refusal(o, ErrorKind::Usage), "output " + dir / "elbow.pc2" +
                                              " would overwrite input " + dir / "elbow.pc2" +
                                              "; choose another --output folder");
  // A chunk beside its input: joining the chunks would replace the shot they came from.
  o.frame_ranges = "1-2";
  EXPECT_EQ(refusal(o, ErrorKind::Usage), "output " + dir / "elbow.0001-0002.pc2" +
                                              ": its chunks would join into " + dir / "elbow.pc2" +
                                              ", which is input " + dir / "elbow.pc2" +
                                              "; choose another --output folder");
  o.frame_ranges = "";
  for (CacheSample& s : samples) s.resize(s.size() - 3);  // one point short
  write_cache(dir / "short.pc2", samples);
  o = cache_run(dir / "short.pc2", dir / "out");
  EXPECT_EQ(refusal(o, ErrorKind::Input),
            dir / "short.pc2" + ": has 1055 points; the bind (" + o.bind +
                ") has 1056 vertices: a cache must hold one point per bind vertex, in the bind's "
                "order");
  EXPECT_FALSE(fs::exists(dir / "out"));  // refused before the output folder is made
}

// A bad sample with --keep-going: every other sample is slid, and still no cache is written.
TEST(CacheFrames, ACacheWithAFailedSampleIsNotWritten) {
  const test::TempDir dir("cache_bad_sample");
  std::vector<CacheSample> samples = elbow_samples();
  write_cache(dir / "elbow.pc2", samples);
  std::string bytes = read_file(dir / "elbow.pc2");
  const std::uint32_t nan = 0x7fc00000u;
  std::memcpy(bytes.data() + 32 + 3 * samples[0].size() * 4 + 8, &nan, 4);  // sample 3
  write_file_atomic(dir / "bad.pc2", bytes);
  RunOptions o = cache_run(dir / "bad.pc2", dir / "out");
  o.keep_going = true;
  const RunResult result = run(o);
  ASSERT_EQ(result.failures.size(), 1u);
  EXPECT_EQ(std::string(result.failures[0].what()),
            dir / "bad.pc2" + ": byte " + std::to_string(32 + 3 * samples[0].size() * 4 + 8) +
                ": sample 3, point 0: coordinate z is NaN");
  EXPECT_TRUE(fs::is_empty(dir / "out"));
}

// A rigged glTF's clip written as a cache: each sample is the clip's frame as --format obj
// writes it, rounded to float32; MDD keeps the clip's times.
TEST(CacheFrames, AnimationWritesACache) {
  const test::TempDir dir("rig_cache");
  std::ofstream(dir / "patch.txt") << "0-1\n";
  RunOptions o;
  o.bind = test::source_path("tests/io/gltf/gltf_morph/skinned_morph.gltf");
  o.patches = {dir / "patch.txt"};
  o.rig = RigOptions{};
  o.output = dir / "out";
  o.format = "obj";
  run(o);
  o.format = "pc2";
  run(o);
  o.format = "mdd";
  run(o);
  const CacheReader pc2(dir / "out/skinned_morph.pc2"), mdd(dir / "out/skinned_morph.mdd");
  EXPECT_EQ(pc2.header().start_frame, 0.0f);
  EXPECT_EQ(pc2.header().sample_rate, 1.0f);
  EXPECT_EQ(mdd.header().times, (std::vector<float>{0, 0.5f, 1}));  // the clip's key times
  ASSERT_EQ(pc2.header().samples, 3);
  for (int k = 0; k < 3; ++k) {
    const Positions3 obj =
        read_mesh_file(dir / ("out/skinned_morph.000" + std::to_string(k) + ".obj")).mesh.positions;
    EXPECT_EQ(pc2.sample(k), positions_sample(obj));
    EXPECT_EQ(mdd.sample(k), positions_sample(obj));
  }
  o.frame_ranges = "1-2";
  o.format = "pc2";
  run(o);
  EXPECT_EQ(CacheReader(dir / "out/skinned_morph.0001-0002.pc2").sample(0), pc2.sample(1));
}

// A glTF bind: a cache holds one point per welded vertex (skinslide's order); one per raw vertex
// (before welding, split at seams) is refused as ambiguous. --format glb writes the bind's
// document with every raw copy at its welded vertex's cache position.
TEST(CacheFrames, GltfBindTakesWeldedPointsAndWritesGlb) {
  SKINSLIDE_REQUIRE_SHARED("data/gltf/CesiumMan.glb");
  const test::TempDir dir("cache_gltf");
  RunOptions o;
  o.bind = test::shared_dir() + "/data/gltf/CesiumMan.glb";
  const MeshFile bind = read_mesh_file(o.bind);
  const Index raw = gltf_raw_vertex_count(bind);
  ASSERT_GT(raw, bind.mesh.vertex_count());  // the character has seams
  std::ofstream(dir / "patch.txt") << "0-9\n";
  o.patches = {dir / "patch.txt"};
  o.output = dir / "out";
  o.no_slide = true;
  o.format = "glb";
  std::vector<CacheSample> samples(2, positions_sample(bind.mesh.positions));
  samples[1][0] += 0.25f;  // sample 1 moves welded vertex 0
  write_cache(dir / "walk.pc2", samples);
  o.frames = {dir / "walk.pc2"};
  run(o);
  const MeshFile frame = read_mesh_file(dir / "out/walk.0002.glb");
  EXPECT_EQ(positions_sample(frame.mesh.positions), samples[1]);
  EXPECT_TRUE(same_faces(frame.mesh, bind.mesh));
  std::vector<CacheSample> raw_samples(1, CacheSample(3 * static_cast<std::size_t>(raw), 0.0f));
  write_cache(dir / "raw.pc2", raw_samples);
  o.frames = {dir / "raw.pc2"};
  EXPECT_EQ(refusal(o, ErrorKind::Input),
            dir / "raw.pc2" + ": has " + std::to_string(raw) + " points; the bind (" + o.bind +
                ") has " + std::to_string(bind.mesh.vertex_count()) + " vertices. " +
                std::to_string(raw) +
                " is the bind's count of raw glTF vertices, before welding: the order of a cache "
                "over them is ambiguous (seams split vertices), so it is refused; a cache holds "
                "one point per welded vertex, in skinslide's order");
}

}  // namespace
}  // namespace skinslide
