// The elastic slide of one patch in one frame: the free vertices move in the patch's fixed chart,
// starting exactly at the frame, and lower an as-rigid-as-possible energy against the bind's
// triangles with fold-free, energy-decreasing steps (README "The method, exactly", elastic).
// ARAP: Sorkine & Alexa 2007; flip-free step bound: Smith & Schaefer 2015.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/types.h"
#include "elastic/chart.h"

namespace skinslide {

struct StepMultigrid;

/// When a frame's relaxation stops (README "Options").
struct ElasticOptions {
  /// ARAP local/global rounds: each fits every triangle's rotation to the slid patch, then
  /// lowers the energy with them held. More rounds reach lower ARAP energies; fewer keep the
  /// slide smoother from frame to frame (README "Choosing the defaults").
  int rotation_fits = 3;
  int max_iterations = 100;  ///< Gauss-Newton steps per round at most
  /// A round stops once two steps in a row each lower its energy by less than this fraction of
  /// the energy it started with.
  double tolerance = 1e-4;
};

/// Bind-time precompute of one patch: plain data, immutable once built, shared by every frame.
struct ElasticSetup {
  Chart chart;
  /// Local ids of the vertices that move (not on a loop, not pinned, slide weight > 0), ascending.
  std::vector<Index> movable;
  std::vector<Index> movable_slot;  ///< per local vertex: its index in `movable`, or -1
  /// Per patch triangle: the inverse of its bind edge matrix in a 2D frame of its own plane,
  /// so that J = [x_b - x_a, x_c - x_a] * rest_inverse is the deformation gradient (3x2). Zero
  /// for a bind triangle without area, which then has no rest shape to return to.
  std::vector<Eigen::Matrix2d> rest_inverse;
  double triangle_weight = 0;  ///< every triangle's energy weight: the mean bind triangle area
  double bind_area = 0;        ///< total bind area of the patch's triangles
  /// The energy's constant Gauss-Newton metric over the movable vertices, K_ij = sum over
  /// triangles of 2 w G_i . G_j (G: the triangle's gradient rows), CSR, full (both triangles of
  /// the symmetric matrix), columns ascending.
  std::vector<Index> metric_start;
  std::vector<Index> metric_column;
  std::vector<double> metric_value;
  /// The multigrid hierarchy every frame's step systems are solved with (step_system.h); null
  /// when nothing moves.
  std::shared_ptr<const StepMultigrid> step_multigrid;
};

/// \param points bind positions of the patch's vertices (local ids); `triangles` index them.
/// \param movable local ids that move, ascending. Loops, `outer_loop`: as disk_chart.
ElasticSetup elastic_setup(const Positions3& points, const std::vector<Triangle>& triangles,
                           const std::vector<std::vector<Index>>& loops, Index outer_loop,
                           const std::vector<Index>& movable);

/// One patch's slide in one frame.
struct ElasticResult {
  /// Per movable vertex (parallel to ElasticSetup::movable): its chart point and where that lies.
  Positions2 uv;
  std::vector<ChartPoint> where;
  Positions3 position;       ///< the slid 3D position: on `where`'s frame triangle
  double energy_before = 0;  ///< the frame's ARAP energy against the bind
  double energy_after = 0;   ///< the slid patch's, never above energy_before
  double scale = 1;          ///< s: sqrt(frame area / bind area), the stretch aimed at
  int iterations = 0;        ///< steps taken, over all rounds
  int held = 0;              ///< vertex-steps held in place to keep a step a descent (total)
  /// Why it stopped: "at rest" (the frame is the bind up to a rigid motion and a uniform scale),
  /// "converged", "limit" (a round took max_iterations steps), "no descent" (round-off ate the
  /// gain: the frame is returned).
  std::string stop;
};

/// Relaxes one patch in one frame. `frame_points` holds the frame's positions of the patch's
/// vertices (local ids). Pure: depends on (setup, frame_points, options) only.
/// Guarantees: every output on one frame triangle (barycentrics in [0, 1]); no chart triangle
/// turned over; no slid triangle whose normal turns against the frame's where the frame's own
/// triangle has area; energy_after <= energy_before; all finite.
/// \throw Error(Numeric) naming the vertex when a position is not finite.
ElasticResult relax_patch(const ElasticSetup& setup, const Positions3& frame_points,
                          const ElasticOptions& options);

/// The ARAP energy of a whole patch at positions `x` (local ids) with target stretch `scale`:
/// the mean bind triangle area times the sum over triangles of (s1 - scale)^2 + (s2 - scale)^2,
/// s1, s2 the singular values of the triangle's deformation gradient from the bind.
double elastic_energy(const ElasticSetup& setup, const Positions3& x, double scale);

}  // namespace skinslide
