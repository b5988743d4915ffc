// One patch prepared for sliding: what both methods start from (two methods,
// one set-up). Built once at bind time by pipeline/bind_setup, immutable afterwards.
#pragma once

#include <array>
#include <vector>

#include "core/types.h"

namespace skinslide {

/// One connected component of the selected faces. "Local" ids index `vertices`; a method's
/// virtual nodes (hole centres) are never part of these arrays.
struct Patch {
  Index selection = 0;                     ///< which selection (--patch file) it came from
  std::vector<Index> faces;                ///< mesh face ids, ascending
  std::vector<Index> vertices;             ///< mesh vertex ids, ascending (local id = position)
  std::vector<std::array<Index, 2>> bars;  ///< polygon edges, local ids, (a < b), sorted
  std::vector<Triangle> triangles;         ///< fan triangles of `faces`, local ids, face order
  std::vector<Index> triangle_face;        ///< mesh face of each triangle
  std::vector<Index> triangle_fan;         ///< k: triangle has face slots (0, k+1, k+2)
  std::vector<std::vector<Index>> loops;   ///< boundary loops, local ids, each from its smallest
  Index outer_loop = 0;                    ///< index into `loops`
  bool outer_loop_chosen = false;  ///< the outer loop came from --outer-loop-vertex/--corners
  bool skipped = false;            ///< every vertex is on a boundary loop: nothing slides
  /// Local ids that slide (not on any loop, not pinned), ascending.
  std::vector<Index> free_vertices;
  std::vector<Index> pinned;         ///< local ids pinned by SlideControls::pins (not on a loop)
  std::vector<double> bind_lengths;  ///< 3D length of each bar in the bind
  double bind_diagonal = 0;          ///< bounding-box diagonal of the patch in the bind
  /// The method's 2D picture of the patch at bind, one entry a local vertex: the paper's bind
  /// net on the unit square, or the elastic method's chart. Empty when skipped.
  Positions2 bind_net;
  int bind_net_flips = 0;  ///< `bind_net` triangles of the minority orientation
};

}  // namespace skinslide
