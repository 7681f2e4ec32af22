#include "hoilcd/bench/methods/front_end_input.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/scene/scene_options.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 8;

// The first kFrames of the paper room (people at the long table in view), video mode on or off.
std::string RenderInto(const test::TestDir& temp, const std::string& name, bool video_mode) {
  SequenceOptions options;
  options.output_dir = temp / name;
  options.frames = kFrames;
  const std::string video = std::string("camera.video.enabled=") + (video_mode ? "true" : "false");
  RenderSequence(LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json", {video}), options);
  return options.output_dir;
}

// A copy of `dir` whose thermal PNGs (the decoded video frames in video mode) are all black; the
// radiometric PNGs and EXRs are untouched and the manifest's checksums are kept consistent.
std::string WithBlackThermalFrames(const std::string& dir, const std::string& copy) {
  fs::copy(dir, copy, fs::copy_options::recursive);
  DatasetManifest manifest = Dataset::Open(copy).manifest();
  const cv::Mat black = cv::Mat::zeros(manifest.intrinsics.height, manifest.intrinsics.width, CV_8U);
  for (int f = 0; f < kFrames; ++f) {
    WriteDatasetFile(copy, "thermal/" + FrameFileName(f, "png"), EncodePng(black), &manifest);
  }
  WriteFileAtomic(copy + "/manifest.json", manifest.ToJson());
  return copy;
}

// HOI points DLCD's front end found, summed over every frame.
int DlcdHoiPoints(const Dataset& dataset) {
  BenchOptions options;
  options.methods = {"dlcd"};
  options.threads = 1;
  const BenchResult result = RunBench(dataset, options);
  int points = 0;
  for (const FrameFeatures& f : result.features) points += static_cast<int>(f.hoi.size());
  return points;
}

TEST(FrontEndInput, VideoModeHandsTheDetectorTheDecodedFramesAndNoRadiometricImage) {
  const test::TestDir temp;
  const Dataset on = Dataset::Open(RenderInto(temp, "on", true));
  const Dataset off = Dataset::Open(RenderInto(temp, "off", false));
  ASSERT_TRUE(IsVideoMode(on));
  ASSERT_FALSE(IsVideoMode(off));
  const FrontEndInput video = ReadFrontEndInput(on, 3, true, true);
  EXPECT_TRUE(video.radiometric_c.empty());
  EXPECT_EQ(cv::norm(video.thermal_u8, on.Thermal(3), cv::NORM_INF), 0.0);
  const FrontEndInput radiometric = ReadFrontEndInput(off, 3, false, true);
  ASSERT_FALSE(radiometric.radiometric_c.empty());
  EXPECT_EQ(cv::norm(radiometric.radiometric_c, off.RadiometricC(3), cv::NORM_INF), 0.0);
  EXPECT_TRUE(ReadFrontEndInput(off, 3, false, false).radiometric_c.empty());  // no detector, no read
}

TEST(FrontEndInput, InVideoModeDifferentDecodedFramesChangeDlcdAndWithoutItTheyDoNot) {
  const test::TestDir temp;
  const std::string on = RenderInto(temp, "on", true);
  const std::string off = RenderInto(temp, "off", false);
  const int on_points = DlcdHoiPoints(Dataset::Open(on));
  const int off_points = DlcdHoiPoints(Dataset::Open(off));
  ASSERT_GT(on_points, 0);
  ASSERT_GT(off_points, 0);
  // Video mode: the detector sees only the decoded frames, so black ones leave it nobody.
  EXPECT_EQ(DlcdHoiPoints(Dataset::Open(WithBlackThermalFrames(on, temp / "on_black"))), 0);
  // Video mode off: it reads the radiometric image, which the black thermal PNGs did not change.
  EXPECT_EQ(DlcdHoiPoints(Dataset::Open(WithBlackThermalFrames(off, temp / "off_black"))), off_points);
}

}  // namespace
}  // namespace hoilcd
