#include "hoilcd/core/util/cpus.h"

#include <gtest/gtest.h>
#include <sched.h>

#include "hoilcd/core/util/parallel.h"

namespace hoilcd {
namespace {

TEST(CpuQuotaLimit, ReadsCgroupV2AndV1QuotasRoundedUpAndNothingWhenUnlimited) {
  EXPECT_EQ(CpuQuotaLimit("200000 100000\n"), 2);
  EXPECT_EQ(CpuQuotaLimit("150000 100000"), 2);  // 1.5 CPUs: two threads, the second half busy
  EXPECT_EQ(CpuQuotaLimit("50000 100000"), 1);
  EXPECT_EQ(CpuQuotaLimit("max 100000\n"), std::nullopt);
  EXPECT_EQ(CpuQuotaLimit("-1\n 100000\n"), std::nullopt);  // v1: no quota
  EXPECT_EQ(CpuQuotaLimit(""), std::nullopt);
  EXPECT_EQ(CpuQuotaLimit("lots 100000"), std::nullopt);
  EXPECT_EQ(CpuQuotaLimit("100000 0"), std::nullopt);
}

TEST(AvailableCpus, FollowsTheAffinityMaskAsTasksetSetsIt) {
  cpu_set_t saved;
  ASSERT_EQ(sched_getaffinity(0, sizeof saved, &saved), 0);
  int first = -1;
  for (int c = 0; c < CPU_SETSIZE && first < 0; ++c) {
    if (CPU_ISSET(c, &saved)) first = c;
  }
  ASSERT_GE(first, 0);
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(first, &one);
  ASSERT_EQ(sched_setaffinity(0, sizeof one, &one), 0);
  const int cpus = AvailableCpus();
  ASSERT_EQ(sched_setaffinity(0, sizeof saved, &saved), 0);
  EXPECT_EQ(cpus, 1);
  EXPECT_GE(AvailableCpus(), 1);
  EXPECT_LE(AvailableCpus(), CPU_COUNT(&saved));
}

TEST(ResolveThreadCount, ZeroMeansTheAvailableCpusAndAPositiveCountIsKept) {
  EXPECT_EQ(ResolveThreadCount(0), std::min(AvailableCpus(), kMaxThreads));
  EXPECT_EQ(ResolveThreadCount(3), 3);
  EXPECT_EQ(ResolveThreadCount(100000), kMaxThreads);
}

}  // namespace
}  // namespace hoilcd
