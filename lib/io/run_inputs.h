// The files a run reads, which it must never replace. The checks made before a run (frame_plans)
// know the files named on the command line; a run also reads files it discovers (a glTF's
// buffers, the --config file) and writes files beside its outputs (a glTF's .bin, dumps,
// previews). So every reader notes the file it read here, by identity (device and inode, so a
// link or another spelling of the path is the same file), and AtomicFile refuses to replace a
// noted file: an input is never destroyed, whichever output would have landed on it.
#pragma once

#include <optional>
#include <string>

namespace skinslide {

/// While one lives (a run: the command line's, or a library call that writes), the files read
/// are noted; the last one to end forgets them, so a long-lived process (Python, Blender) may
/// write a file it read in an earlier call. Scopes may nest and live on several threads.
class InputScope {
 public:
  InputScope();
  ~InputScope();
  InputScope(const InputScope&) = delete;
  InputScope& operator=(const InputScope&) = delete;
};

/// Notes `path` as read by the run (nothing without a live InputScope, or when it does not
/// exist). Thread-safe.
void note_input(const std::string& path);

/// The path under which the file now at `path` was noted as read, if it was. Thread-safe.
std::optional<std::string> noted_input(const std::string& path);

}  // namespace skinslide
