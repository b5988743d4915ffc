// The slide field of a frame: where the skin at each point of the bind net sits in the frame's
// net before sliding, as an image over the unit square.
#pragma once

#include <vector>

#include "core/types.h"
#include "locate/id_raster.h"

namespace skinslide {

/// Two float planes (the EXR's slide.X, slide.Y), size x size, stored at [j*size + i] with
/// row 0 = v = 0 (as IdImage).
struct SlideField {
  int size = 0;
  std::vector<float> x, y;
};

/// For each texel centre u = ((i + 0.5)/size, (j + 0.5)/size): the bind-net triangle holding u
/// (the one id_raster() of the bind net assigns to that pixel) and u's barycentric weights in
/// it; the point with the same weights in the frame net is where the skin material at u sits in
/// the frame before sliding. The field is that point minus u (net units: the unit square):
///   slide(u) = frame point of u - u.
/// Sliding moves the skin the other way: a vertex whose bind-net position is u goes back to u
/// in the frame's net, a 2D move of -slide(u). An identity frame gives 0 everywhere; texels whose
/// centre no bind triangle covers (holes) get 0.
/// \param bind_net, frame_net 2D position of every net vertex (#n each, same triangles)
/// \pre size >= 1; frame_net.size() == bind_net.size()
SlideField slide_field(const Positions2& bind_net, const Positions2& frame_net,
                       const std::vector<Triangle>& triangles, int size);

}  // namespace skinslide
