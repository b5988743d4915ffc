// Which file a path names, as the system says: the checks that keep a run from writing over
// what it reads (pipeline/frame_plans.h) compare these keys, never spellings. For a path that
// exists, its device and inode (one file under any name: a link, `sub/..`, another spelling); for
// one that does not exist yet (an output a run will make), its nearest existing folder's device
// and inode and the rest of the path below that folder. Two paths name one file exactly when
// their keys are equal.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "core/error.h"

namespace skinslide {

/// A file's identity (FileKeys::key).
struct FileKey {
  std::uint64_t device = 0;
  std::uint64_t inode = 0;
  /// Below the folder (device, inode), lexically normal; empty when the path itself exists.
  std::string rest;
  bool operator==(const FileKey&) const = default;
};

struct FileKeyHash {
  std::size_t operator()(const FileKey& key) const;
};

/// Keys of many paths, each missing path's folder looked at once (a run's outputs share one): a
/// path costs one stat, so n paths are O(n).
class FileKeys {
 public:
  /// The key of `path`. A path that is missing, or leads through a file, is one not made yet.
  /// \throw Error(kind) "PATH: cannot read: REASON" (kind Input) or "PATH: cannot write: REASON"
  ///        (any other kind) when the system cannot look at it: a folder on the way that cannot
  ///        be entered (Permission denied), a loop of links, a name too long.
  FileKey key(const std::string& path, ErrorKind kind);

 private:
  std::unordered_map<std::string, FileKey> folders_;  // a missing path's folder -> its key
};

}  // namespace skinslide
