#include "pipeline/input_checks.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <optional>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/mesh_formats.h"
#include "pipeline/cache_frames.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

// Why `path` cannot be read, in read_file's words (io/atomic_write.h); none when it can. Without
// blocking: a named pipe opens at once here, and is read (or waited for) by its reader.
std::optional<Error> unreadable(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return Error(ErrorKind::Input, path + ": cannot read: " + std::strerror(errno));
  struct stat st {};
  const bool folder = ::fstat(fd, &st) == 0 && S_ISDIR(st.st_mode);
  ::close(fd);
  if (folder) return Error(ErrorKind::Input, path + ": cannot read: it is a directory");
  return std::nullopt;
}

void require_readable(const std::string& path) {
  if (std::optional<Error> e = unreadable(path)) throw *e;
}

// The FRAME files of `read` that cannot be read; without keep_going the first, with the others
// counted.
std::vector<UnreadableFrame> check_frame_files(const RunOptions& o,
                                               const std::vector<std::size_t>& read) {
  std::vector<UnreadableFrame> bad;
  for (std::size_t i : read)
    if (std::optional<Error> e = unreadable(o.frames[i])) bad.push_back({i, std::move(*e)});
  if (bad.empty() || o.keep_going) return bad;
  std::string text = bad.front().error.what();
  if (bad.size() > 1)
    text += " (and " + std::to_string(bad.size() - 1) + " more of the " +
            std::to_string(o.frames.size()) + " FRAMEs, " + o.frames[bad[1].frame] +
            (bad.size() > 2 ? ", ..." : "") + "; --keep-going names each and slides the rest)";
  throw Error(ErrorKind::Input, text);
}

}  // namespace

std::vector<UnreadableFrame> check_inputs(const RunOptions& o,
                                          const std::vector<std::size_t>& chosen) {
  const bool cache_run = !o.rig && is_cache_run(o.frames);
  (void)mesh_format(o.bind);
  if (!cache_run)
    for (const std::string& f : o.frames) (void)mesh_format(f);
  require_readable(o.bind);
  for (const std::string& p : o.patches) require_readable(p);
  for (const std::string* f : {&o.weights, &o.pin})
    if (!f->empty()) require_readable(*f);
  if (cache_run) {
    require_readable(o.frames.front());
    return {};
  }
  // --window reads the chosen frames' neighbours too: then every FRAME is read.
  std::vector<std::size_t> read = chosen;
  if (o.window > 0) {
    read.resize(o.frames.size());
    std::iota(read.begin(), read.end(), std::size_t{0});
  }
  return check_frame_files(o, read);
}

void check_output_folder(const std::string& folder, const std::string& first_output) {
  std::error_code ec;
  if (fs::exists(folder, ec)) {
    if (!fs::is_directory(folder, ec))
      throw Error(ErrorKind::Output, folder + ": cannot write: exists and is not a folder");
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
      throw Error(ErrorKind::Output, first_output + ": cannot write: " + std::strerror(errno));
    return;
  }
  // The folders create_directories would make, up to the nearest one there.
  fs::path above = fs::path(folder).parent_path();
  while (!above.empty() && !fs::exists(above, ec)) above = above.parent_path();
  if (above.empty()) above = ".";
  const int fault = !fs::is_directory(above, ec)                ? ENOTDIR
                    : ::access(above.c_str(), W_OK | X_OK) != 0 ? errno
                                                                : 0;
  if (fault != 0)
    throw Error(ErrorKind::Output,
                folder + ": cannot create the output folder: " + std::strerror(fault));
}

}  // namespace skinslide
