// The elastic method's options as the command line, the API, the report and Python take them
// (core/option.h): one entry each, over ElasticOptions (elastic/relax.h, where each default is).
#pragma once

#include "core/option.h"
#include "elastic/relax.h"

namespace skinslide {

/// --solver, --passes; the research options --rotation-fits, --max-iterations, --tolerance,
/// --convergence, --blend (0, or 0.001 to 2: its rule) and --ease-in (below --rotation-fits: its
/// rule; check_rules).
template <>
const OptionTable<ElasticOptions>& option_table<ElasticOptions>();

}  // namespace skinslide
