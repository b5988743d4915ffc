#include "elastic/elastic_options.h"

namespace skinslide {
namespace {

constexpr Words<ElasticSolver, 2> kSolverWords{
    "solver", {{{"map", ElasticSolver::Map}, {"search", ElasticSolver::Search}}}};

// --blend's narrowest bands, in inradii: below it a band is thinner than round-off places a chart
// point, and the blended surface's slopes overflow (tests/bench/elastic.md "Figures behind the
// code's constants").
constexpr double kMinBlend = 1e-3;

void check_blend(const ElasticOptions& options) {
  if (options.blend > 0 && options.blend < kMinBlend)
    throw Error(ErrorKind::Usage, "--blend " + format_double(options.blend) +
                                      ": bands this narrow are below round-off; use 0 (the facets) "
                                      "or " +
                                      format_double(kMinBlend) + " to 2");
}

// The last rotation fit aims fully at the bind's stretch (relax.h ElasticOptions::ease_in).
void check_ease_in(const ElasticOptions& options) {
  if (options.ease_in >= options.rotation_fits)
    throw Error(ErrorKind::Usage, "--ease-in " + std::to_string(options.ease_in) +
                                      " leaves no rotation fit that aims fully: give at most "
                                      "--rotation-fits - 1 (--rotation-fits is " +
                                      std::to_string(options.rotation_fits) + ")");
}

}  // namespace

template <>
const OptionTable<ElasticOptions>& option_table<ElasticOptions>() {
  using O = ElasticOptions;
  static const OptionTable<O> table = {
      {"solver",
       "Elastic: map (a fixed map of the frame, smooth in time) or search (relax each frame until "
       "its gain left is small: separate poses, e.g. blendshape expressions)",
       word_option(&O::solver, kSolverWords)},
      {"passes",
       "Elastic map: passes from the frame, the quality-for-speed dial (more even the stretch "
       "further; the time grows with them)",
       NumberOption<O, int>{&O::passes, 1, 100}},
      {"rotation-fits",
       "Elastic search: ARAP local/global rounds (fit each triangle's rotation, then relax with "
       "them "
       "held); more reach lower energies, fewer pop less from frame to frame",
       NumberOption<O, int>{&O::rotation_fits, 1, 1000}, /*run_wide=*/false, /*research=*/true,
       "solver", "search"},
      {"max-iterations", "Elastic search: Gauss-Newton steps per round at most",
       NumberOption<O, int>{&O::max_iterations, 0, 100000}, /*run_wide=*/false, /*research=*/true,
       "solver", "search"},
      {"tolerance",
       "Elastic search: a round stops at the first step that lowers its energy by less than this "
       "fraction of its starting energy",
       NumberOption<O, double>{&O::tolerance, 0.0, 1.0}, /*run_wide=*/false, /*research=*/true,
       "solver", "search"},
      {"convergence",
       "Elastic: a frame has converged when the first-order gain left is at most this fraction "
       "of its energy; any other stop is logged as not converged",
       NumberOption<O, double>{&O::convergence, 0.0, 1.0}, /*run_wide=*/false, /*research=*/true},
      {"blend",
       "Elastic search: relax on the frame's facets blended smooth near their edges, each edge's "
       "blend "
       "this share of its triangles' inradius wide (1: far less jitter in slow motion, up to 3x "
       "the relax time); 0: on the facets; else at least 0.001. Slid vertices stay on the facets",
       NumberOption<O, double>{&O::blend, 0.0, 2.0}, /*run_wide=*/false, /*research=*/true,
       "solver", "search", check_blend},
      {"ease-in",
       "Elastic search: the first N rotation fits aim only part of the way from the frame's own "
       "stretch "
       "to the bind's ((r+1)/(N+1) in fit r), so the slide follows one branch of minima from the "
       "frame: less jitter in slow motion, with --blend 1 --tolerance 1e-6 most; fewer than "
       "--rotation-fits",
       NumberOption<O, int>{&O::ease_in, 0, 999}, /*run_wide=*/false, /*research=*/true, "solver",
       "search", check_ease_in},
  };
  return table;
}

}  // namespace skinslide
