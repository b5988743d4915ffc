#include "io/atomic_write.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/check.h"
#include "core/error.h"
#include "io/run_inputs.h"

namespace skinslide {
namespace {

[[noreturn]] void throw_output(const std::string& path, const std::string& what) {
  throw Error(ErrorKind::Output, path + ": cannot write: " + what);
}

// The temporaries in flight, where a signal handler can read them: fixed slots of plain
// characters (no allocation, no lock), each free, being filled, or listing a live temporary.
// A temporary that finds no slot is still never renamed half-written; only a signal would leave
// it behind, as SIGKILL leaves any.
constexpr int kTemporarySlots = 256;  // files written at once: a few per frame thread
constexpr std::size_t kSlotPathBytes = 4096;
enum SlotState : int { kFree, kFilling, kLive };
struct TemporarySlot {
  std::atomic<int> state{kFree};
  char path[kSlotPathBytes];
};
TemporarySlot temporary_slots[kTemporarySlots];
static_assert(std::atomic<int>::is_always_lock_free, "slots read by a signal handler");

int list_temporary(const std::string& path) {
  if (path.size() >= kSlotPathBytes) return -1;
  for (int i = 0; i < kTemporarySlots; ++i) {
    int expected = kFree;
    if (!temporary_slots[i].state.compare_exchange_strong(expected, kFilling)) continue;
    std::memcpy(temporary_slots[i].path, path.c_str(), path.size() + 1);
    temporary_slots[i].state.store(kLive, std::memory_order_release);
    return i;
  }
  return -1;
}

void unlist_temporary(int slot) {
  if (slot >= 0) temporary_slots[slot].state.store(kFree, std::memory_order_release);
}

// Async-signal-safe: atomic loads, unlink, signal, raise. A slot freed and refilled while this
// runs names a file already renamed or removed (unlink fails harmlessly) or is skipped.
extern "C" void remove_temporaries_and_end(int signal_number) {
  for (TemporarySlot& slot : temporary_slots)
    if (slot.state.load(std::memory_order_acquire) == kLive) ::unlink(slot.path);
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

}  // namespace

void remove_temporaries_on_termination() {
  for (const int signal_number : {SIGTERM, SIGINT, SIGHUP}) {
    struct sigaction action {
    }, previous{};
    action.sa_handler = remove_temporaries_and_end;
    sigemptyset(&action.sa_mask);
    if (::sigaction(signal_number, &action, &previous) == 0 && previous.sa_handler == SIG_IGN)
      ::sigaction(signal_number, &previous, nullptr);  // nohup and `&` in scripts ignore some
  }
}

constexpr size_t kBufferBytes = size_t{1} << 20;  // pieces are gathered into writes this size

AtomicFile::AtomicFile(const std::string& path) : path_(path) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  std::error_code ec;
  if (fs::is_directory(target, ec)) throw_output(path, "it is a directory");
  // rename() would replace a device, a pipe or a socket (/dev/null as root) with a plain file.
  if (fs::exists(target, ec) && !fs::is_regular_file(target, ec))
    throw_output(path,
                 "it is not a regular file (a device, a pipe or a socket), which a whole-"
                 "file write would replace");
  if (const std::optional<std::string> input = noted_input(path))
    throw_output(path, "it is an input of this run (" + *input +
                           "), which the output would replace; choose another output folder");
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  // The temporary lives in the target folder so that rename() is atomic (same file system);
  // its name starts with '.' so a glob over the folder does not pick up a half-written file.
  std::string name = ".";
  name.append(target.filename().string()).append(".tmp.XXXXXX");
  temporary_ = (dir / name).string();
  fd_ = mkstemp(temporary_.data());
  if (fd_ < 0) throw_output(path, std::strerror(errno));
  slot_ = list_temporary(temporary_);
  buffer_.reserve(kBufferBytes);
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) {
    ::close(fd_);
    remove_temporary();
  }
}

void AtomicFile::remove_temporary() {
  ::unlink(temporary_.c_str());
  unlist_temporary(slot_);
  slot_ = -1;
}

void AtomicFile::fail(const std::string& reason) {
  ::close(fd_);
  fd_ = -1;
  remove_temporary();
  throw_output(path_, reason);
}

void AtomicFile::write_all(const char* p, size_t left) {
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(std::strerror(errno));
    }
    p += n;
    left -= static_cast<size_t>(n);
  }
}

void AtomicFile::write(std::string_view bytes) {
  SKINSLIDE_CHECK(fd_ >= 0, "a file not yet committed");
  if (buffer_.size() + bytes.size() <= kBufferBytes) {
    buffer_.append(bytes);
    return;
  }
  write_all(buffer_.data(), buffer_.size());
  buffer_.clear();
  if (bytes.size() >= kBufferBytes)
    write_all(bytes.data(), bytes.size());  // a large piece goes out as it is, uncopied
  else
    buffer_.append(bytes);
}

void AtomicFile::write_at(std::uint64_t offset, std::string_view bytes) {
  SKINSLIDE_CHECK(fd_ >= 0 && buffer_.empty(), "write_at on an open file without write()s");
  const char* p = bytes.data();
  size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::pwrite(fd_, p, left, static_cast<off_t>(offset));
    if (n < 0) {
      if (errno == EINTR) continue;
      // No fail(): other threads may be writing through fd_; the destructor cleans up.
      throw_output(path_, std::strerror(errno));
    }
    p += n;
    offset += static_cast<std::uint64_t>(n);
    left -= static_cast<size_t>(n);
  }
}

void AtomicFile::commit() {
  SKINSLIDE_CHECK(fd_ >= 0, "a file not yet committed");
  write_all(buffer_.data(), buffer_.size());
  buffer_.clear();
  // mkstemp creates 0600; outputs get the usual 0666 & ~umask like any other file. umask() can
  // only be read by setting it, and frames are written from several threads: read it once.
  static const mode_t mask = [] {
    const mode_t m = ::umask(0);
    ::umask(m);
    return m;
  }();
  if (::fchmod(fd_, 0666 & ~mask) != 0 || ::fsync(fd_) != 0) fail(std::strerror(errno));
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    const std::string reason = std::strerror(errno);
    remove_temporary();
    throw_output(path_, reason);
  }
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    remove_temporary();
    throw_output(path_, reason);
  }
  unlist_temporary(slot_);
  slot_ = -1;
}

void write_file_atomic(const std::string& path, std::string_view bytes) {
  AtomicFile file(path);
  file.write(bytes);
  file.commit();
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
  note_input(path);
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
