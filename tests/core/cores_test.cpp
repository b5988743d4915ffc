#include "core/cores.h"

#include <sched.h>

#include <gtest/gtest.h>

namespace skinslide {
namespace {

// Pinned to one core (as `taskset -c N` pins a farm task), the process has one core to use,
// whatever the machine has; unpinned again, it has its whole mask back.
TEST(Cores, FollowTheAffinityMaskNotTheMachine) {
  cpu_set_t original;
  ASSERT_EQ(sched_getaffinity(0, sizeof original, &original), 0);
  const int all = CPU_COUNT(&original);
  ASSERT_GT(all, 0);
  EXPECT_EQ(usable_cores(), static_cast<unsigned>(all));
  int first = 0;
  while (!CPU_ISSET(first, &original)) ++first;
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(first, &one);
  // A sandbox may forbid pinning (seccomp); there is nothing to check then.
  if (sched_setaffinity(0, sizeof one, &one) != 0) GTEST_SKIP() << "this sandbox forbids pinning";
  EXPECT_EQ(usable_cores(), 1u);
  ASSERT_EQ(sched_setaffinity(0, sizeof original, &original), 0);
  EXPECT_EQ(usable_cores(), static_cast<unsigned>(all));
}

}  // namespace
}  // namespace skinslide
