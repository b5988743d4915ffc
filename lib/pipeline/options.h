// The run's method and its tunables, and the animator's controls (README "Options", "Controls").
// Each method's options live in its own folder with their defaults and their option table
// (elastic/elastic_options.h, paper/paper_options.h); this only says which one a run uses.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/types.h"
#include "elastic/elastic_options.h"
#include "paper/paper_options.h"

namespace skinslide {

/// Which slide a run makes, with that method's options (README "The method, exactly"):
/// ElasticOptions, the default (the free vertices relax in a fixed chart of the patch), or
/// PaperOptions (Yang & Zhang 2010: bind and frame flattened by bar nets, bind points located).
/// Everything before (patches, loops, pins, weights) and after (transfer, write, report) is
/// shared.
using SlideOptions = std::variant<ElasticOptions, PaperOptions>;

/// The default options of the method named "elastic" or "paper".
/// \throw Error(Usage) on another name.
SlideOptions parse_method(const std::string& name);

/// "elastic" or "paper".
std::string method_name(const SlideOptions& options);

/// Calls `f(name, option_table<Options>())` for each method, in SlideOptions' order: what lists
/// every method's options (the Python module's).
template <class F>
void for_each_method(F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (f(method_name(SlideOptions(std::in_place_index<I>)),
       option_table<std::variant_alternative_t<I, SlideOptions>>()),
     ...);
  }
  (std::make_index_sequence<std::variant_size_v<SlideOptions>>());
}

/// The animator's controls (README "Controls"): where and how much skin slides, and how a patch
/// is laid on the square. Every member's default leaves the method as README "The method" states.
/// Vertex ids are 0-based mesh ids in file order.
struct SlideControls {
  /// Slide weight per mesh vertex (#V, each in [0, 1]); empty = 1 everywhere. A sliding vertex
  /// ends at lerp(frame, slid, clamp(weight * strength, 0, 1)); 0 leaves it exactly at the frame.
  std::vector<double> weight;
  double strength = 1;  ///< multiplies every weight (>= 0); the product is clamped to [0, 1]
  /// Vertices that do not slide: fixed in every frame net at their bind-net position, so they
  /// stay at the frame position while the skin around them slides. Ids on a boundary loop or
  /// outside every patch change nothing (they never slide) and are counted in BindSetup.
  std::vector<Index> pins;
  /// Corner choices (the paper's method), each four mesh vertex ids on one boundary loop of a
  /// patch, in the loop's walking order, for (0,0) (1,0) (1,1) (0,1). The loop holding them
  /// becomes the outer loop of every patch it bounds. Empty = automatic (README rule 3).
  std::vector<std::array<Index, 4>> corners;
  /// Outer-loop choices: the boundary loop through each vertex becomes the outer loop of every
  /// patch it bounds (corners then automatic on that loop unless `corners` names them).
  std::vector<Index> outer_loop_vertices;
};

}  // namespace skinslide
