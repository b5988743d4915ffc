// The elastic method's options as the command line, the API, the report and Python take them
// (core/option.h): one entry each, over ElasticOptions (elastic/relax.h, where each default is).
#pragma once

#include "core/option.h"
#include "elastic/relax.h"

namespace skinslide {

/// --rotation-fits, --max-iterations, --tolerance, --convergence, --blend, --ease-in.
template <>
const OptionTable<ElasticOptions>& option_table<ElasticOptions>();

}  // namespace skinslide
