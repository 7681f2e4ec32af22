#include "hoilcd/bench/export/mcap_export.h"

#include <cmath>
#include <filesystem>
#include <map>

#include <gtest/gtest.h>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/file_io.h"
#include "input_error_of.h"
#include "recording_runs.h"
#include "test_dir.h"
#include "tiny_room.h"

namespace hoilcd {
namespace {

constexpr int kFrames = 8;

std::map<std::string, uint64_t> Counts(const McapExportResult& r) { return {r.topics.begin(), r.topics.end()}; }

TEST(McapExport, EveryTopicHasAMessagePerFrameAndTfStaticOne) {
  const test::TestDir temp;
  const std::string dataset = test::RenderTinyRoom(temp / "dataset", {"frames=" + std::to_string(kFrames)});
  const McapExportResult r = ExportMcap(dataset, temp / "bag.mcap");
  const std::map<std::string, uint64_t> counts = Counts(r);
  EXPECT_EQ(counts.at("/tf_static"), 1u);
  for (const char* topic :
       {"/thermal/camera_info", "/thermal/image_raw", "/thermal/image_mono8", "/thermal/depth", "/thermal/instance",
        "/odom", "/tf", "/ground_truth/pose", "/ground_truth/camera_pose", "/persons"}) {
    EXPECT_EQ(counts.at(topic), static_cast<uint64_t>(kFrames)) << topic;
  }
  EXPECT_EQ(r.messages, 1u + 10u * kFrames);
  EXPECT_EQ(r.bytes, std::filesystem::file_size(temp / "bag.mcap"));
  EXPECT_EQ(ReadFileBytes(temp / "bag.mcap").substr(0, 8), std::string("\x89MCAP0\r\n", 8));
}

TEST(McapExport, ASecondExportIsByteIdenticalAtAnyThreadCountAndCompression) {
  const test::TestDir temp;
  const std::string dataset = test::RenderTinyRoom(temp / "dataset", {"frames=" + std::to_string(kFrames)});
  McapExportOptions one, two;
  one.threads = 1;
  two.threads = 2;
  ExportMcap(dataset, temp / "a.mcap", one);
  ExportMcap(dataset, temp / "b.mcap", two);
  const std::string a = ReadFileBytes(temp / "a.mcap");
  EXPECT_EQ(a, ReadFileBytes(temp / "b.mcap"));
  ExportMcap(dataset, temp / "a.mcap", one);  // over the first: replaced, the same bytes
  EXPECT_EQ(a, ReadFileBytes(temp / "a.mcap"));
  McapExportOptions none;
  none.compression = McapCompression::kNone;
  ExportMcap(dataset, temp / "n1.mcap", none);
  ExportMcap(dataset, temp / "n2.mcap", none);
  EXPECT_EQ(ReadFileBytes(temp / "n1.mcap"), ReadFileBytes(temp / "n2.mcap"));
  EXPECT_GT(std::filesystem::file_size(temp / "n1.mcap"), a.size());
}

TEST(McapExport, OutputsTheDatasetLacksHaveNoTopic) {
  const test::TestDir temp;
  const std::string dir = temp / "dataset";
  SequenceOptions options;
  options.output_dir = dir;
  options.frames = 3;
  options.outputs = "thermal";
  RenderSequence(LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/tiny_room.json", {}), options);
  const std::map<std::string, uint64_t> counts = Counts(ExportMcap(dir, temp / "bag.mcap"));
  EXPECT_EQ(counts.count("/thermal/image_raw") + counts.count("/thermal/depth") + counts.count("/persons"), 0u);
  EXPECT_EQ(counts.at("/thermal/image_mono8"), 3u);
  EXPECT_EQ(counts.at("/odom"), 3u);
}

TEST(McapExport, RecordingRunsAreOneBagWithTheDatasetsGapBetweenThem) {
  const test::TestDir temp;
  const Dataset runs = test::TinyRoomTwoRuns(temp.str(), 4);
  const McapExportResult r = ExportMcap(runs.dir(), temp / "runs.mcap");
  EXPECT_EQ(Counts(r).at("/odom"), 8u);
  EXPECT_EQ(r.start_time_ns, static_cast<uint64_t>(std::llround(runs.poses().front().time_s * 1e9)));
  EXPECT_EQ(r.end_time_ns, static_cast<uint64_t>(std::llround(runs.poses().back().time_s * 1e9)));
  EXPECT_GT(r.end_time_ns - r.start_time_ns, static_cast<uint64_t>(5.5 * 3600 * 1e9));
}

TEST(McapExport, AMissingDatasetIsAnErrorNamingTheFolderAndWritesNothing) {
  const test::TestDir temp;
  const std::string message = test::InputErrorOf([&] { ExportMcap(temp / "nowhere", temp / "bag.mcap"); });
  EXPECT_NE(message.find(temp / "nowhere"), std::string::npos) << message;
  EXPECT_FALSE(std::filesystem::exists(temp / "bag.mcap"));
}

TEST(McapExport, ADamagedFrameIsAnErrorNamingItsFileAndLeavesTheOldBag) {
  const test::TestDir temp;
  const std::string dataset = test::RenderTinyRoom(temp / "dataset", {"frames=" + std::to_string(kFrames)});
  WriteFileAtomic(temp / "bag.mcap", "an earlier bag");
  std::string png = ReadFileBytes(dataset + "/radiometric/000005.png");
  png[png.size() / 2] ^= 0x40;
  WriteFileAtomic(dataset + "/radiometric/000005.png", png);
  const std::string message = test::InputErrorOf([&] { ExportMcap(dataset, temp / "bag.mcap"); });
  EXPECT_NE(message.find("radiometric/000005.png"), std::string::npos) << message;
  EXPECT_EQ(ReadFileBytes(temp / "bag.mcap"), "an earlier bag");
  for (const auto& entry : std::filesystem::directory_iterator(temp.str())) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp."), std::string::npos) << entry.path();
  }
}

TEST(McapExport, AFolderAsTheOutputIsAnErrorNamingIt) {
  const test::TestDir temp;
  std::filesystem::create_directories(temp / "out");
  const std::string message = test::InputErrorOf([&] { ExportMcap(temp / "nowhere", temp / "out"); });
  EXPECT_NE(message.find("is a folder"), std::string::npos) << message;
}

}  // namespace
}  // namespace hoilcd
