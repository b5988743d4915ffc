#include "io/atomic_write.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/error.h"

namespace skinslide {
namespace {

[[noreturn]] void throw_output(const std::string& path, const std::string& what) {
  throw Error(ErrorKind::Output, path + ": cannot write: " + what);
}

}  // namespace

void write_file_atomic(const std::string& path, std::string_view bytes) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  std::error_code ec;
  if (fs::is_directory(target, ec)) throw_output(path, "it is a directory");
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  // The temporary lives in the target folder so that rename() is atomic (same file system);
  // its name starts with '.' so a glob over the folder does not pick up a half-written file.
  std::string name = ".";
  name.append(target.filename().string()).append(".tmp.XXXXXX");
  std::string tmpl = (dir / name).string();
  const int fd = mkstemp(tmpl.data());
  if (fd < 0) throw_output(path, std::strerror(errno));
  const char* p = bytes.data();
  size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string reason = std::strerror(errno);
      ::close(fd);
      ::unlink(tmpl.c_str());
      throw_output(path, reason);
    }
    p += n;
    left -= static_cast<size_t>(n);
  }
  // mkstemp creates 0600; outputs get the usual 0666 & ~umask like any other file. umask() can
  // only be read by setting it, and frames are written from several threads: read it once.
  static const mode_t mask = [] {
    const mode_t m = ::umask(0);
    ::umask(m);
    return m;
  }();
  if (::fchmod(fd, 0666 & ~mask) != 0 || ::fsync(fd) != 0) {
    const std::string reason = std::strerror(errno);
    ::close(fd);
    ::unlink(tmpl.c_str());
    throw_output(path, reason);
  }
  if (::close(fd) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(tmpl.c_str());
    throw_output(path, reason);
  }
  if (std::rename(tmpl.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(tmpl.c_str());
    throw_output(path, reason);
  }
}

void sync_folder(const std::string& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw_output(folder, std::strerror(errno));
  if (::fsync(fd) != 0 && errno != EINVAL) {
    const std::string reason = std::strerror(errno);
    ::close(fd);
    throw_output(folder, reason);
  }
  ::close(fd);
}

std::string read_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw Error(ErrorKind::Input, path + ": cannot read: it is a directory");
  // One bulk read into a string of the file's size: no stream buffers, no second copy.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw Error(ErrorKind::Input, path + ": cannot read: " + std::strerror(errno));
  struct stat st {};
  std::string bytes;
  if (::fstat(fd, &st) == 0 && st.st_size > 0) bytes.resize(static_cast<size_t>(st.st_size));
  size_t used = 0;
  char probe[4096];  // past the expected size (a file that grew, or a pipe): read on in chunks
  for (;;) {
    const bool full = used == bytes.size();
    const ssize_t n = full ? ::read(fd, probe, sizeof probe)
                           : ::read(fd, bytes.data() + used, bytes.size() - used);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::string reason = std::strerror(errno);
      ::close(fd);
      throw Error(ErrorKind::Input, path + ": read failed: " + reason);
    }
    if (n == 0) break;
    if (full) bytes.append(probe, static_cast<size_t>(n));
    used += static_cast<size_t>(n);
  }
  ::close(fd);
  bytes.resize(used);
  return bytes;
}

}  // namespace skinslide
