#include "paper/paper_options.h"

namespace skinslide {
namespace {

// Each enum's words, in the order --help lists them; the first word naming a value is its name.
// `length` is the older spelling of `inverse` (q ~ 1/L).
constexpr Words<Density, 4> kDensity{"density",
                                     {{{"paper", Density::Paper},
                                       {"inverse", Density::Inverse},
                                       {"length", Density::Inverse},
                                       {"uniform", Density::Uniform}}}};
constexpr Words<Holes, 2> kHoles{"hole mode", {{{"free", Holes::Free}, {"fill", Holes::Fill}}}};
constexpr Words<FrameSolver, 4> kFrameSolver{"frame solver",
                                             {{{"auto", FrameSolver::Auto},
                                               {"cholesky", FrameSolver::Cholesky},
                                               {"multigrid", FrameSolver::Multigrid},
                                               {"cg", FrameSolver::Cg}}}};
constexpr Words<Locate, 2> kLocate{"locate method",
                                   {{{"walk", Locate::Walk}, {"image", Locate::Image}}}};

}  // namespace

template <>
const OptionTable<PaperOptions>& option_table<PaperOptions>() {
  using O = PaperOptions;
  static const OptionTable<O> table = {
      {"density",
       "Paper: force density q of a bar of length L: paper = 1 - L/Lmax (floored), "
       "inverse|length = Lmin/L, uniform = 1",
       word_option(&O::density, kDensity), /*run_wide=*/false, /*research=*/true},
      {"holes",
       "Paper: inner boundary loops in the bind net: free (the paper) or fill (a virtual centre "
       "node per hole)",
       word_option(&O::holes, kHoles), /*run_wide=*/false, /*research=*/true},
      {"q-floor", "Paper: smallest force density (densities paper, inverse)",
       NumberOption<O, double>{&O::q_floor, 1e-12, 1.0}, /*run_wide=*/false, /*research=*/true},
      {"frame-solver",
       "Paper: how bind and frame nets are solved: cholesky (sparse factor, analysis reused by "
       "every frame), multigrid (conjugate gradient preconditioned by an aggregation multigrid; "
       "no ordering, so a shorter set-up, and faster frames on large patches), auto (multigrid "
       "for patches of " +
           std::to_string(kMultigridFreeNodes) +
           " free vertices or more, else cholesky) or cg (frame nets by Jacobi-preconditioned CG; "
           "slow, for comparison). The nets agree within --cg-tolerance",
       word_option(&O::frame_solver, kFrameSolver), /*run_wide=*/false, /*research=*/true},
      {"cg-tolerance",
       "Paper: CG (multigrid, cg) stops at |r| <= tol |b|; every method keeps a frame's warm "
       "start that meets it",
       NumberOption<O, double>{&O::cg_tolerance, 1e-16, 1e-2}, /*run_wide=*/false,
       /*research=*/true},
      {"cg-max-iterations", "Paper: past this the frame net is solved directly (counted)",
       NumberOption<O, int>{&O::cg_max_iterations, 1, 1000000}, /*run_wide=*/false,
       /*research=*/true},
      {"locate",
       "Paper: finding bind positions in frame nets: walk (from each vertex's own triangles) or "
       "image (a triangle-ID image, --lookup-size)",
       word_option(&O::locate, kLocate), /*run_wide=*/false, /*research=*/true},
      {"lookup-size", "Side of the triangle-ID images (--locate image, --dump), pixels",
       NumberOption<O, int>{&O::lookup_size, 8, 16384}, /*run_wide=*/true, /*research=*/true},
  };
  return table;
}

FrameSolver parse_frame_solver(const std::string& name) { return kFrameSolver.value(name); }
Locate parse_locate(const std::string& name) { return kLocate.value(name); }
std::string to_string(Density d) { return kDensity.name(d); }
std::string to_string(Holes h) { return kHoles.name(h); }
std::string to_string(FrameSolver s) { return kFrameSolver.name(s); }
std::string to_string(Locate l) { return kLocate.name(l); }

}  // namespace skinslide
