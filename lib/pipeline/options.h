// Tunables of the method, with their defaults (README "Options").
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/types.h"
#include "elastic/relax.h"
#include "unwrap/force_density.h"

namespace skinslide {

/// Which slide a run makes (README "The method, exactly"). Everything before (patches, loops, pins,
/// weights) and after (transfer, write, report) is shared.
enum class SlideMethod {
  Elastic,  ///< the default: the free vertices relax in a fixed chart of the patch
  Paper,    ///< Yang & Zhang 2010: bind and frame flattened by bar nets, bind points located
};

/// What the non-outer boundary loops (holes) do in the bind net.
enum class Holes {
  Free,  ///< the paper: hole vertices are free nodes
  Fill,  ///< each hole gets a virtual free node joined to every loop vertex
};

/// How each frame net is solved (same result within the CG tolerance).
enum class FrameSolver {
  Auto,       ///< per patch: Multigrid from kMultigridFreeNodes free nodes on, else Cholesky
  Cholesky,   ///< sparse Cholesky, ordering and symbolic analysis reused by every frame
  Cg,         ///< conjugate gradient (Jacobi), warm-started at the bind net
  Multigrid,  ///< conjugate gradient preconditioned by an aggregation multigrid, warm-started
};

/// Where Auto switches to Multigrid: the frame system's free nodes. A factorisation grows as
/// n^1.5 and a multigrid solve as n. With the multigrid's two-lane sweeps in Cuthill-McKee order,
/// fused passes and its coarse steps' products taken from their sweeps, a frame net costs,
/// Cholesky against multigrid (three interleaved runs each): on the benchmark's nets 1.6k free
/// nodes 0.55 / 0.76 ms, 4.3k 1.85 / 1.99, 8.8k 4.86 / 4.29; on the ICT face (9.0k) 5.59 /
/// 5.26. The crossover lies near 6k; the multigrid's set-up, with no ordering, is 1.6-2.4x
/// shorter at every size (4.3k: 18.4 against 8.7 ms).
constexpr int kMultigridFreeNodes = 6000;

/// How each free vertex's bind-net point is found in the frame net (the same rule for picking
/// among the triangles that hold it; README "The method, exactly", 7).
enum class Locate {
  Walk,   ///< walk the frame net from the vertex's own triangles
  Image,  ///< look up a triangle-ID image of the frame net (the paper's way)
};

struct SlideOptions {
  SlideMethod method = SlideMethod::Elastic;
  ElasticOptions elastic;  ///< SlideMethod::Elastic only
  // The rest: SlideMethod::Paper only.
  Density density = Density::Inverse;
  Holes holes = Holes::Fill;
  double q_floor = 1e-3;  ///< lower bound of q (Paper, Inverse)
  FrameSolver frame_solver = FrameSolver::Auto;
  double cg_tolerance = 1e-12;   ///< CG stops at |r| <= tol * |b| (Eigen's criterion)
  int cg_max_iterations = 2000;  ///< past it the frame net is solved directly (counted)
  Locate locate = Locate::Walk;
  int lookup_size = 1024;  ///< ID image side in pixels (Locate::Image)
};

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
  /// Corner choices, each four mesh vertex ids on one boundary loop of a patch, in the loop's
  /// walking order, for (0,0) (1,0) (1,1) (0,1). The loop holding them becomes the outer loop of
  /// every patch it bounds. Empty = automatic (README rule 3).
  std::vector<std::array<Index, 4>> corners;
  /// Outer-loop choices: the boundary loop through each vertex becomes the outer loop of every
  /// patch it bounds (corners then automatic on that loop unless `corners` names them).
  std::vector<Index> outer_loop_vertices;
};

SlideMethod parse_method(const std::string& name);         ///< throws Usage on an unknown name
Density parse_density(const std::string& name);           ///< throws Usage on an unknown name
Holes parse_holes(const std::string& name);               ///< throws Usage on an unknown name
FrameSolver parse_frame_solver(const std::string& name);  ///< throws Usage on an unknown name
Locate parse_locate(const std::string& name);             ///< throws Usage on an unknown name
std::string to_string(SlideMethod m);
std::string to_string(Density d);
std::string to_string(Holes h);
std::string to_string(FrameSolver s);
std::string to_string(Locate l);

}  // namespace skinslide
