// The elastic slide of one patch in one frame: the free vertices move in the patch's fixed chart,
// starting exactly at the frame, and lower an as-rigid-as-possible energy against the bind's
// triangles with fold-free, energy-decreasing steps (lib/elastic/README.md).
// ARAP: Sorkine & Alexa 2007; fold-free steps: Smith & Schaefer 2015.
//
//   ElasticSetup setup = elastic_setup(bind, triangles, loops, outer, movable);   // bind time
//   ElasticResult slid = relax_patch(setup, frame, options);                        // per frame
#pragma once

#include <string>
#include <vector>

#include "core/types.h"
#include "elastic/blended_surface.h"
#include "elastic/chart.h"
#include "elastic/step_direction.h"

namespace skinslide {

/// How a frame's patch is slid (lib/elastic/README.md): a fixed map of the frame (smooth in time,
/// the default) or a search for a minimum of its energy (separate poses).
enum class ElasticSolver {
  Map,     ///< smooth_map.h: a fixed number of continuous passes from the frame
  Search,  ///< rounds of ARAP steps until a tolerance, with holds and a line search
};

/// When a frame's relaxation stops (README "Options").
struct ElasticOptions {
  ElasticSolver solver = ElasticSolver::Map;
  /// The map's passes from the frame: more even the stretch further at a proportional cost
  /// (lib/elastic/README.md "The quality dial").
  int passes = 2;
  /// ARAP local/global rounds: each fits every triangle's rotation to the slid patch, then
  /// lowers the energy with them held. More rounds reach lower ARAP energies; fewer keep the
  /// slide smoother from frame to frame (lib/elastic/README.md "Choosing the defaults").
  int rotation_fits = 3;
  int max_iterations = 100;  ///< steps per round at most
  /// A round stops at the first step that lowers its energy by less than this fraction of the
  /// energy it started with.
  double tolerance = 3e-4;
  /// A frame has converged when the first-order gain left (stationarity.h: what a Newton step
  /// in the bind's metric along every vertex's steepest one-sided descent would gain) is at most
  /// this fraction of the frame's energy (README rule 10; what the default steps leave:
  /// tests/bench/elastic.md "Figures behind the code's constants").
  double convergence = 5e-2;
  /// Bind time: relax on the frame's facets blended smooth near their edges (blended_surface.h),
  /// each edge's blend this share of its triangles' inradius wide (narrower next to slivers);
  /// 0: on the facets. On the facets a slid vertex's minimum sticks to chart edges and slips off
  /// them from frame to frame (jitter in slow motion); 1 takes far less jitter, at a few times
  /// the relax time (tests/bench/elastic.md "A blended surface").
  double blend = 0;
  /// The first this many rotation fits aim only part of the way from the frame's own stretch to
  /// the bind's: fit r (from 0) aims at (1 - a) J_frame + a s R with a = (r + 1) / (ease_in + 1),
  /// then the rest aim at s R. From the frame, where a = 0 is at its minimum, the slide follows
  /// one branch of minima as the aim moves, instead of stepping into whichever basin the full
  /// target's first steps reach; the basin changes from frame to frame less often (less jitter
  /// in slow motion: tests/bench/elastic.md "Easing the target in"). Counts among
  /// rotation_fits, and must leave at least one fit that aims fully.
  int ease_in = 0;
};

/// The map's conjugate-gradient iterations a pass on a patch whose bind's factor preconditions
/// its step system well: they solve the damped step nearly exactly there (16 slide the same); 2 or
/// 4 leave a step's direction to the truncation, which jitters (lib/elastic/README.md "The map").
constexpr int kMapStepIterations = 8;
/// The most any patch is given (smooth_map.h map_step_budget): 16 times the least.
constexpr int kMaxMapStepIterations = 128;
/// The share of its starting residual the bind's own step system must be solved to within a
/// patch's budget (map_step_budget).
constexpr double kMapStepResidual = 0.05;

/// Bind-time precompute of one patch: plain data, immutable once built, shared by every frame.
struct ElasticSetup {
  Chart chart;
  SurfaceBlend blend;  ///< the surface the relaxation moves on; empty: the facets
  /// Local ids of the vertices that move (not on a loop, not pinned, slide weight > 0), ascending.
  std::vector<Index> movable;
  std::vector<Index> movable_slot;  ///< per local vertex: its index in `movable`, or -1
  /// Per patch triangle its rest shape (arap.h rest_inverse); zero without bind area.
  std::vector<Eigen::Matrix2d> rest_inverse;
  double triangle_weight = 0;  ///< every triangle's energy weight: the mean bind triangle area
  double bind_area = 0;        ///< total bind area of the patch's triangles
  /// The bind's ARAP metric over the movable vertices and its factor: every step's
  /// preconditioner (step_direction.h).
  ElasticMetric metric;
  /// The map's conjugate-gradient iterations a pass (smooth_map.h map_step_budget).
  int map_step_iterations = kMapStepIterations;
};

/// \param points bind positions of the patch's vertices (local ids); `triangles` index them.
/// \param movable local ids that move, ascending. Loops, `outer_loop`: as disk_chart.
/// `blend`: ElasticOptions::blend (0: none).
/// \throw Error(Numeric) when the chart or the metric's factor cannot be built.
ElasticSetup elastic_setup(const Positions3& points, const std::vector<Triangle>& triangles,
                           const std::vector<std::vector<Index>>& loops, Index outer_loop,
                           const std::vector<Index>& movable, double blend = 0);

/// The triangles the setup's energy sums over.
ArapTriangles arap_triangles(const ElasticSetup& setup);

/// Why a frame's relaxation stopped (README rule 10). Only AtRest and Converged say that the
/// slid patch is where its energy is stationary; the others say why it was left elsewhere.
enum class ElasticStop {
  AtRest,          ///< the frame is the bind up to a rigid motion and a uniform scale
  Converged,       ///< the first-order gain left is within `convergence` of the frame's energy
  SmallGain,       ///< the last round's last step gained less than `tolerance`; gain is left
  IterationLimit,  ///< the last round took max_iterations steps; gain is left
  NoStep,          ///< no step along the last direction lowered the energy (folds, round-off)
  NoDescent,       ///< round-off ate the gain: the frame is returned
  SolveFailed,     ///< a step's direction was not finite: the round ended there
  Passes,          ///< the map's passes ended with more gain left than `convergence`
};

/// The report's word for a stop: "at rest", "converged", "small gain", "limit", "no step",
/// "no descent", "solve failed", "passes".
const char* stop_name(ElasticStop stop);

/// One patch's slide in one frame.
struct ElasticResult {
  /// Per movable vertex (parallel to ElasticSetup::movable): its chart point and where that lies.
  Positions2 uv;
  std::vector<ChartPoint> where;
  Positions3 position;        ///< the slid 3D position: on `where`'s frame triangle
  double energy_before = 0;   ///< the frame's ARAP energy against the bind
  double energy_after = 0;    ///< the slid patch's, never above energy_before
  double scale = 1;           ///< s: sqrt(frame area / bind area), the stretch aimed at
  int iterations = 0;         ///< steps taken, over all rounds
  int solves = 0;             ///< step directions solved (a step's first, and with holds)
  int solver_iterations = 0;  ///< conjugate-gradient iterations over all solves
  /// Times the directions' iteration budget was raised for a frame the measure found short of
  /// stationary (rule 10).
  int escalations = 0;
  /// Vertex-steps held in place: their energy would rise, a triangle of theirs would fold, or
  /// they were held for the step that won.
  int held = 0;
  /// Rule 10's measure (stationarity.h): the first-order gain left at the slid patch (at the
  /// frame when it is returned), in the energy's units.
  double gain_left = 0;
  /// window_mean.h: vertices written at this frame's own relaxation instead of the window's mean.
  int window_returned = 0;
  ElasticStop stop = ElasticStop::Converged;
};

/// Puts every movable vertex of `result` at its start: its own chart node, exactly at its frame
/// position (`frame`: local ids), on a patch triangle around it. Nothing else of `result` changes.
void put_at_start(const ElasticSetup& setup, const Positions3& frame, ElasticResult& result);

/// Relaxes one patch in one frame. `frame_points` holds the frame's positions of the patch's
/// vertices (local ids). Pure: depends on (setup, frame_points, options) only.
/// Guarantees: every output on one frame triangle (barycentrics in [0, 1]); no slid triangle
/// folded over in the chart; none turned against the frame's where the frame's own triangle has
/// area; energy_after <= energy_before; all finite.
/// \throw Error(Numeric) naming the vertex when a position is not finite.
ElasticResult relax_patch(const ElasticSetup& setup, const Positions3& frame_points,
                          const ElasticOptions& options);

/// The ARAP energy of a whole patch at positions `x` (local ids) with target stretch `scale`:
/// the mean bind triangle area times the sum over triangles of (s1 - scale)^2 + (s2 - scale)^2,
/// s1, s2 the singular values of the triangle's deformation gradient from the bind.
double elastic_energy(const ElasticSetup& setup, const Positions3& x, double scale);

}  // namespace skinslide
