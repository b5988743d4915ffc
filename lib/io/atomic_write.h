// Whole-file writes that never leave a partial file: temp file in the target folder + rename.
#pragma once

#include <string>
#include <string_view>

namespace skinslide {

/// Writes `bytes` to `path` atomically: a temporary file beside it is written, flushed, closed
/// (each step checked) and renamed over `path`. A crash leaves the old file or the new one.
/// \throw Error(Output) naming `path` and the system's reason.
void write_file_atomic(const std::string& path, std::string_view bytes);

/// Reads a whole file. \throw Error(Input) naming `path` when it cannot be read.
std::string read_file(const std::string& path);

}  // namespace skinslide
