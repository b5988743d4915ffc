#include "io/atomic_write.h"

#include <csignal>
#include <filesystem>

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include "core/error.h"
#include "helpers/meshes.h"
#include "helpers/temp_dir.h"

namespace skinslide {

TEST(AtomicWrite, WritesReplacesAndLeavesNoTemporary) {
  namespace fs = std::filesystem;
  const std::string dir = test::temp_dir("atomic");
  const std::string path = dir + "/out.obj";
  write_file_atomic(path, "first");
  write_file_atomic(path, "second");
  EXPECT_EQ(read_file(path), "second");
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1);
}

// Pieces below, at and above the buffer's size (1 MiB) come out in order, byte for byte; the
// old file stays until commit, and an abandoned file leaves nothing behind.
TEST(AtomicWrite, AFileWrittenInPiecesAppearsWholeOnlyOnCommit) {
  namespace fs = std::filesystem;
  const std::string dir = test::temp_dir("atomic_pieces");
  const std::string path = dir + "/out.obj";
  write_file_atomic(path, "old");
  std::string expected;
  {
    AtomicFile file(path);
    for (size_t size : {size_t{1}, size_t{1000}, size_t{1} << 20, size_t{3}, (size_t{1} << 20) + 7,
                        size_t{700000}, size_t{700000}}) {
      std::string piece(size, '\0');
      for (size_t i = 0; i < size; ++i)
        piece[i] = static_cast<char>('a' + (expected.size() + i) % 26);
      expected += piece;
      file.write(piece);
      EXPECT_EQ(read_file(path), "old");
    }
    file.commit();
  }
  EXPECT_EQ(read_file(path), expected);
  {
    AtomicFile abandoned(path);
    abandoned.write("never");
  }
  EXPECT_EQ(read_file(path), expected);
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1);
}

TEST(AtomicWrite, SyncingAFolderWorksOnAFolderAndNamesAMissingOne) {
  const std::string dir = test::temp_dir("atomic_sync");
  write_file_atomic(dir + "/a.obj", "a");
  EXPECT_NO_THROW(sync_folder(dir));
  try {
    sync_folder(dir + "/missing");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Output);
    EXPECT_NE(std::string(e.what()).find(dir + "/missing: cannot write: "), std::string::npos)
        << e.what();
  }
}

TEST(AtomicWrite, FailuresAreOutputErrorsNamingThePath) {
  const std::string dir = test::temp_dir("atomic_fail");
  try {
    write_file_atomic(dir, "x");  // a folder
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Output);
    EXPECT_NE(std::string(e.what()).find(dir), std::string::npos);
  }
  EXPECT_THROW(write_file_atomic(dir + "/missing/sub/out.obj", "x"), Error);
  EXPECT_THROW(read_file(dir + "/none.obj"), Error);
}

// A child process holding a file half written is ended by `signal_number`: returns how it ended
// (waitpid's status). `ignore_first`: the child ignores the signal before installing the cleanup.
int end_child_writing(const std::string& path, int signal_number, bool ignore_first) {
  int ready[2];
  if (::pipe(ready) != 0) return -1;
  const pid_t child = ::fork();
  if (child == 0) {
    if (ignore_first) ::signal(signal_number, SIG_IGN);
    remove_temporaries_on_termination();
    AtomicFile file(path);
    file.write(std::string(3 << 20, 'x'));  // past the buffer: bytes in the temporary
    if (::write(ready[1], "r", 1) != 1) ::_exit(2);
    for (;;) ::pause();
  }
  char byte = 0;
  const bool started = ::read(ready[0], &byte, 1) == 1;
  ::close(ready[0]);
  ::close(ready[1]);
  ::kill(child, signal_number);
  if (ignore_first) {
    ::usleep(100000);  // the signal, ignored, must not end it: SIGKILL does
    int status = 0;
    EXPECT_EQ(::waitpid(child, &status, WNOHANG), 0) << "an ignored signal ended the child";
    ::kill(child, SIGKILL);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  return started ? status : -1;
}

// A scheduler cancelling a task (SIGTERM) or a person pressing Ctrl-C (SIGINT): the half-written
// file's temporary goes, nothing appears at its name, and the process ends by that signal.
TEST(AtomicWrite, TerminationRemovesTheTemporariesInFlight) {
  namespace fs = std::filesystem;
  for (const int signal_number : {SIGTERM, SIGINT, SIGHUP}) {
    const test::TempDir dir("atomic_term" + std::to_string(signal_number));
    const int status = end_child_writing(dir / "out.pc2", signal_number, false);
    ASSERT_TRUE(WIFSIGNALED(status)) << status;
    EXPECT_EQ(WTERMSIG(status), signal_number);
    EXPECT_TRUE(fs::is_empty(dir.path())) << fs::directory_iterator(dir.path())->path();
  }
  // An ignored signal stays ignored; SIGKILL cannot be caught and leaves the temporary.
  const test::TempDir dir("atomic_term_ignored");
  const int status = end_child_writing(dir / "out.pc2", SIGTERM, true);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGKILL);
  ASSERT_FALSE(fs::is_empty(dir.path()));
  const std::string left = fs::directory_iterator(dir.path())->path().filename().string();
  EXPECT_EQ(left.rfind(".out.pc2.tmp.", 0), 0u) << left;
}

}  // namespace skinslide
