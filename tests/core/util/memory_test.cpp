#include "hoilcd/core/util/memory.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "input_error_of.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

void Write(const std::string& path, const std::string& text) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path) << text;
}

constexpr char kMeminfo[] =
    "MemTotal:       16000000 kB\n"
    "MemFree:         1000000 kB\n"
    "MemAvailable:    8000000 kB\n";

TEST(MemAvailableBytes, ReadsTheKilobytesOfMeminfoAndNothingWithoutTheLine) {
  EXPECT_EQ(MemAvailableBytes(kMeminfo), 8000000.0 * 1024);
  EXPECT_EQ(MemAvailableBytes("MemTotal: 100 kB\n"), std::nullopt);
  EXPECT_EQ(MemAvailableBytes(""), std::nullopt);
  EXPECT_EQ(MemAvailableBytes("MemAvailable: lots kB\n"), std::nullopt);
}

TEST(CgroupMemoryRoom, IsTheLimitMinusTheUsageAndNothingWhenUnlimited) {
  EXPECT_EQ(CgroupMemoryRoom("1000000\n", "400000\n"), 600000.0);
  EXPECT_EQ(CgroupMemoryRoom("1000\n", "5000\n"), 0.0);  // over the limit: no room
  EXPECT_EQ(CgroupMemoryRoom("max\n", "400000\n"), std::nullopt);
  EXPECT_EQ(CgroupMemoryRoom("9223372036854771712\n", "400000\n"), std::nullopt);  // v1: no limit
  EXPECT_EQ(CgroupMemoryRoom("", ""), std::nullopt);
}

TEST(AllocatableBytes, IsMemAvailableWhenTheCgroupHasNoLimit) {
  test::TestDir dir;
  const MemoryFiles files{dir / "proc", dir / "cgroup"};
  Write(dir / "proc/meminfo", kMeminfo);
  Write(dir / "proc/self/cgroup", "0::/user.slice/job\n");
  Write(dir / "cgroup/user.slice/job/memory.max", "max\n");
  Write(dir / "cgroup/user.slice/job/memory.current", "5000\n");
  EXPECT_EQ(AllocatableBytes(files), 8000000.0 * 1024);
}

TEST(AllocatableBytes, IsTheTightestRoomOfTheCgroupV2AndItsAncestors) {
  test::TestDir dir;
  const MemoryFiles files{dir / "proc", dir / "cgroup"};
  Write(dir / "proc/meminfo", kMeminfo);
  Write(dir / "proc/self/cgroup", "0::/slice/job\n");
  Write(dir / "cgroup/slice/job/memory.max", "max\n");
  Write(dir / "cgroup/slice/memory.max", "2000000000\n");
  Write(dir / "cgroup/slice/memory.current", "500000000\n");
  EXPECT_EQ(AllocatableBytes(files), 1500000000.0);
}

TEST(AllocatableBytes, ReadsTheCgroupV1MemoryController) {
  test::TestDir dir;
  const MemoryFiles files{dir / "proc", dir / "cgroup"};
  Write(dir / "proc/meminfo", kMeminfo);
  Write(dir / "proc/self/cgroup", "4:cpu,cpuacct:/job\n3:memory:/job\n");
  Write(dir / "cgroup/memory/job/memory.limit_in_bytes", "300000000\n");
  Write(dir / "cgroup/memory/job/memory.usage_in_bytes", "100000000\n");
  EXPECT_EQ(AllocatableBytes(files), 200000000.0);
}

TEST(AllocatableBytes, IsNothingWhenNoFigureCanBeRead) {
  test::TestDir dir;
  EXPECT_EQ(AllocatableBytes({dir / "proc", dir / "cgroup"}), std::nullopt);
  EXPECT_NO_THROW(CheckAllocation(1e30, "--size", "a table", {dir / "proc", dir / "cgroup"}));
}

TEST(CheckAllocation, RefusesARequestBeyondTheAvailableMemoryNamingItAndTheSizes) {
  test::TestDir dir;
  const MemoryFiles files{dir / "proc", dir / "cgroup"};
  Write(dir / "proc/meminfo", "MemAvailable: 1000000 kB\n");
  const std::string message =
      test::InputErrorOf([&] { CheckAllocation(40e9, "--param thumbnails.width_px", "the thumbnails", files); });
  EXPECT_NE(message.find("--param thumbnails.width_px: the thumbnails needs 40.0 GB"), std::string::npos) << message;
  EXPECT_NE(message.find("may allocate 1.0 GB"), std::string::npos) << message;
  EXPECT_NO_THROW(CheckAllocation(1e6, "--param thumbnails.width_px", "the thumbnails", files));
}

TEST(CheckAllocation, RefusesAnExabyteOnThisMachine) {
  EXPECT_NE(
      test::InputErrorOf([] { CheckAllocation(1e18, "--frames", "the frames"); }).find("--frames: the frames needs"),
      std::string::npos);
}

TEST(FormatBytes, UsesDecimalUnitsWithOneDecimalBelowAHundred) {
  EXPECT_EQ(FormatBytes(512), "512 bytes");
  EXPECT_EQ(FormatBytes(40e9), "40.0 GB");
  EXPECT_EQ(FormatBytes(250e6), "250 MB");
}

}  // namespace
}  // namespace hoilcd
