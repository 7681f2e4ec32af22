// Shards (`--shard I/N` of render, sweep and suite): the syntax, refused by flag name when wrong,
// and the contiguous parts a render splits its frames into, which tile the frames in order.
#include "hoilcd/core/util/shard.h"

#include <string>

#include <gtest/gtest.h>

#include "input_error_of.h"

namespace hoilcd {
namespace {

TEST(ShardSyntax, BadShardIsAnErrorNamingTheFlagAndWhatWasExpected) {
  const Shard ok = ParseShard("3/4");
  EXPECT_EQ(ok.index, 3);
  EXPECT_EQ(ok.count, 4);
  EXPECT_EQ(ok.Name(), "3/4");
  for (const std::string bad :
       {"0/0", "4/4", "3/2", "1", "x", "a/2", "1/0", "-1/2", "1/2/3", "/2", "1/", "", "9999999999/2"}) {
    const std::string message = test::InputErrorOf([&] { ParseShard(bad); });
    EXPECT_NE(message.find("--shard"), std::string::npos) << bad << " gave: " << message;
    EXPECT_NE(message.find("'" + bad + "'"), std::string::npos) << bad << " gave: " << message;
  }
}

TEST(ContiguousPart, PartsTileTheItemsInOrderAndDifferInSizeByAtMostOne) {
  for (int total : {0, 1, 2, 7, 10, 1996}) {
    for (int count = 1; count <= 6; ++count) {
      int next = 0;
      for (int index = 0; index < count; ++index) {
        const IndexRange part = ContiguousPart(Shard{index, count}, total);
        EXPECT_EQ(part.begin, next) << index << "/" << count << " of " << total;
        EXPECT_GE(part.end - part.begin, total / count);
        EXPECT_LE(part.end - part.begin, total / count + 1);
        next = part.end;
      }
      EXPECT_EQ(next, total) << count << " shards of " << total;
    }
  }
  EXPECT_EQ(ContiguousPart(Shard{1, 3}, 10), (IndexRange{3, 6}));
}

}  // namespace
}  // namespace hoilcd
