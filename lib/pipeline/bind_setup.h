// Bind-time set-up: patches, boundary loops, pins and weights (shared by both methods), then
// each patch's set-up by the run's method (pipeline/method.h), built once. A frame is then a
// pure function of (BindSetup, frame positions): see slide_frame.h.
#pragma once

#include <vector>

#include "core/types.h"
#include "mesh/patch.h"
#include "mesh/patches.h"
#include "mesh/poly_mesh.h"
#include "pipeline/method.h"
#include "pipeline/options.h"

namespace skinslide {

struct BindSetup {
  Index vertex_count = 0;
  std::vector<Patch> patches;  ///< ordered by smallest mesh vertex id
  /// Final slide weight per mesh vertex, clamp(weight * strength, 0, 1) (#V); empty = 1 everywhere.
  std::vector<double> weight;
  Index pins_ignored = 0;  ///< distinct pins on a boundary loop or outside every patch
  /// The bind's positions (#V): a patch whose frame positions are these to float32 precision is
  /// at rest (pipeline/slide_frame.h).
  Positions3 bind_positions;
  MethodSetup method;  ///< the method and its per-patch set-up
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
/// \param name_selection names a selection in messages (its patch file); default "patch N".
/// \throw Error(Usage) naming the option and the vertex id for: an id past the last vertex, a
///        weight outside [0, 1], a corner or outer-loop vertex on no patch's boundary loop,
///        corners not in the loop's walking order, two choices for one patch that disagree.
BindSetup bind_setup(const PolyMesh& bind, const std::vector<std::vector<Index>>& selections,
                     const SlideOptions& options, const SlideControls& controls,
                     const FaceNamer& name_face = {}, unsigned threads = 1,
                     const SelectionNamer& name_selection = {});

}  // namespace skinslide
