// Whole-file writes that never leave a partial file: temp file in the target folder + rename.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace skinslide {

/// A file written piece by piece that appears at `path` only when complete: a temporary file
/// beside it takes the pieces (through a buffer) and commit() flushes, closes (each step checked)
/// and renames it over `path`. Destroyed uncommitted (an error on the way), it removes the
/// temporary and leaves `path` as it was. A crash leaves the old file or the new one. It never
/// replaces a device, pipe or socket, nor a file the run read (run_inputs.h).
class AtomicFile {
 public:
  /// \throw Error(Output) naming `path` and the system's reason.
  explicit AtomicFile(const std::string& path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// \throw Error(Output) naming `path` and the system's reason.
  void write(std::string_view bytes);
  /// Writes `bytes` at byte `offset` of the file, for files of a fixed layout whose pieces come
  /// in any order (a point cache's samples): each call is its own pwrite, so several threads may
  /// call it at once. Not mixed with write(): every byte goes through one or the other. A failed
  /// write leaves the temporary for the destructor to remove.
  /// \throw Error(Output) naming `path` and the system's reason.
  void write_at(std::uint64_t offset, std::string_view bytes);
  /// \throw Error(Output) naming `path` and the system's reason.
  void commit();

 private:
  void write_all(const char* bytes, size_t size);
  [[noreturn]] void fail(const std::string& reason);
  void remove_temporary();

  std::string path_;
  std::string temporary_;
  int fd_ = -1;
  int slot_ = -1;  // where the termination handler finds the temporary; -1 = not listed
  std::string buffer_;
};

/// Makes SIGTERM, SIGINT and SIGHUP remove the temporary files of the AtomicFiles in flight, then
/// end the process as the signal would have: a farm's scheduler cancels a task with SIGTERM (and
/// SIGKILL only a grace period later), and a cancelled run then leaves neither a partial output
/// nor a temporary beside it. Signals the process ignores stay ignored. Call once, early in
/// main(), before any thread starts. (SIGKILL cannot be caught: after one, temporaries remain,
/// `.NAME.tmp.XXXXXX`, never a partial NAME.)
void remove_temporaries_on_termination();

/// Writes `bytes` to `path` atomically (AtomicFile in one piece).
/// \throw Error(Output) naming `path` and the system's reason.
void write_file_atomic(const std::string& path, std::string_view bytes);

/// Flushes a folder's entries to disk, so that the renames of write_file_atomic into it survive a
/// power cut, not only a crash. One call after many writes into the same folder is enough. A file
/// system that cannot flush folders (EINVAL) is left as it is.
/// \throw Error(Output) naming `folder` and the system's reason.
void sync_folder(const std::string& folder);

/// Reads a whole file, noted as an input of the run (run_inputs.h).
/// \throw Error(Input) naming `path` when it cannot be read.
std::string read_file(const std::string& path);

}  // namespace skinslide
