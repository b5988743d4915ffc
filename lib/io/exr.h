// OpenEXR output: the only user of OpenEXR. Scanline, single-part, ZIP-compressed files.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace skinslide {

/// An image to encode: named channels of `width` x `height` samples and header attributes.
/// Planes are stored at [row*width + column] with row 0 = the BOTTOM of the image (v = 0, the
/// convention of IdImage and the dump images); the encoder flips them, as EXR's first scanline is
/// the top. The spans must stay valid until the call that encodes the image returns.
struct ExrImage {
  struct UintChannel {
    std::string name;
    std::span<const std::uint32_t> values;
  };
  struct FloatChannel {
    std::string name;
    std::span<const float> values;
  };
  int width = 0;
  int height = 0;
  std::vector<UintChannel> uint_channels;    ///< written as UINT
  std::vector<FloatChannel> float_channels;  ///< written as FLOAT (32-bit)
  std::vector<std::pair<std::string, std::string>> string_attributes;
  std::vector<std::pair<std::string, int>> int_attributes;
};

/// The bytes of an EXR file holding `image`: data and display window (0,0)-(width-1,height-1),
/// ZIP compression, increasing-y line order, the given attributes and nothing else that varies
/// (no time stamp), so the same image always gives the same bytes.
/// \throw Error(Internal) when a plane's size is not width*height or a name repeats;
///        Error(Output) when OpenEXR refuses the image (its message is kept).
std::string exr_bytes(const ExrImage& image);

/// Writes exr_bytes(image) to `path` atomically (io/atomic_write.h).
/// \throw Error(Output) naming `path`.
void write_exr(const std::string& path, const ExrImage& image);

}  // namespace skinslide
