#include "hoilcd/bench/export/mot_export.h"

#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>

#include "hoilcd/sim/output/sequence.h"
#include "test_dir.h"
#include "tiny_room.h"

namespace hoilcd {
namespace {

TEST(MotExport, GroundTruthRowsAreOneBasedAndUnscoredPeopleAreDistractorsNotToConsider) {
  FramePersons f;
  f.frame = 0;
  PersonRecord seen;
  seen.id = 0;
  seen.box_px = cv::Rect2f(10, 20, 30, 60);
  seen.visible_fraction = 0.9;
  PersonRecord hidden = seen;
  hidden.id = 4;
  hidden.visible_fraction = 0.1;
  f.persons = {seen, hidden};
  EXPECT_EQ(MotGroundTruth({f}, BenchOptions().tracking_metrics),
            "1,1,11.00,21.00,30.00,60.00,1,1,0.9000\n"
            "1,5,11.00,21.00,30.00,60.00,0,8,0.1000\n");
}

TEST(MotExport, TrackerRowsCarryTheTrackIdAndTheMotPlaceholders) {
  FrameTracks f;
  f.frame = 9;
  f.tracks.push_back({3, cv::Rect2f(0, 0, 5, 8), {}});
  EXPECT_EQ(MotTracks({f}), "10,3,1.00,1.00,5.00,8.00,1,-1,-1,-1\n");
}

TEST(MotExport, TwoDatasetsExportedIntoOneFolderKeepBothSequencesAndBothInTheSeqmap) {
  const test::TestDir temp;
  const Dataset a = test::TinyRoomDataset(temp / "a");
  const Dataset b = test::TinyRoomDataset(temp / "b", {"seed=2"});
  const MotExport ea = ExportMot(a, BenchOptions{}, temp / "mot");
  const MotExport eb = ExportMot(b, BenchOptions{}, temp / "mot");
  EXPECT_NE(ea.sequence, eb.sequence);
  EXPECT_NE(ea.sequence.find("-seed1-"), std::string::npos) << ea.sequence;
  EXPECT_NE(eb.sequence.find("-seed2-"), std::string::npos) << eb.sequence;
  EXPECT_TRUE(std::filesystem::exists(ea.ground_truth));
  EXPECT_TRUE(std::filesystem::exists(eb.ground_truth));
  const std::string seqmap = ReadFileBytes(temp / "mot/gt/mot_challenge/seqmaps/HOILCD-train.txt");
  EXPECT_EQ(seqmap, "name\n" + std::min(ea.sequence, eb.sequence) + "\n" + std::max(ea.sequence, eb.sequence) + "\n");
  ExportMot(a, BenchOptions{}, temp / "mot");  // again: listed once
  EXPECT_EQ(ReadFileBytes(temp / "mot/gt/mot_challenge/seqmaps/HOILCD-train.txt"), seqmap);
}

TEST(MotExport, ADatasetExportsTrackEvalsLayoutWithOneGroundTruthRowPerPersonRecord) {
  const test::TestDir temp;
  const Dataset dataset = test::TinyRoomDataset(temp / "dataset");
  const MotExport e = ExportMot(dataset, BenchOptions{}, temp / "mot");
  size_t records = 0;
  for (const FramePersons& f : dataset.persons()) records += f.persons.size();
  ASSERT_GT(records, 0u);
  const std::string gt = ReadFileBytes(e.ground_truth);
  EXPECT_EQ(static_cast<size_t>(std::count(gt.begin(), gt.end(), '\n')), records);
  EXPECT_EQ(e.ground_truth, temp / ("mot/gt/mot_challenge/HOILCD-train/" + e.sequence + "/gt/gt.txt"));
  EXPECT_EQ(ReadFileBytes(temp / "mot/gt/mot_challenge/seqmaps/HOILCD-train.txt"), "name\n" + e.sequence + "\n");
  const std::string info = ReadFileBytes(temp / ("mot/gt/mot_challenge/HOILCD-train/" + e.sequence + "/seqinfo.ini"));
  EXPECT_NE(info.find("seqLength=" + std::to_string(dataset.num_frames()) + "\n"), std::string::npos) << info;
  const std::string tracks = ReadFileBytes(e.tracks);
  EXPECT_FALSE(tracks.empty());
  std::istringstream lines(tracks);
  std::string line;
  while (std::getline(lines, line)) {
    const int frame = std::stoi(line.substr(0, line.find(',')));
    EXPECT_GE(frame, 1);
    EXPECT_LE(frame, dataset.num_frames());
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 9) << line;
  }
}

}  // namespace
}  // namespace hoilcd
