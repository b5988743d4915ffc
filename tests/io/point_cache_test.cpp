#include "io/point_cache.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <thread>

#include "core/error.h"
#include "helpers/temp_dir.h"
#include "io/atomic_write.h"

namespace skinslide {
namespace {

// Bytes written out by hand, independently of the library's encoder: the layouts of Blender's
// exporters (io_export_pc2.py: struct '<12siiffi' then '<fff' a point; io_shape_mdd
// export_mdd.py: '>2i', '>%df' times, '>%df' coordinates).
std::string le32(std::uint32_t v) {
  return {char(v & 0xff), char((v >> 8) & 0xff), char((v >> 16) & 0xff), char(v >> 24)};
}
std::string be32(std::uint32_t v) {
  return {char(v >> 24), char((v >> 16) & 0xff), char((v >> 8) & 0xff), char(v & 0xff)};
}
std::string lef(float f) { return le32(std::bit_cast<std::uint32_t>(f)); }
std::string bef(float f) { return be32(std::bit_cast<std::uint32_t>(f)); }

// A cache of `samples` samples of 2 points: point p of sample k at (k, p, k * 0.1 + p).
float coordinate(int k, int p, int c) {
  return c == 0 ? float(k) : c == 1 ? float(p) : k * 0.1f + p;
}

std::string pc2_bytes(int samples, float start = 1, float rate = 1, int points = 2) {
  std::string b("POINTCACHE2\0", 12);
  b += le32(1) + le32(points) + lef(start) + lef(rate) + le32(samples);
  for (int k = 0; k < samples; ++k)
    for (int p = 0; p < points; ++p)
      for (int c = 0; c < 3; ++c) b += lef(coordinate(k, p, c));
  return b;
}

std::string mdd_bytes(int samples, int points = 2) {
  std::string b = be32(samples) + be32(points);
  for (int k = 0; k < samples; ++k) b += bef(k / 24.0f);
  for (int k = 0; k < samples; ++k)
    for (int p = 0; p < points; ++p)
      for (int c = 0; c < 3; ++c) b += bef(coordinate(k, p, c));
  return b;
}

// The Input error message reading `bytes` gives; "" when it reads (every sample too).
std::string refusal(CacheFormat format, const std::string& bytes) {
  try {
    CacheReader reader("c", format, bytes);
    for (int k = 0; k < reader.header().samples; ++k) reader.sample(k);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(PointCache, FormatFromTheFileName) {
  EXPECT_EQ(cache_format("shot/a.pc2"), CacheFormat::Pc2);
  EXPECT_EQ(cache_format("A.PC2"), CacheFormat::Pc2);
  EXPECT_EQ(cache_format("a.mdd"), CacheFormat::Mdd);
  EXPECT_FALSE(cache_format("a.obj").has_value());
  EXPECT_FALSE(cache_format("pc2").has_value());
}

TEST(PointCache, ReadsPc2AsBlenderWritesIt) {
  const std::string bytes = pc2_bytes(3, 1.0f, 0.5f);
  ASSERT_EQ(bytes.size(), 32u + 3 * 2 * 12);
  CacheReader reader("c.pc2", CacheFormat::Pc2, bytes);
  const CacheHeader& h = reader.header();
  EXPECT_EQ(h.points, 2);
  EXPECT_EQ(h.samples, 3);
  EXPECT_EQ(h.start_frame, 1.0f);
  EXPECT_EQ(h.sample_rate, 0.5f);
  EXPECT_EQ(header_bytes(h), 32u);
  EXPECT_EQ(sample_offset(h, 2), 32u + 2 * 24);
  EXPECT_EQ(cache_bytes(h), bytes.size());
  for (int k = 0; k < 3; ++k) {
    const CacheSample s = reader.sample(k);
    ASSERT_EQ(s.size(), 6u);
    for (int i = 0; i < 6; ++i) EXPECT_EQ(s[i], coordinate(k, i / 3, i % 3));
  }
  EXPECT_EQ(encode_header(h), bytes.substr(0, 32));
}

TEST(PointCache, ReadsMddAsBlenderWritesIt) {
  const std::string bytes = mdd_bytes(4);
  CacheReader reader("c.mdd", CacheFormat::Mdd, bytes);
  const CacheHeader& h = reader.header();
  EXPECT_EQ(h.points, 2);
  EXPECT_EQ(h.samples, 4);
  EXPECT_EQ(h.times, (std::vector<float>{0, 1 / 24.0f, 2 / 24.0f, 3 / 24.0f}));
  EXPECT_EQ(header_bytes(h), 8u + 16);
  EXPECT_EQ(cache_bytes(h), bytes.size());
  EXPECT_EQ(reader.sample(3)[5], coordinate(3, 1, 2));
  EXPECT_EQ(encode_header(h), bytes.substr(0, 24));
  EXPECT_EQ(encode_sample("c", CacheFormat::Mdd, 3, reader.sample(3)),
            bytes.substr(sample_offset(h, 3), 24));
}

TEST(PointCache, FrameNumbers) {
  CacheHeader h;
  h.start_frame = 1;
  h.sample_rate = 1;
  EXPECT_EQ(sample_frame(h, 0), 1);
  EXPECT_EQ(sample_frame(h, 99), 100);
  h.start_frame = -5;
  EXPECT_EQ(sample_frame(h, 2), -3);
  // Below a frame: each sample belongs to the whole frame it falls in.
  h.start_frame = 1;
  h.sample_rate = 0.5f;
  EXPECT_EQ(sample_frame(h, 0), 1);
  EXPECT_EQ(sample_frame(h, 1), 1);
  EXPECT_EQ(sample_frame(h, 2), 2);
  // 0.01 is below its decimal in float32: 100 samples on lands 2e-7 short of frame 2.
  h.sample_rate = 0.01f;
  ASSERT_LT(1.0 + 100 * double(0.01f), 2.0);
  EXPECT_EQ(sample_frame(h, 100), 2);
  EXPECT_EQ(sample_frame(h, 99), 1);
  h.format = CacheFormat::Mdd;  // MDD: the sample index
  EXPECT_EQ(sample_frame(h, 7), 7);
}

TEST(PointCache, EveryPrefixIsRefusedAsBadInput) {
  for (const CacheFormat format : {CacheFormat::Pc2, CacheFormat::Mdd}) {
    const std::string whole = format == CacheFormat::Pc2 ? pc2_bytes(3) : mdd_bytes(3);
    EXPECT_EQ(refusal(format, whole), "");
    for (std::size_t n = 0; n < whole.size(); ++n) {
      const std::string why = refusal(format, whole.substr(0, n));
      EXPECT_NE(why, "") << n << " bytes";
      EXPECT_TRUE(contains(why, "truncated") || contains(why, "empty")) << why;
    }
    EXPECT_TRUE(contains(refusal(format, whole + "x"), "1 bytes past the last sample"));
  }
  EXPECT_EQ(refusal(CacheFormat::Pc2, pc2_bytes(3).substr(0, 70)),
            "c: truncated: the header says 3 samples of 2 points; the file has 70 bytes, which "
            "hold 1 of them (sample 1 is cut at byte 70)");
}

TEST(PointCache, RefusesBadHeaders) {
  std::string b = pc2_bytes(2);
  b[0] = 'X';
  EXPECT_EQ(refusal(CacheFormat::Pc2, b),
            "c: not a PC2 point cache: it does not start with \"POINTCACHE2\\0\"");
  b = pc2_bytes(2);
  b.replace(12, 4, le32(2));
  EXPECT_EQ(refusal(CacheFormat::Pc2, b), "c: byte 12: PC2 version 2; only version 1 exists");
  EXPECT_EQ(refusal(CacheFormat::Pc2, pc2_bytes(0)),
            "c: byte 28: the sample count is 0: the cache holds no samples");
  EXPECT_EQ(refusal(CacheFormat::Pc2, pc2_bytes(2, 1, 0)),
            "c: byte 24: sampleRate 0: the frames from one sample to the next must be a finite "
            "number above 0");
  EXPECT_TRUE(contains(refusal(CacheFormat::Pc2, pc2_bytes(2, 1, -1)), "sampleRate -1"));
  EXPECT_TRUE(
      contains(refusal(CacheFormat::Pc2, pc2_bytes(2, std::nanf(""))), "byte 20: startFrame"));
  EXPECT_EQ(refusal(CacheFormat::Pc2, pc2_bytes(2, 1, 1, 0)),
            "c: byte 16: the point count is 0: a cache needs at least one point");
  b = pc2_bytes(2);
  b.replace(28, 4, le32(std::uint32_t(-3)));
  EXPECT_EQ(refusal(CacheFormat::Pc2, b),
            "c: byte 28: the sample count is -3: it cannot be negative");
  EXPECT_EQ(refusal(CacheFormat::Mdd, mdd_bytes(0)),
            "c: byte 0: the sample count is 0: the cache holds no samples");
  EXPECT_EQ(refusal(CacheFormat::Mdd, mdd_bytes(2, 0)),
            "c: byte 4: the point count is 0: a cache needs at least one point");
}

// Counts far beyond the file are refused from the file's size alone, before anything is
// allocated for them (the largest counts would need exabytes).
TEST(PointCache, HugeCountsAreRefusedBeforeAllocating) {
  std::string b("POINTCACHE2\0", 12);
  b += le32(1) + le32(0x7fffffff) + lef(1) + lef(1) + le32(0x7fffffff);
  EXPECT_TRUE(contains(refusal(CacheFormat::Pc2, b),
                       "truncated: the header says 2147483647 samples of 2147483647 points"));
  EXPECT_TRUE(contains(refusal(CacheFormat::Mdd, be32(0x7fffffff) + be32(0x7fffffff)),
                       "whose header alone is 8589934596 bytes; the file has 8"));
  // Through a file too: the reader reads MDD's times only once they fit in the file.
  const test::TempDir dir("cache_huge");
  write_file_atomic(dir / "huge.mdd", be32(0x7fffffff) + be32(1) + std::string(64, '\0'));
  EXPECT_THROW(CacheReader(dir / "huge.mdd"), Error);
}

TEST(PointCache, RefusesMddTimesThatDoNotIncrease) {
  std::string b = mdd_bytes(3);
  b.replace(8 + 8, 4, bef(1 / 24.0f));  // sample 2 at sample 1's time
  EXPECT_EQ(refusal(CacheFormat::Mdd, b),
            "c: byte 16: the time of sample 2 (0.041666668 s) is not after sample 1's "
            "(0.041666668 s): MDD times must increase");
  b.replace(8 + 8, 4, bef(0.01f));
  EXPECT_TRUE(contains(refusal(CacheFormat::Mdd, b), "is not after sample 1's"));
  b.replace(8 + 4, 4, bef(std::numeric_limits<float>::infinity()));
  EXPECT_EQ(refusal(CacheFormat::Mdd, b), "c: byte 12: the time of sample 1 is inf");
}

TEST(PointCache, RefusesNonFiniteCoordinatesNamingSampleAndPoint) {
  std::string b = pc2_bytes(3);
  b.replace(32 + 24 * 2 + 12 + 4, 4, lef(std::nanf("")));  // sample 2, point 1, y
  EXPECT_EQ(refusal(CacheFormat::Pc2, b), "c: byte 96: sample 2, point 1: coordinate y is NaN");
  b = mdd_bytes(2);
  b.replace(16, 4, bef(-std::numeric_limits<float>::infinity()));  // sample 0, point 0, x
  EXPECT_EQ(refusal(CacheFormat::Mdd, b),
            "c: byte 16: sample 0, point 0: coordinate x is infinite");
}

TEST(PointCache, FileReaderMatchesMemoryAndNamesTheFile) {
  const test::TempDir dir("cache_file");
  write_file_atomic(dir / "a.pc2", pc2_bytes(4));
  CacheReader reader(dir / "a.pc2");
  EXPECT_EQ(reader.header().samples, 4);
  EXPECT_EQ(reader.sample(3), CacheReader("m", CacheFormat::Pc2, pc2_bytes(4)).sample(3));
  write_file_atomic(dir / "cut.mdd", mdd_bytes(4).substr(0, 30));
  try {
    CacheReader cut(dir / "cut.mdd");
    ADD_FAILURE() << "a cut file was read";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_TRUE(contains(e.what(), dir / "cut.mdd" + ": truncated")) << e.what();
  }
  try {
    CacheReader missing(dir / "none.pc2");
    ADD_FAILURE() << "a missing file was read";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), dir / "none.pc2" + ": cannot read: No such file or directory");
  }
  EXPECT_THROW(CacheReader(dir / "a.txt"), Error);
}

// Samples written in any order, from several threads, give the bytes written in order; every
// coordinate bit for bit (negative zero, a subnormal).
TEST(PointCache, WriterPutsSamplesAtTheirOffsetsInAnyOrder) {
  const test::TempDir dir("cache_write");
  for (const CacheFormat format : {CacheFormat::Pc2, CacheFormat::Mdd}) {
    const std::string bytes = format == CacheFormat::Pc2 ? pc2_bytes(6) : mdd_bytes(6);
    const CacheReader in("in", format, bytes);
    const std::string path = dir / (std::string("out.") + to_string(format));
    CacheWriter writer(path, in.header());
    std::vector<std::thread> threads;
    for (int t = 0; t < 2; ++t)
      threads.emplace_back([&, t] {
        for (int k = 5 - t; k >= 0; k -= 2) writer.write_sample(k, in.sample(k));
      });
    for (std::thread& t : threads) t.join();
    EXPECT_FALSE(std::filesystem::exists(path));  // nothing at the name before commit
    writer.commit();
    EXPECT_EQ(read_file(path), bytes);
  }
  CacheHeader h = CacheReader("in", CacheFormat::Pc2, pc2_bytes(1)).header();
  CacheWriter writer(dir / "bits.pc2", h);
  const CacheSample odd = {-0.0f, std::numeric_limits<float>::denorm_min(), 3.5f, -1e30f, 1e-30f,
                           0.1f};
  writer.write_sample(0, odd);
  writer.commit();
  const CacheSample back = CacheReader(dir / "bits.pc2").sample(0);
  for (int i = 0; i < 6; ++i)
    EXPECT_EQ(std::bit_cast<std::uint32_t>(back[i]), std::bit_cast<std::uint32_t>(odd[i]));
}

TEST(PointCache, AWriterNotCommittedLeavesNoFile) {
  const test::TempDir dir("cache_uncommitted");
  const CacheHeader h = CacheReader("in", CacheFormat::Pc2, pc2_bytes(2)).header();
  {
    CacheWriter writer(dir / "a.pc2", h);
    writer.write_sample(0, CacheSample(6, 1.0f));
    EXPECT_THROW(writer.write_sample(1, CacheSample{1, 2, std::nanf(""), 4, 5, 6}), Error);
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
  CacheWriter writer(dir / "b.pc2", h);
  writer.write_sample(1, CacheSample(6, 1.0f));
  EXPECT_THROW(writer.commit(), Error);  // sample 0 missing: a hole is a bug, never written
}

}  // namespace
}  // namespace skinslide
