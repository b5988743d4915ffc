// A picture of one patch in one frame that any image viewer shows: the bind net and the frame
// net drawn over each other in the unit square.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/types.h"

namespace skinslide {

/// 8-bit RGB, rows top first (as PNG stores them): pixel (x, y) at rgb[3*(y*width + x) + c].
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;
};

/// Colours of the preview (README "Dumps"), sRGB.
struct PreviewColors {
  std::array<std::uint8_t, 3> background{255, 255, 255};
  std::array<std::uint8_t, 3> square{190, 190, 190};  ///< the unit square's outline
  std::array<std::uint8_t, 3> bind{31, 119, 180};     ///< bind-net bars (blue)
  std::array<std::uint8_t, 3> frame{230, 110, 20};    ///< frame-net bars (orange)
  std::array<std::uint8_t, 3> moved{20, 20, 20};      ///< slide segments and dots (near black)
};

/// Draws, on a size x size image with v up (v = 1 at the top row) and a margin of size/32
/// pixels around the unit square: the square's outline, the bind net's `bars`, the frame net's
/// `bars` over them, and for every vertex in `moved` a segment from its frame-net position to its
/// bind-net position (where it slides to in the frame's net) ending in a dot. With
/// `slides_to_frame_net` (the elastic method: `bind_net` is the patch's chart, `frame_net` where
/// the vertices slid to in it) the segments run the other way and the dots mark `frame_net`. Lines
/// are about one pixel wide, anti-aliased by distance; the image depends only on the inputs. \param
/// bind_net, frame_net 2D position of every net vertex (#n each); `bars` and `moved`
///        index them (local ids). Points outside the unit square are drawn while in the margin.
/// \pre size >= 16
RgbImage preview_image(const Positions2& bind_net, const Positions2& frame_net,
                       const std::vector<std::array<Index, 2>>& bars,
                       const std::vector<Index>& moved, int size, const PreviewColors& colors = {},
                       bool slides_to_frame_net = false);

}  // namespace skinslide
