#include "hoilcd/core/util/cgroup.h"

#include <gtest/gtest.h>

namespace hoilcd {
namespace {

TEST(Cgroup, MembershipsOfV1AndV2LinesWithTheirControllersAndPaths) {
  const std::vector<CgroupMembership> m =
      ParseCgroupMemberships("12:cpu,cpuacct:/job\n3:memory:/job/step\nmalformed\n0::/user.slice/job\n");
  ASSERT_EQ(m.size(), 3u);
  EXPECT_FALSE(m[0].v2);
  EXPECT_TRUE(m[0].Has("cpu"));
  EXPECT_TRUE(m[0].Has("cpuacct"));
  EXPECT_FALSE(m[0].Has("cpuset"));
  EXPECT_EQ(m[0].path, "/job");
  EXPECT_TRUE(m[1].Has("memory"));
  EXPECT_EQ(m[1].path, "/job/step");
  EXPECT_TRUE(m[2].v2);
  EXPECT_TRUE(m[2].controllers.empty());
  EXPECT_EQ(m[2].path, "/user.slice/job");
}

TEST(Cgroup, ACgroupAndItsAncestorsNearestFirstUpToTheRoot) {
  EXPECT_EQ(CgroupAndAncestors("/a/b"), (std::vector<std::string>{"/a/b", "/a", ""}));
  EXPECT_EQ(CgroupAndAncestors("/"), (std::vector<std::string>{"/"}));
  EXPECT_EQ(CgroupAndAncestors(""), (std::vector<std::string>{""}));
}

TEST(Cgroup, AnUnreadableFileReadsAsEmpty) { EXPECT_EQ(ReadSmallFile("/nonexistent/hoilcd/cgroup"), ""); }

}  // namespace
}  // namespace hoilcd
