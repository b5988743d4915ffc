// The checks a run makes before its bind is set up (README "Exit codes"): every file it reads is
// there, readable and of a known format, and its output folder can be written, each by a look
// at the file system (stat, open), none by reading a mesh: a shot of a thousand frames with one
// missing fails in its first second, not hours later at that frame.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/error.h"
#include "pipeline/run_options.h"

namespace skinslide {

/// A FRAME file that cannot be read: its index in RunOptions::frames and why.
struct UnreadableFrame {
  std::size_t frame = 0;
  Error error;
};

/// Looks at every file `options` reads (BIND, the FRAME files or the cache, --patch, --weights,
/// --pin): each must exist, be a file (not a folder) that opens for reading, and BIND and FRAME
/// files must have a mesh extension (.obj, .gltf, .glb) or be one point cache. Of FRAME files,
/// those `chosen` (indices into options.frames: the plan's) are looked at, every one with
/// --window (a chosen frame's neighbours are read too). Opens, reads nothing.
/// \return with keep_going, the FRAME files that cannot be read, in frame order (each such
///         frame fails, the others are slid); empty otherwise.
/// \throw Error(Usage) "PATH: unknown mesh format" for a BIND or FRAME file's extension;
///        Error(Input) "PATH: cannot read: REASON" for the first input that is missing, a folder
///        or unreadable (without keep_going, a FRAME too: the message then counts the others).
std::vector<UnreadableFrame> check_inputs(const RunOptions& options,
                                          const std::vector<std::size_t>& chosen);

/// That the run may write `folder`: an existing folder it can create files in, or a missing one
/// whose nearest existing folder it can create folders in. Makes nothing.
/// \throw Error(Output) "FOLDER: cannot write: exists and is not a folder", "FOLDER: cannot
///        create the output folder: REASON", or "FIRST: cannot write: REASON" (`first_output`, the
///        run's first output in that folder) when the folder is not writable.
void check_output_folder(const std::string& folder, const std::string& first_output);

}  // namespace skinslide
