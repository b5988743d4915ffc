#include "io/exr.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "helpers/exr_read.h"
#include "helpers/run.h"
#include "helpers/temp_dir.h"
#include "io/atomic_write.h"

namespace skinslide {
namespace {

// A 3 x 2 image whose samples say where they are: value = 10*row + column, row 0 = bottom.
struct Sample {
  std::vector<std::uint32_t> id{0, 1, 2, 10, 11, 12};
  std::vector<float> f{0.5f, 1.5f, 2.5f, 10.5f, 11.5f, 12.5f};
  std::vector<float> g{-1, -2, -3, -4, -5, -6};

  ExrImage image() const {
    ExrImage im;
    im.width = 3;
    im.height = 2;
    im.uint_channels = {{"id", id}};
    im.float_channels = {{"P.X", f}, {"A", g}};
    im.string_attributes = {{"skinslide.source", "frames/f0003.obj"}};
    im.int_attributes = {{"skinslide.patch", 7}};
    return im;
  }
};

TEST(Exr, ReadsBackWithChannelsTypesAttributesAndBottomRowLast) {
  test::TempDir dir("exr_read_back");
  const Sample s;
  const std::string path = dir / "a.exr";
  write_exr(path, s.image());
  const test::ExrContents c = test::read_exr(path);
  EXPECT_EQ(c.width, 3);
  EXPECT_EQ(c.height, 2);
  EXPECT_EQ(c.compression, Imf::ZIP_COMPRESSION);
  ASSERT_EQ(c.types.size(), 3u);
  EXPECT_EQ(c.types.at("id"), Imf::UINT);
  EXPECT_EQ(c.types.at("P.X"), Imf::FLOAT);
  EXPECT_EQ(c.types.at("A"), Imf::FLOAT);
  // The file's first scanline is the top: our row 1.
  EXPECT_EQ(c.uints.at("id"), (std::vector<std::uint32_t>{10, 11, 12, 0, 1, 2}));
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(c.uint_at("id", i, j), s.id[j * 3 + i]);
      EXPECT_EQ(c.float_at("P.X", i, j), s.f[j * 3 + i]);
      EXPECT_EQ(c.float_at("A", i, j), s.g[j * 3 + i]);
    }
  EXPECT_EQ(c.strings.at("skinslide.source"), "frames/f0003.obj");
  EXPECT_EQ(c.ints.at("skinslide.patch"), 7);
}

TEST(Exr, SameImageSameBytes) {
  test::TempDir dir("exr_same_bytes");
  const Sample s;
  const std::string a = exr_bytes(s.image());
  EXPECT_EQ(a, exr_bytes(s.image()));
  write_exr(dir / "a.exr", s.image());
  write_exr(dir / "b.exr", s.image());
  EXPECT_EQ(read_file(dir / "a.exr"), a);
  EXPECT_EQ(read_file(dir / "b.exr"), a);
}

TEST(Exr, BadPlaneSizeIsAnInternalError) {
  Sample s;
  s.f.pop_back();
  try {
    exr_bytes(s.image());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Internal);
  }
}

TEST(Exr, UnwritableFolderIsAnOutputErrorNamingThePath) {
  test::TempDir dir("exr_unwritable");
  const std::string path = dir / "missing/a.exr";
  try {
    write_exr(path, Sample().image());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Output);
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

// exrheader (Debian's `openexr`) is an independent reader: it must accept the file and list
// each channel with its type and our attributes.
TEST(Exr, ExrheaderListsChannelsAndAttributes) {
  test::TempDir dir("exr_exrheader");
  const std::string path = dir / "a.exr";
  write_exr(path, Sample().image());
  const test::RunResult r = test::run("exrheader '" + path + "'");
  ASSERT_EQ(r.exit_code, 0) << "exrheader failed (is Debian's `openexr` installed?):\n" << r.output;
  const std::string& out = r.output;
  for (const char* want :
       {"id, 32-bit unsigned integer", "P.X, 32-bit floating-point", "A, 32-bit floating-point",
        "zip", "skinslide.source", "frames/f0003.obj", "skinslide.patch"})
    EXPECT_NE(out.find(want), std::string::npos) << want << " not in:\n" << out;
}

}  // namespace
}  // namespace skinslide
