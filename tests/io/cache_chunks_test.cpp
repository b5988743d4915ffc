#include "io/cache_chunks.h"

#include <gtest/gtest.h>

#include <bit>
#include <filesystem>

#include "core/error.h"
#include "helpers/temp_dir.h"
#include "io/atomic_write.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

// A whole cache of `samples` samples of 3 points, every coordinate distinct.
CacheHeader whole_header(CacheFormat format, int samples, float start = 1, float rate = 1) {
  CacheHeader h;
  h.format = format;
  h.points = 3;
  h.samples = samples;
  h.start_frame = start;
  h.sample_rate = rate;
  if (format == CacheFormat::Mdd)
    for (int k = 0; k < samples; ++k) h.times.push_back(0.5f + k / 30.0f);
  return h;
}

CacheSample sample_of(std::size_t k) {
  CacheSample s(9);
  for (std::size_t i = 0; i < 9; ++i) s[i] = float(k) * 10 + float(i) * 0.125f;
  return s;
}

void write_cache(const std::string& path, const CacheHeader& h, std::size_t first) {
  CacheWriter w(path, h);
  for (std::size_t k = 0; k < static_cast<std::size_t>(h.samples); ++k)
    w.write_sample(k, sample_of(first + k));
  w.commit();
}

// Writes the chunks [first, last] (sample indices) of `whole` into `dir` as a task would, and
// returns their paths.
std::vector<std::string> write_chunks(const test::TempDir& dir, const CacheHeader& whole,
                                      const std::vector<std::pair<int, int>>& runs) {
  std::vector<std::string> paths;
  for (const auto& [a, b] : runs) {
    const CacheHeader h = chunk_header(whole, a, b - a + 1);
    const std::string ext = std::string(".") + to_string(whole.format);
    paths.push_back(dir /
                    chunk_file_name("shot", sample_frame(whole, a), sample_frame(whole, b), ext));
    write_cache(paths.back(), h, a);
  }
  return paths;
}

std::string join_refusal(const std::vector<std::string>& chunks, const std::string& out) {
  try {
    join_cache_chunks(chunks, out);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
    return e.what();
  }
  return "";
}

TEST(CacheChunks, Names) {
  EXPECT_EQ(chunk_file_name("shot", 101, 200, ".pc2"), "shot.0101-0200.pc2");
  EXPECT_EQ(chunk_file_name("a.b", 0, 12345, ".MDD"), "a.b.0000-12345.MDD");
  const auto n = parse_chunk_name("farm/out/a.b.0101-0200.pc2");
  ASSERT_TRUE(n);
  EXPECT_EQ(n->stem, "a.b");
  EXPECT_EQ(n->first, 101);
  EXPECT_EQ(n->last, 200);
  EXPECT_EQ(n->extension, ".pc2");
  for (const char* bad : {"shot.pc2", "shot.0200-0101.pc2", "shot.1-x.pc2", ".0001-0002.pc2",
                          "shot.-0001-0002.pc2", "shot.0001-.pc2"})
    EXPECT_FALSE(parse_chunk_name(bad)) << bad;
}

TEST(CacheChunks, ChunkHeaders) {
  const CacheHeader pc2 = whole_header(CacheFormat::Pc2, 10, -0.0f, 0.1f);
  const CacheHeader first = chunk_header(pc2, 0, 4);
  EXPECT_EQ(first.samples, 4);
  // Sample 0's chunk keeps startFrame's bits (here -0: adding 0 * rate would make it +0).
  EXPECT_EQ(std::bit_cast<std::uint32_t>(first.start_frame), std::bit_cast<std::uint32_t>(-0.0f));
  const CacheHeader later = chunk_header(pc2, 4, 6);
  EXPECT_EQ(later.start_frame, float(4 * double(0.1f)));
  EXPECT_EQ(later.sample_rate, 0.1f);
  const CacheHeader mdd = chunk_header(whole_header(CacheFormat::Mdd, 5), 2, 2);
  EXPECT_EQ(mdd.times, (std::vector<float>{0.5f + 2 / 30.0f, 0.5f + 3 / 30.0f}));
}

