// skinslide's version string, as `--version` prints it and EXR headers record it.
#pragma once

namespace skinslide {
const char* version();
}
