#include "io/file_key.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <functional>

#include <sys/stat.h>

namespace skinslide {

std::size_t FileKeyHash::operator()(const FileKey& key) const {
  std::size_t h = std::hash<std::uint64_t>{}(key.device);
  h ^= std::hash<std::uint64_t>{}(key.inode) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
  h ^= std::hash<std::string>{}(key.rest) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
  return h;
}

FileKey FileKeys::key(const std::string& path, ErrorKind kind) {
  namespace fs = std::filesystem;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0)
    return {static_cast<std::uint64_t>(st.st_dev), static_cast<std::uint64_t>(st.st_ino), {}};
  // Missing, or below a file: not made yet, named by its folder. Anything else (EACCES, ELOOP,
  // ENAMETOOLONG) means the system cannot say which file it is: never "the same" as another.
  if (errno != ENOENT && errno != ENOTDIR)
    throw Error(kind, path + (kind == ErrorKind::Input ? ": cannot read: " : ": cannot write: ") +
                          std::strerror(errno));
  const fs::path p(path);
  std::string folder = p.parent_path().string();
  if (folder.empty()) folder = ".";
  if (folder == path)  // a root that is missing: nothing above it to name it by
    throw Error(kind, path + ": cannot look at it: " + std::strerror(ENOENT));
  auto found = folders_.find(folder);
  if (found == folders_.end()) found = folders_.emplace(folder, key(folder, kind)).first;
  FileKey k = found->second;
  k.rest = (fs::path(k.rest) / p.filename()).lexically_normal().string();
  return k;
}

}  // namespace skinslide
