// The round robin of sweep's and suite's shards over a sorted run list, which covers every run
// exactly once for any number of shards (the syntax: tests/core/util/shard_test.cpp).
#include "hoilcd/bench/pipeline/shard.h"

#include <vector>

#include <gtest/gtest.h>

namespace hoilcd {
namespace {

TEST(ShardOf, ShardsOfOneToFiveCoverEveryRunExactlyOnceInOrder) {
  std::vector<int> runs(11);
  for (int k = 0; k < 11; ++k) runs[static_cast<size_t>(k)] = k;
  for (int count = 1; count <= 5; ++count) {
    std::vector<int> seen(runs.size(), 0);
    for (int index = 0; index < count; ++index) {
      const std::vector<int> part = ShardOf(runs, Shard{index, count});
      for (size_t k = 0; k < part.size(); ++k) {
        EXPECT_EQ(part[k], index + static_cast<int>(k) * count) << index << "/" << count;
        ++seen[static_cast<size_t>(part[k])];
      }
    }
    for (size_t k = 0; k < runs.size(); ++k) EXPECT_EQ(seen[k], 1) << "run " << k << " with " << count << " shards";
  }
  EXPECT_EQ(ShardOf(std::vector<int>{}, Shard{2, 3}).size(), 0u);
}

}  // namespace
}  // namespace hoilcd
