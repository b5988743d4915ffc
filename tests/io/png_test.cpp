#include "io/png.h"

#include <gtest/gtest.h>

// The decoder, for the round trip only: internal linkage, so it cannot clash with anything.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

#include "core/error.h"
#include "helpers/temp_dir.h"
#include "io/atomic_write.h"

namespace skinslide {
namespace {

std::vector<std::uint8_t> gradient(int w, int h) {
  std::vector<std::uint8_t> rgb(size_t(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = &rgb[(size_t(y) * w + x) * 3];
      p[0] = std::uint8_t(x * 7);
      p[1] = std::uint8_t(y * 5);
      p[2] = std::uint8_t((x ^ y) * 3);
    }
  return rgb;
}

TEST(Png, RoundTripsAndStartsWithTheSignature) {
  const int w = 37, h = 23;
  const std::vector<std::uint8_t> rgb = gradient(w, h);
  const std::string bytes = png_bytes(w, h, rgb);
  ASSERT_GE(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  int dw = 0, dh = 0, dc = 0;
  stbi_uc* decoded = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()),
                                           int(bytes.size()), &dw, &dh, &dc, 3);
  ASSERT_NE(decoded, nullptr);
  EXPECT_EQ(dw, w);
  EXPECT_EQ(dh, h);
  EXPECT_EQ(dc, 3);
  EXPECT_TRUE(std::equal(rgb.begin(), rgb.end(), decoded));
  stbi_image_free(decoded);
}

TEST(Png, SameImageSameBytesOnDisk) {
  test::TempDir dir("png_same_bytes");
  const std::vector<std::uint8_t> rgb = gradient(16, 16);
  write_png(dir / "a.png", 16, 16, rgb);
  write_png(dir / "b.png", 16, 16, rgb);
  EXPECT_EQ(read_file(dir / "a.png"), read_file(dir / "b.png"));
  EXPECT_EQ(read_file(dir / "a.png"), png_bytes(16, 16, rgb));
}

TEST(Png, WrongBufferSizeIsAnInternalError) {
  try {
    png_bytes(4, 4, std::vector<std::uint8_t>(47));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Internal);
  }
}

}  // namespace
}  // namespace skinslide
