// The animator's controls of a run read from their files and options (README "Controls"): slide
// weights (a file, the OBJ bind's vertex colours or a glTF attribute), strength, pins, corners,
// outer loops. Read after the bind, whose vertex count checks their ids.
#pragma once

#include "io/mesh_file.h"
#include "pipeline/options.h"
#include "pipeline/report.h"
#include "pipeline/run_options.h"

namespace skinslide {

/// The controls `o` names, read against `bind`; `report` records where they came from.
/// \throw Error(Input) for a malformed file (path and line), Error(Usage) for a malformed
///        --corners or a control the bind's format cannot give (vertex colours of a glTF).
SlideControls slide_controls(const RunOptions& o, const MeshFile& bind, RunReport& report);

}  // namespace skinslide
