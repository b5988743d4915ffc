#include "core/allocator.h"

#include <gtest/gtest.h>

namespace skinslide {

constexpr const char* kMadvise = "always [madvise] never\n";

TEST(HugePages, RestartsOnlyWhereTheKernelWaitsToBeAsked) {
  EXPECT_TRUE(huge_pages_restart_wanted(kMadvise, nullptr, nullptr, "2.36"));
  // Already on for every mapping, or off whatever glibc asks.
  EXPECT_FALSE(huge_pages_restart_wanted("[always] madvise never\n", nullptr, nullptr, "2.36"));
  EXPECT_FALSE(huge_pages_restart_wanted("always madvise [never]\n", nullptr, nullptr, "2.36"));
  // No such file (a container without /sys): nothing known, nothing done.
  EXPECT_FALSE(huge_pages_restart_wanted("", nullptr, nullptr, "2.36"));
}

TEST(HugePages, TheUsersTunableDecides) {
  EXPECT_FALSE(huge_pages_restart_wanted(kMadvise, "glibc.malloc.hugetlb=0", nullptr, "2.36"));
  EXPECT_FALSE(huge_pages_restart_wanted(kMadvise, "glibc.malloc.check=3:glibc.malloc.hugetlb=1",
                                         nullptr, "2.36"));
  // Other tunables are kept and the request appended.
  EXPECT_TRUE(huge_pages_restart_wanted(kMadvise, "glibc.malloc.check=3", nullptr, "2.36"));
  EXPECT_EQ(tunables_with_huge_pages("glibc.malloc.check=3"),
            "glibc.malloc.check=3:glibc.malloc.hugetlb=1");
  EXPECT_EQ(tunables_with_huge_pages(nullptr), "glibc.malloc.hugetlb=1");
  EXPECT_EQ(tunables_with_huge_pages(""), "glibc.malloc.hugetlb=1");
}

TEST(HugePages, NoRestartUnderValgrindOrWithAnOldGlibc) {
  EXPECT_FALSE(huge_pages_restart_wanted(
      kMadvise, nullptr, "/usr/libexec/valgrind/vgpreload_memcheck-amd64-linux.so", "2.36"));
  EXPECT_TRUE(huge_pages_restart_wanted(kMadvise, nullptr, "/usr/lib/libfoo.so", "2.36"));
  EXPECT_FALSE(huge_pages_restart_wanted(kMadvise, nullptr, nullptr, "2.34"));
  EXPECT_TRUE(huge_pages_restart_wanted(kMadvise, nullptr, nullptr, "2.35"));
  EXPECT_TRUE(huge_pages_restart_wanted(kMadvise, nullptr, nullptr, "3.0"));
  EXPECT_FALSE(huge_pages_restart_wanted(kMadvise, nullptr, nullptr, "unknown"));
}

}  // namespace skinslide
