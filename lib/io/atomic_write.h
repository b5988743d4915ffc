// Whole-file writes that never leave a partial file: temp file in the target folder + rename.
#pragma once

#include <string>
#include <string_view>

namespace skinslide {

/// A file written piece by piece that appears at `path` only when complete: a temporary file
/// beside it takes the pieces (through a buffer) and commit() flushes, closes (each step checked)
/// and renames it over `path`. Destroyed uncommitted (an error on the way), it removes the
/// temporary and leaves `path` as it was. A crash leaves the old file or the new one.
class AtomicFile {
 public:
  /// \throw Error(Output) naming `path` and the system's reason.
  explicit AtomicFile(const std::string& path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// \throw Error(Output) naming `path` and the system's reason.
  void write(std::string_view bytes);
  /// \throw Error(Output) naming `path` and the system's reason.
  void commit();

 private:
  void write_all(const char* bytes, size_t size);
  [[noreturn]] void fail(const std::string& reason);

  std::string path_;
  std::string temporary_;
  int fd_ = -1;
  std::string buffer_;
};

/// Writes `bytes` to `path` atomically (AtomicFile in one piece).
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