// The farm's promise: chunks joined in any order are the one-task cache, byte for byte.
TEST(CacheChunks, JoinedChunksAreTheWholeCacheByteForByte) {
  for (const CacheFormat format : {CacheFormat::Pc2, CacheFormat::Mdd}) {
    const test::TempDir dir(std::string("join_") + to_string(format));
    const CacheHeader whole = whole_header(format, 10, 1.0f, 0.25f);
    const std::string ext = std::string(".") + to_string(format);
    write_cache(dir / ("whole" + ext), whole, 0);
    std::vector<std::string> chunks = write_chunks(dir, whole, {{8, 9}, {0, 3}, {4, 7}});
    const JoinResult r = join_cache_chunks(chunks, dir / "joined");
    EXPECT_EQ(r.output, dir / "joined" + "/shot" + ext);
    EXPECT_EQ(r.chunks, 3u);
    EXPECT_EQ(read_file(r.output), read_file(dir / ("whole" + ext)));
  }
}

TEST(CacheChunks, JoinRefusesGapsOverlapsAndMismatches) {
  const test::TempDir dir("join_bad");
  const CacheHeader whole = whole_header(CacheFormat::Pc2, 10);
  const auto chunks = write_chunks(dir, whole, {{0, 3}, {4, 6}, {7, 9}});
  EXPECT_TRUE(join_refusal({chunks[0], chunks[2]}, dir / "out")
                  .ends_with("shot.0008-0010.pc2: starts at frame 8 but the chunks before it "
                             "end one sample before frame 5: the samples between are missing"));
  // Overlap: a chunk of samples 3-5 beside 0-3.
  const auto overlapping = write_chunks(dir, whole, {{3, 5}});
  EXPECT_TRUE(
      join_refusal({chunks[0], overlapping[0]}, dir / "out")
          .ends_with("shot.0004-0006.pc2: frames 4-6 overlap " + chunks[0] + "'s frames 1-4"));
  // Renamed: the name no longer tells its frames.
  fs::copy_file(chunks[1], dir / "shot.0005-0009.pc2");
  EXPECT_TRUE(join_refusal({chunks[0], dir / "shot.0005-0009.pc2"}, dir / "out")
                  .find("its name says frames 5-9, but its 3 samples are frames 5-7") !=
              std::string::npos);
  EXPECT_TRUE(join_refusal({dir / "whole.pc2"}, dir / "out").find("not a chunk's name") !=
              std::string::npos);
  // Another point count.
  CacheHeader other = chunk_header(whole, 4, 3);
  other.points = 2;
  const std::string two = dir / "sub/shot.0005-0007.pc2";
  fs::create_directories(dir / "sub");
  {
    CacheWriter w(two, other);
    for (int k = 0; k < 3; ++k) w.write_sample(k, CacheSample(6, 1.0f));
    w.commit();
  }
  EXPECT_TRUE(join_refusal({chunks[0], two}, dir / "out")
                  .ends_with("has 2 points; " + chunks[0] + " has 3"));
  EXPECT_FALSE(fs::exists(dir / "out/shot.pc2"));  // nothing written by a refused join
}

TEST(CacheChunks, MddJoinChecksFramesAndTimes) {
  const test::TempDir dir("join_mdd");
  const CacheHeader whole = whole_header(CacheFormat::Mdd, 6);
  const auto chunks = write_chunks(dir, whole, {{0, 1}, {2, 3}, {4, 5}});
  EXPECT_TRUE(join_refusal({chunks[0], chunks[2]}, dir / "out")
                  .ends_with("starts at frame 4 but the chunks before it end at frame 1: the "
                             "frames between are missing"));
  // Times that go back across chunks.
  CacheHeader back = chunk_header(whole, 2, 2);
  back.times = {0.1f, 0.2f};
  fs::create_directories(dir / "b");
  write_cache(dir / "b/shot.0002-0003.mdd", back, 2);
  EXPECT_TRUE(join_refusal({chunks[0], dir / "b/shot.0002-0003.mdd"}, dir / "out")
                  .find("its first time (0.1 s) is not after the last of") != std::string::npos);
}

}  // namespace
}  // namespace skinslide
