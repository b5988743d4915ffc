// What a method's per-frame function hands on for one patch: where each vertex it moves landed
// on the frame's surface. Everything after it (transfer into the frame, figures, dumps) is shared
// by both methods (pipeline/slide_frame).
#pragma once

#include <array>
#include <vector>

#include "core/types.h"
#include "locate/id_raster.h"

namespace skinslide {

/// One patch's slide in one frame, local ids (Patch::vertices).
struct PatchSlide {
  /// The vertices written, ascending, each on patch triangle `triangle[k]` of the frame at
  /// barycentrics `weight[k]`, written at `position[k]` (with a slide weight below 1 off the
  /// surface, between the frame position and that point).
  std::vector<Index> vertex;
  std::vector<Index> triangle;
  std::vector<std::array<double, 3>> weight;
  Positions3 position;
  /// Vertices the method placed, written or not: the mean slide's denominator (the paper places
  /// a vertex of slide weight 0 and leaves it at the frame).
  Index placed = 0;
  /// The 2D picture of the frame, one entry a local vertex: the paper's frame net, or where the
  /// vertices slid to in the elastic method's chart.
  Positions2 net;
  /// The frame lies over Patch::bind_net (the elastic method's fixed chart) rather than over a
  /// net of its own: `net` then says where the vertices slid to in that picture.
  bool frame_in_bind_net = false;
  IdImage id_image;           ///< the lookup image of the frame's net, when asked for
  double solve_seconds = 0;   ///< wall time of the frame net or the relaxation
  double locate_seconds = 0;  ///< ID image and point location
};

}  // namespace skinslide
