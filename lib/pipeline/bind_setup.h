// Bind-time set-up: patches, boundary loops, square boundary and the bind net, built once.
// A frame is then a pure function of (BindSetup, frame positions): see slide_frame.h.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "core/types.h"
#include "elastic/relax.h"
#include "locate/id_raster.h"
#include "locate/locate.h"
#include "mesh/patches.h"
#include "mesh/poly_mesh.h"
#include "pipeline/options.h"

namespace skinslide {

class FrameNetSolver;  // unwrap/bar_net.h

/// One connected component of the selected faces, prepared for sliding. "Local" ids index
/// `vertices`; a virtual hole node (Holes::Fill) is never part of these arrays.
struct PatchNet {
  std::vector<Index> faces;                ///< mesh face ids, ascending
  std::vector<Index> vertices;             ///< mesh vertex ids, ascending (local id = position)
  std::vector<std::array<Index, 2>> bars;  ///< polygon edges, local ids, (a < b), sorted
  std::vector<Triangle> triangles;         ///< fan triangles of `faces`, local ids, face order
  std::vector<Index> triangle_face;        ///< mesh face of each triangle
  std::vector<Index> triangle_fan;         ///< k: triangle has face slots (0, k+1, k+2)
  TriangleTopology topology;               ///< neighbours of `triangles`, for walking frame nets
  std::vector<std::vector<Index>> loops;   ///< boundary loops, local ids, each from its smallest
  Index outer_loop = 0;                    ///< index into `loops`
  std::array<Index, 4> corners{};  ///< local ids of the square's corners (0,0) (1,0) (1,1) (0,1)
  bool skipped = false;            ///< every vertex is on a boundary loop: nothing slides
  Positions2 bind_net;             ///< 2D position of every local vertex
  std::vector<Index>
      free_vertices;          ///< local ids that slide (not on any loop, not pinned), ascending
  std::vector<Index> pinned;  ///< local ids pinned by SlideControls::pins (not on a loop)
  std::vector<double> bind_lengths;  ///< 3D length of each bar in the bind
  bool outer_loop_chosen = false;    ///< the outer loop came from --outer-loop-vertex/--corners
  bool corners_chosen = false;       ///< the corners came from --corners
  double bind_diagonal = 0;          ///< bounding-box diagonal of the patch in the bind
  int bind_net_flips = 0;            ///< bind-net triangles of the minority orientation
  Index selection = 0;               ///< which selection (--patch file) it came from
  std::shared_ptr<const FrameNetSolver> solver;  ///< the paper's frame nets, reused by every frame
  /// The elastic method's chart and rest shape (SlideMethod::Elastic; then `bind_net` is the
  /// chart's positions of the patch vertices and `solver` is empty).
  std::shared_ptr<const ElasticSetup> elastic;
};

struct BindSetup {
  SlideOptions options;
  Index vertex_count = 0;
  std::vector<PatchNet> patches;  ///< ordered by smallest mesh vertex id
  /// Final slide weight per mesh vertex, clamp(weight * strength, 0, 1) (#V); empty = 1 everywhere.
  std::vector<double> weight;
  Index pins_ignored = 0;  ///< distinct pins on a boundary loop or outside every patch
};

/// Builds the bind set-up for the selected faces of `bind`.
/// \param selections face-id lists (one per --patch file; components are split within each)
/// \throw Error(Input) on topology errors (non-manifold, closed patch, ...); names the face/vertex.
/// \throw Error(Numeric) when the bind net cannot be solved.
BindSetup bind_setup(const PolyMesh& bind, const std::vector<std::vector<Index>>& selections,
                     const SlideOptions& options, const FaceNamer& name_face = {});

/// The same with the animator's controls (weights, pins, corners, outer loops).
/// \param threads patches set up at once (each patch by one thread); the result is the same
///        for any count. `name_face` must then be safe to call from several threads.
/// \throw Error(Usage) naming the option and the vertex id for: an id past the last vertex, a
///        weight outside [0, 1], a corner or outer-loop vertex on no patch's boundary loop,
///        corners not in the loop's walking order, two choices for one patch that disagree.
BindSetup bind_setup(const PolyMesh& bind, const std::vector<std::vector<Index>>& selections,
                     const SlideOptions& options, const SlideControls& controls,
                     const FaceNamer& name_face = {}, unsigned threads = 1);

}  // namespace skinslide
