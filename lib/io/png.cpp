#include "io/png.h"

// Debian's libstb-dev also ships the implementation as libstb.so; compiling it here, with
// internal linkage, keeps the link line to the standard library and avoids a second copy of
// the symbols clashing with one linked in by a dependency.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

#include "core/check.h"
#include "core/error.h"
#include "io/atomic_write.h"

namespace skinslide {
namespace {

void append(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                             static_cast<size_t>(size));
}

}  // namespace

std::string png_bytes(int width, int height, const std::vector<std::uint8_t>& rgb) {
  SKINSLIDE_CHECK(width >= 1 && height >= 1, "PNG image size");
  SKINSLIDE_CHECK(rgb.size() == static_cast<size_t>(width) * height * 3, "PNG buffer size");
  std::string bytes;
  if (stbi_write_png_to_func(append, &bytes, width, height, 3, rgb.data(), width * 3) == 0)
    throw Error(ErrorKind::Output, "cannot encode PNG");
  return bytes;
}

void write_png(const std::string& path, int width, int height,
               const std::vector<std::uint8_t>& rgb) {
  std::string bytes;
  try {
    bytes = png_bytes(width, height, rgb);
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::Output) throw;
    throw Error(ErrorKind::Output, path + ": " + e.what());
  }
  write_file_atomic(path, bytes);
}

}  // namespace skinslide
