// The paper method's options (README "Options"): PaperOptions with each default, the words of its
// enums, and its option table (core/option.h), from which the command line, the API, the report
// and Python take them.
#pragma once

#include <string>

#include "core/option.h"
#include "locate/id_raster.h"
#include "paper/force_density.h"

namespace skinslide {

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
/// n^1.5 and a multigrid solve as n, so above some size the multigrid's frame net is the
/// cheaper; this is the measured crossover (tests/bench/README.md "Where Auto switches").
constexpr int kMultigridFreeNodes = 6000;

/// How each free vertex's bind-net point is found in the frame net (the same rule for picking
/// among the triangles that hold it; README "The method, exactly", 7).
enum class Locate {
  Walk,   ///< walk the frame net from the vertex's own triangles
  Image,  ///< look up a triangle-ID image of the frame net (the paper's way)
};

/// The paper method's tunables (README "Options"), with their defaults.
struct PaperOptions {
  Density density = Density::Inverse;
  Holes holes = Holes::Fill;
  double q_floor = 1e-3;  ///< lower bound of q (Density::Paper, Inverse)
  FrameSolver frame_solver = FrameSolver::Auto;
  double cg_tolerance = 1e-12;   ///< CG stops at |r| <= tol * |b| (Eigen's criterion)
  int cg_max_iterations = 2000;  ///< past it the frame net is solved directly (counted)
  Locate locate = Locate::Walk;
  int lookup_size = kLookupSize;  ///< ID image side in pixels (Locate::Image)
};

/// --density, --holes, --q-floor, --frame-solver, --cg-tolerance, --cg-max-iterations, --locate,
/// --lookup-size (which the command line also takes with the elastic method, for --dump).
template <>
const OptionTable<PaperOptions>& option_table<PaperOptions>();

FrameSolver parse_frame_solver(const std::string& name);  ///< throws Usage on an unknown name
Locate parse_locate(const std::string& name);             ///< throws Usage on an unknown name
std::string to_string(Density d);
std::string to_string(Holes h);
std::string to_string(FrameSolver s);
std::string to_string(Locate l);

}  // namespace skinslide
