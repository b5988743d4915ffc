// A window over the neighbouring frames (README "Slow motion", lib/elastic/README.md rule 12): a
// frame written at the weighted mean of the chart points that its own and its neighbours'
// relaxations reached. The chart is the patch's, fixed at bind time, so the frames' chart points
// are points of one picture; their mean is put on this frame's own facets. Each relaxation still
// depends on its own frame alone; the mean is what smooths a minimum that jumps between two basins
// for a single frame (tests/bench/elastic.md "A window over the neighbouring frames").
#pragma once

#include <vector>

#include "core/types.h"
#include "elastic/relax.h"

namespace skinslide {

/// One frame of a window: its relaxation's chart points (ElasticResult::uv, per movable vertex)
/// and its weight.
struct WindowFrame {
  const Positions2* uv = nullptr;
  double weight = 0;
};

/// The weighted mean of the frames' chart points, summed in the order given (the weights sum to
/// 1). \pre every frame has as many points as the first.
Positions2 chart_point_mean(const std::vector<WindowFrame>& frames);

/// `own`, this frame's relaxation of the patch, with the chart points `mean` written instead, on
/// this frame's facets (`frame`: its positions of the patch's vertices, local ids). A moving corner
/// of a slid triangle that would fold in the chart or face against its frame triangle goes back
/// towards its own relaxed point, as far as its triangles need and no further, until none folds
/// (at the whole way a triangle is own's, which has none: relax.h's guarantees); when the mean's
/// energy would be above the frame's, the whole patch goes back towards own's as far as the
/// energy needs; a frame at rest (rule 4) is
/// returned as it is. The stop, the steps and the measure stay own's; energy_after is what is
/// written; window_returned counts the vertices sent back, wholly or in part.
ElasticResult window_mean(const ElasticSetup& setup, const Positions3& frame,
                          const ElasticResult& own, const Positions2& mean);

}  // namespace skinslide
