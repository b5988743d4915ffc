#include "io/atomic_write.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "core/error.h"
#include "helpers/meshes.h"

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

}  // namespace skinslide
