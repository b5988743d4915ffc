#include "elastic/elastic_options.h"

namespace skinslide {

template <>
const OptionTable<ElasticOptions>& option_table<ElasticOptions>() {
  using O = ElasticOptions;
  static const OptionTable<O> table = {
      {"rotation-fits",
       "Elastic: ARAP local/global rounds (fit each triangle's rotation, then relax with them "
       "held); more reach lower energies, fewer pop less from frame to frame",
       NumberOption<O, int>{&O::rotation_fits, 1, 1000}},
      {"max-iterations", "Elastic: Gauss-Newton steps per round at most",
       NumberOption<O, int>{&O::max_iterations, 0, 100000}},
      {"tolerance",
       "Elastic: a round stops at the first step that lowers its energy by less than this "
       "fraction of its starting energy",
       NumberOption<O, double>{&O::tolerance, 0.0, 1.0}},
      {"convergence",
       "Elastic: a frame has converged when the first-order gain left is at most this fraction "
       "of its energy; any other stop is logged as not converged",
       NumberOption<O, double>{&O::convergence, 0.0, 1.0}},
      {"blend",
       "Elastic: relax on the frame's facets blended smooth near their edges, each edge's blend "
       "this share of its triangles' inradius wide (1: far less jitter in slow motion, up to 3x "
       "the relax time); 0: on the facets; else at least 0.001. Slid vertices stay on the facets",
       NumberOption<O, double>{&O::blend, 0.0, 2.0}},
      {"ease-in",
       "Elastic: the first N rotation fits aim only part of the way from the frame's own stretch "
       "to the bind's ((r+1)/(N+1) in fit r), so the slide follows one branch of minima from the "
       "frame: less jitter in slow motion, with --blend 1 --tolerance 1e-6 most; fewer than "
       "--rotation-fits",
       NumberOption<O, int>{&O::ease_in, 0, 999}},
  };
  return table;
}

}  // namespace skinslide
