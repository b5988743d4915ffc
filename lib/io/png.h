// PNG output (stb_image_write): 8-bit RGB previews any image viewer opens.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace skinslide {

/// The bytes of a PNG holding an 8-bit RGB image, rows top first: pixel (x, y) at
/// rgb[3*(y*width + x) + c]. No time stamp or text chunk, so equal images give equal bytes.
/// \throw Error(Internal) when rgb.size() != 3*width*height; Error(Output) when encoding fails.
std::string png_bytes(int width, int height, const std::vector<std::uint8_t>& rgb);

/// Writes png_bytes(...) to `path` atomically (io/atomic_write.h).
/// \throw Error(Output) naming `path`.
void write_png(const std::string& path, int width, int height,
               const std::vector<std::uint8_t>& rgb);

}  // namespace skinslide
