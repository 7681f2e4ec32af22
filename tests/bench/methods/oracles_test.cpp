// The oracle front ends and methods (dlcd-oracle, slcd-ideal): what they read of the ground truth,
// that they equal their models where the ground truth is what the camera saw, and what happens on
// a dataset without the ground truth they need.
#include <algorithm>

#include <gtest/gtest.h>

#include "hoilcd/bench/methods/front_end_input.h"
#include "hoilcd/bench/methods/front_ends.h"
#include "hoilcd/bench/methods/method_params.h"
#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/bench/report/report.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "input_error_of.h"
#include "test_dir.h"
#include "tiny_room.h"

namespace hoilcd {
namespace {

// Every effect of the camera's own switched off: what it outputs is the true temperature.
const std::vector<std::string> kIdealSensor = {"camera.optics_blur=false",   "camera.temporal_noise=false",
                                               "camera.fixed_pattern=false", "camera.drift=false",
                                               "camera.lens_shading=false",  "camera.ffc_freeze=false",
                                               "camera.time_constant=false", "camera.quantisation=false"};

// The person pixels of frame f, from the EXR's class channel, computed here without the bench.
cv::Mat PersonMaskOf(const Dataset& dataset, int f) {
  const int person = dataset.manifest().classes.at("person");
  for (const auto& [name, channel] : ReadDatasetExr(dataset, f)) {
    if (name != "class") continue;
    cv::Mat mask(channel.size(), CV_8U, cv::Scalar(0));
    for (int y = 0; y < channel.rows; ++y)
      for (int x = 0; x < channel.cols; ++x) mask.at<uint8_t>(y, x) = channel.at<float>(y, x) == person ? 1 : 0;
    return mask;
  }
  ADD_FAILURE() << "no class channel";
  return {};
}

TEST(Oracles, TruePersonHoiPointsAreTheHoiExtractionOfTheGroundTruthPeople) {
  const test::TestDir temp;
  const Dataset dataset = test::TinyRoomDataset(temp / "ds", {"frames=60"});
  FrontEndOptions options;
  options.threads = 2;
  const FrontEndOutput out = RunFrontEnds(dataset, {FrontEnd::kTruePersons}, options);
  ASSERT_EQ(out.true_hoi.size(), 60u);
  int points = 0;
  for (int f = 0; f < 60; ++f) {
    std::vector<Track> people;
    for (const PersonRecord& p : dataset.persons()[f].persons) {
      if (p.visible_fraction > 0) people.push_back(Track{p.id, p.box_px, 1.0f});
    }
    const std::vector<HoiFeature> expected = ExtractHoiFeatures(PersonMaskOf(dataset, f), people, options.hoi);
    ASSERT_EQ(out.true_hoi[f].size(), expected.size()) << "frame " << f;
    for (size_t i = 0; i < expected.size(); ++i) {
      EXPECT_EQ(out.true_hoi[f][i].point, expected[i].point) << "frame " << f;
      EXPECT_EQ(out.true_hoi[f][i].track_id, expected[i].track_id) << "frame " << f;
    }
    points += static_cast<int>(expected.size());
  }
  EXPECT_GT(points, 100);        // the table's people are in view: the comparison is not of empty sets
  EXPECT_TRUE(out.hoi.empty());  // no detector, no tracker
}

TEST(Oracles, IdealImageIsTheTrueTemperatureInTheThermalWindow) {
  const test::TestDir temp;
  const Dataset ideal = test::TinyRoomDataset(temp / "ideal", [] {
    std::vector<std::string> o = kIdealSensor;
    o.push_back("frames=20");
    return o;
  }());
  const Dataset real = test::TinyRoomDataset(temp / "real", {"frames=20"});
  int differing_real = 0;
  for (int f = 0; f < 20; ++f) {
    // With the camera's effects off, its PNG is the true temperature in the same window.
    EXPECT_EQ(cv::norm(ReadGroundTruthInput(ideal, f, true, false).ideal_u8, ideal.Thermal(f), cv::NORM_INF), 0)
        << "frame " << f;
    differing_real += cv::countNonZero(ReadGroundTruthInput(real, f, true, false).ideal_u8 != real.Thermal(f));
  }
  EXPECT_GT(differing_real, 1000);  // with the sensor on, the oracle does not read the camera's image
}

TEST(Oracles, SlcdIdealScoresAsSlcdWhereTheSensorIsIdeal) {
  const test::TestDir temp;
  const Dataset dataset = test::TinyRoomDataset(temp / "ds", kIdealSensor);
  BenchOptions options;
  options.methods = {"slcd", "slcd-ideal"};
  options.threads = 2;
  const BenchResult result = RunBench(dataset, options);
  ASSERT_EQ(result.runs.size(), 2u);
  EXPECT_GT(result.runs[0].metrics.mrr, 0.0);
  EXPECT_EQ(result.runs[1].scores, result.runs[0].scores);
  EXPECT_EQ(result.runs[1].metrics.mrr, result.runs[0].metrics.mrr);
}

TEST(Oracles, NamedOracleOnADatasetWithoutItsGroundTruthIsAnInputErrorNamingOutputAndMethod) {
  const test::TestDir temp;
  // Rendered without EXRs and people: a user's --outputs thermal,radiometric.
  SequenceOptions render;
  render.output_dir = temp / "thermal_only";
  render.outputs = "thermal,radiometric";
  render.frames = 40;
  RenderSequence(LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/tiny_room.json"), render);
  const Dataset bare = Dataset::Open(render.output_dir);
  for (const std::string method : {"dlcd-oracle", "slcd-ideal"}) {
    BenchOptions options;
    options.methods = {"slcd", method};
    const std::string error = test::InputErrorOf([&] { RunBench(bare, options); });
    EXPECT_NE(error.find("has no exr output"), std::string::npos) << error;
    EXPECT_NE(error.find("method " + method), std::string::npos) << error;
  }
}

TEST(Oracles, AllOnADatasetWithoutGroundTruthLeavesTheOraclesOutWithANoteInTheReport) {
  const test::TestDir temp;
  SequenceOptions render;
  render.output_dir = temp / "thermal_only";
  render.outputs = "thermal,radiometric";
  render.frames = 40;
  RenderSequence(LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/tiny_room.json"), render);
  const Dataset bare = Dataset::Open(render.output_dir);
  BenchOptions options;
  options.methods = ParseMethodList("all", &options.optional_methods);
  options.threads = 2;
  ReportTiming timing;
  const BenchResult result = BenchAndWriteReport(bare, options, &timing, temp / "report");
  EXPECT_NE(ReadFileBytes(temp / "report/report.md").find("- dlcd-oracle: not run, the dataset has no exr output"),
            std::string::npos);
  EXPECT_EQ(result.Find("dlcd-oracle"), nullptr);
  EXPECT_EQ(result.Find("slcd-ideal"), nullptr);
  EXPECT_NE(result.Find("dlcd"), nullptr);
  ASSERT_EQ(result.skipped.size(), 2u);
  EXPECT_NE(result.skipped[0].find("dlcd-oracle: not run, the dataset has no exr output"), std::string::npos)
      << result.skipped[0];
}

TEST(Oracles, AreInAllButNotInPaperAndOnlyNamedMethodsAreRequired) {
  std::vector<std::string> from_groups;
  const std::vector<std::string> all = ParseMethodList("slcd,all", &from_groups);
  for (const char* oracle : {"dlcd-oracle", "slcd-ideal"}) {
    EXPECT_NE(std::find(all.begin(), all.end(), oracle), all.end()) << oracle;
    EXPECT_NE(std::find(from_groups.begin(), from_groups.end(), oracle), from_groups.end()) << oracle;
    EXPECT_FALSE(FindMethod(oracle).FromPaper()) << oracle;
  }
  EXPECT_EQ(std::find(from_groups.begin(), from_groups.end(), "slcd"), from_groups.end());  // named
  const std::vector<std::string> paper = ParseMethodList("paper");
  EXPECT_EQ(std::find(paper.begin(), paper.end(), "dlcd-oracle"), paper.end());
}

TEST(Oracles, IdealKeypointsTakeTheKeypointParamsAndTruePersonsNoDetectorParams) {
  EXPECT_NO_THROW(CheckParams({"keypoints.max_keypoints=500"}, {"slcd-ideal"}));
  BenchOptions options;
  options.params = {"keypoints.max_keypoints=500"};
  EXPECT_EQ(WithFrontEndParams(options, FrontEnd::kIdealKeypoints).keypoints.max_keypoints, 500);
  const std::string error = test::InputErrorOf([] { CheckParams({"persons.threshold_c=27"}, {"dlcd-oracle"}); });
  EXPECT_NE(error.find("front end persons is used by none of the methods run"), std::string::npos) << error;
}

}  // namespace
}  // namespace hoilcd
