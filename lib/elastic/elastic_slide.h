// The elastic method, one patch at a time, in the shape the paper's method has
// (paper/paper_slide.h): its options and bind-time set-up (relax.h's ElasticOptions and
// ElasticSetup), and a per-frame pure function returning positions and a report. The
// relaxation itself is relax.h's; this adds what the pipeline asks of every method: the
// patch's chart as its bind picture, slide weights, and the slid triangles turned over.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/types.h"
#include "elastic/relax.h"
#include "mesh/patch.h"
#include "slide/patch_slide.h"

namespace skinslide {

/// Sets up one patch that slides (not skipped): its chart and rest shape over the vertices that
/// move (free, slide weight > 0: a vertex of weight 0 is held where the frame puts it, and the
/// skin around it slides). Fills `patch.bind_net` with the chart's positions of the patch's
/// vertices and `patch.bind_net_flips`.
/// \param points bind positions of the patch's vertices (local ids)
/// \param weight slide weight per mesh vertex (#V); empty = 1 everywhere
/// \param blend ElasticOptions::blend: the surface the relaxation moves on (0: the facets)
/// \throw Error as elastic_setup (disk_chart).
std::shared_ptr<const ElasticSetup> elastic_patch_setup(Patch& patch, const Positions3& points,
                                                        const std::vector<double>& weight,
                                                        double blend = 0);

/// What the elastic slide of one patch did in one frame (relax.h's ElasticResult's figures).
struct ElasticReport {
  double energy_before = 0;  ///< the frame's elastic energy against the bind
  double energy_after = 0;   ///< after the slide, never above energy_before
  int iterations = 0;        ///< steps taken
  int solves = 0;            ///< step directions solved (a step's first, and around holds)
  int solve_iterations = 0;  ///< conjugate-gradient iterations of those solves
  int escalations = 0;       ///< times their iteration budget was raised (relax.h, rule 10)
  int held = 0;              ///< vertex-steps held in place to keep a step a descent
  int slid_flips = 0;        ///< slid triangles whose normal turns against the frame's (want 0)
  double gain_left = 0;      ///< the first-order gain left at the slid patch (relax.h, rule 10)
  /// With a window over the neighbouring frames (window_mean.h): vertices written at the frame's
  /// own slide instead of the window's mean, to keep every slid triangle facing the frame's.
  int window_returned = 0;
  /// The frame's own relaxation's energy: energy_after, or with a window what its mean is
  /// written instead of (told on the frame's line when the mean costs much more).
  double energy_own = 0;
  std::string stop;  ///< why the relaxation stopped; empty: the patch was skipped
};

struct ElasticSlide {
  PatchSlide slid;
  ElasticReport report;
};

/// Slides one patch in one frame: relaxes it in the chart, then each vertex of slide weight
/// w < 1 goes back a fraction 1 - w of the way to its start in the chart, so that it stays on
/// the frame's surface. Pure: depends on (setup, patch, points, weight, options) only (the
/// timings aside).
/// \param points the frame's positions of the patch's vertices (local ids)
/// \param weight slide weight per mesh vertex (#V); empty = 1 everywhere
/// \param id_image_size > 0: keep the chart's ID image at that size (PatchSlide::id_image)
/// \throw Error(Numeric) naming the vertex when a slid position is not finite.
ElasticSlide elastic_slide(const ElasticSetup& setup, const Patch& patch, const Positions3& points,
                           const std::vector<double>& weight, const ElasticOptions& options,
                           int id_image_size = 0);

/// elastic_slide's second half: writes a relaxation of this frame's patch (`relaxed`:
/// relax_patch's, or window_mean's), with the slide weights applied as elastic_slide says.
ElasticSlide elastic_written(const ElasticSetup& setup, const Patch& patch,
                             const Positions3& points, const std::vector<double>& weight,
                             const ElasticResult& relaxed, int id_image_size = 0);

}  // namespace skinslide
