#include "core/version.h"

namespace skinslide {
const char* version() { return SKINSLIDE_VERSION; }
}  // namespace skinslide
