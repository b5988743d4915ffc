// The real test data in ../shared (the folder checked out beside the repository): where it is,
// and skipping a test that needs a file which is not there (a clone elsewhere has no ../shared).
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace skinslide::test {

/// The shared folder: $SKINSLIDE_SHARED_DIR when set, else ../shared beside the source tree.
inline std::string shared_dir() {
  const char* env = std::getenv("SKINSLIDE_SHARED_DIR");
  return std::filesystem::path(env && *env ? env : SKINSLIDE_SHARED_DIR).lexically_normal().string();
}

/// True when SKINSLIDE_REQUIRE_SHARED=1 (CI, which has ../shared): a missing file fails the test.
inline bool shared_required() {
  const char* env = std::getenv("SKINSLIDE_REQUIRE_SHARED");
  return env && std::string(env) == "1";
}

/// The first of `relatives` (paths in the shared folder) that is missing, as a full path; "" when
/// all are there.
inline std::string missing_shared(const std::vector<std::string>& relatives) {
  for (const std::string& r : relatives) {
    const std::filesystem::path p = std::filesystem::path(shared_dir()) / r;
    if (!std::filesystem::exists(p)) return p.string();
  }
  return "";
}

}  // namespace skinslide::test

/// SKINSLIDE_REQUIRE_SHARED("data/obj/x.obj", ...): in a test body, ends the test when one of
/// the files is missing from the shared folder: skipped with "missing <path>", or failed when
/// SKINSLIDE_REQUIRE_SHARED=1. (GTEST_SKIP returns from the function it is in, hence a macro.)
#define SKINSLIDE_REQUIRE_SHARED(...) \
  SKINSLIDE_SKIP_IF_MISSING_(::skinslide::test::missing_shared({__VA_ARGS__}))

/// Ends the test when `missing` (an expression giving a path, or "" for none) is not empty.
#define SKINSLIDE_SKIP_IF_MISSING_(missing)                                         \
  do {                                                                              \
    const std::string missing_ = (missing);                                         \
    if (!missing_.empty()) {                                                        \
      if (::skinslide::test::shared_required())                                     \
        GTEST_FAIL() << "missing " << missing_ << " (SKINSLIDE_REQUIRE_SHARED=1)";   \
      GTEST_SKIP() << "missing " << missing_;                                       \
    }                                                                               \
  } while (0)
