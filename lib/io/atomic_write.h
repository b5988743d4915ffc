// Whole-file writes that never leave a partial file: temp file in the target folder + rename.
#pragma once

#include <string>
#include <string_view>

namespace skinslide {

/// Writes `bytes` to `path` atomically: a temporary file beside it is written, flushed, closed
/// (each step checked) and renamed over `path`. A crash leaves the old file or the new one.
/// \throw Error(Output) naming `path` and the system's reason.
void write_file_atomic(const std::string& path, std::string_view bytes);

/// Flushes a folder's entries to disk, so that the renames of write_file_atomic into it survive a
/// power cut, not only a crash. One call after many writes into the same folder is enough. A file
/// system that cannot flush folders (EINVAL) is left as it is.
/// \throw Error(Output) naming `folder` and the system's reason.
void sync_folder(const std::string& folder);

/// Reads a whole file. \throw Error(Input) naming `path` when it cannot be read.
std::string read_file(const std::string& path);

}  // namespace skinslide
