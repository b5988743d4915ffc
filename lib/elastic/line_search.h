// The elastic method's flip-free line search (lib/elastic/README.md rules 8-9): how far the
// movable vertices go along a step in the chart so that no slid triangle folds over, in the chart
// or against the frame, and the energy falls.
#pragma once

#include <cmath>
#include <functional>
#include <vector>

#include "core/types.h"
#include "elastic/surface_map.h"

namespace skinslide {

/// Where a patch's movable vertices are in one frame.
struct SlideState {
  Positions2 node_uv;             ///< every chart node's point: the movable ones follow the slide
  std::vector<ChartPoint> where;  ///< per movable vertex: its chart triangle and barycentrics
  std::vector<char> on_node;      ///< per movable vertex: still exactly on its own chart node
  Positions3 x;                   ///< the slid patch (local ids): the others at the frame
};

/// A step to search along: per movable vertex its chart step d_i and its true first-order
/// change rise_i = g_i . T_i d_i (T_i the Jacobian of the triangle the vertex enters along d_i),
/// each <= 0: a vertex whose energy would rise does not move.
struct StepCandidate {
  Positions2 d;
  std::vector<Index> entered;
  std::vector<double> rise;
  /// Set by bound_folds, once: the chart triangles with a moving corner, each one's fold root
  /// along d (the smallest positive share of d at which it folds over; infinite when none) and
  /// the smallest of them.
  std::vector<Index> moving;
  std::vector<double> fold_roots;
  double fold_bound = INFINITY;
  bool bounded = false;
};

/// The patch as the line search sees it.
struct LineSearchPatch {
  const FrameSurface& surface;
  const std::vector<Index>& movable;       ///< local ids of the movable vertices
  const std::vector<Index>& movable_slot;  ///< per local id its movable index, or -1
};

struct LineSearchResult {
  bool accepted = false;
  size_t candidate = 0;  ///< which candidate won
  double alpha = 0;      ///< the share of its step taken
  double energy = 0;     ///< at the new state (the old energy when nothing was accepted)
  Index held = 0;        ///< moving vertices kept in place: a triangle of theirs would fold
  SlideState state;      ///< the new state when accepted
};

/// A slid triangle folds: turned over in the chart (its corners' chart points a, b, c, in the
/// triangle's order), or its slid normal turned against its frame triangle's (turned_against;
/// never where the frame triangle has no area). The line search (rule 9) and the weights (rule
/// 11) hold moving corners until no slid triangle folds.
bool slid_triangle_folds(const Vec2& a, const Vec2& b, const Vec2& c, const Vec3& slid_normal,
                         const Vec3& frame_normal);

/// The same test for patch triangle `t` of a written slide: a movable vertex's chart point from
/// `uv` (by `movable_slot`), the others' their chart nodes; the slid normal from `slid`, the
/// frame's from `frame` (local ids). Rule 11's weights and rule 12's window hold by it.
bool slid_triangle_folds(const Chart& chart, const std::vector<Index>& movable_slot,
                         const Positions2& uv, const Positions3& frame, const Positions3& slid,
                         const Triangle& t);

/// The smallest positive step along `node_d` (per chart node) at which chart triangle t's signed
/// area vanishes (Smith & Schaefer 2015), infinite when none.
double fold_root(const Chart& chart, const Positions2& node_uv, const Positions2& node_d, Index t);

/// Sets `step`'s moving triangles, their fold roots from `state` (Smith & Schaefer 2015: a
/// triangle's signed area is a quadratic in the share of the step) and its fold bound.
void bound_folds(const LineSearchPatch& patch, const SlideState& state, StepCandidate& step);

/// Searches along each candidate (bounded from `state`: bound_folds) from `state` (energy
/// `energy` there) and keeps the one reaching the lower energy. Along a candidate: alpha from
/// min(1, 0.8 x its fold bound), halving at most 40 times; at each alpha the moving vertices go
/// alpha of their step, then the moving corners of every slid triangle folded in the chart or
/// turned against its frame triangle (where that has area) stay where they are, until none is;
/// accepted when `energy_at` falls below `energy` and by at least 1e-4 of the true first-order
/// change of the step taken (Armijo).
LineSearchResult flip_free_line_search(const LineSearchPatch& patch, const SlideState& state,
                                       double energy, const std::vector<StepCandidate>& candidates,
                                       const std::function<double(const Positions3&)>& energy_at);

}  // namespace skinslide
