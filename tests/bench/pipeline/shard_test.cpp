// Shards (`--shard I/N`): the syntax, refused by flag name when wrong, and the round robin over a
// sorted run list, which covers every run exactly once for any number of shards.
#include "hoilcd/bench/pipeline/shard.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "input_error_of.h"

namespace hoilcd {
namespace {

TEST(ShardSyntax, BadShardIsAnErrorNamingTheFlagAndWhatWasExpected) {
  const Shard ok = ParseShard("3/4");
  EXPECT_EQ(ok.index, 3);
  EXPECT_EQ(ok.count, 4);
  EXPECT_EQ(ok.Name(), "3/4");
  for (const std::string bad : {"4/4", "3/2", "1", "x", "a/2", "1/0", "-1/2", "1/2/3", "/2", "1/", ""}) {
    const std::string message = test::InputErrorOf([&] { ParseShard(bad); });
    EXPECT_NE(message.find("--shard"), std::string::npos) << bad << " gave: " << message;
    EXPECT_NE(message.find("'" + bad + "'"), std::string::npos) << bad << " gave: " << message;
  }
}

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
