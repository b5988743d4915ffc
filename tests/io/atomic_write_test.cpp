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
