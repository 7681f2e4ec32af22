#include "hoilcd/bench/report/camera_output.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/scene/scene_options.h"
#include "hoilcd/sim/sensor/sensor.h"
#include "option_properties.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

// Renders the first `frames` of the paper room into `temp`/dataset; returns that folder.
std::string RenderInto(const test::TestDir& temp, const std::vector<std::string>& overrides, int frames) {
  SequenceOptions options;
  options.output_dir = temp / "dataset";
  options.frames = frames;
  RenderSequence(LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json", overrides), options);
  return options.output_dir;
}

TEST(CameraOutput, OptionsHoldTheirTablesDefaultsAndEveryBoundIsChecked) {
  ExpectConstructedHoldsTheTableDefaults<CameraOutputOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<CameraOutputOptions>(), 5);
  CameraOutputOptions options;
  options.patch_px = 65;
  EXPECT_EQ(options.Check(), "patch_px: must be in [1, 64] px (got 65)");
}

TEST(CameraOutput, VideoModeOffMeasuresThePreviewAndFreezesAndShading) {
  // FFC every second (frame 25), 0.12 s freeze (frames 25–27); strong shading.
  const std::vector<std::string> overrides = {"camera.ffc_interval_s=1", "camera.ffc_freeze_s=0.12",
                                              "camera.housing_warming_k_per_min=10", "camera.vignetting_k_per_k=1"};
  const test::TestDir temp;
  const std::string dir = RenderInto(temp, overrides, 30);
  const Dataset dataset = Dataset::Open(dir);
  const CameraOutputStats s = MeasureCameraOutput(dataset);
  EXPECT_FALSE(s.video_mode);
  EXPECT_EQ(s.video_problem, "");
  EXPECT_EQ(s.video_frames, 30);
  EXPECT_EQ(s.frames_compared, 30);
  EXPECT_EQ(s.frames_shading, 27);
  EXPECT_FALSE(s.thermal_is_video);  // the thermal PNGs are the uncompressed frames
  EXPECT_GT(s.psnr_mean_db, 30.0);
  EXPECT_LT(s.psnr_mean_db, 60.0);
  EXPECT_LE(s.psnr_min_db, s.psnr_mean_db);
  EXPECT_EQ(s.freeze_events, 3);
  EXPECT_EQ(s.frozen_frames, 3);
  // Configured: the housing warms 1/6 K/s after each FFC, times (1 + 0.2) K/K corner to centre.
  const BandRadianceTable table;
  const SensorModel model(
      SensorOptionsFromScene(LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json", overrides)),
      256, 192, 25.0, 1, &table);
  double configured = 0.0;  // frozen frames are left out of the measurement
  for (int f = 0; f < 30; ++f) {
    if (model.ShownFrame(f) == f) configured += model.ShadingCornerToCentreK(f);
  }
  configured /= 27.0;
  EXPECT_NEAR(s.shading_mean_k, configured, 0.25 * configured + 0.02);
  const InspectSection section = CameraOutputSection(s);
  EXPECT_EQ(section.key, "camera_output");
  ASSERT_NE(section.Find("frozen_frames"), nullptr);
  EXPECT_EQ(section.Find("frozen_frames")->value, 3);
  EXPECT_EQ(section.Find("video_readable")->value, 1);
  // hoilcd inspect (and so every bench report) carries the section.
  const InspectReport report = InspectDataset(dataset);
  ASSERT_NE(report.Find("camera_output"), nullptr);
  EXPECT_DOUBLE_EQ(report.Find("camera_output")->Find("psnr_mean_db")->value, s.psnr_mean_db);
  EXPECT_NE(report.ToText().find("lens shading"), std::string::npos);
}

TEST(CameraOutput, VideoModeOnReadsDecodedFramesAndABrokenVideoIsReportedNotThrown) {
  const test::TestDir temp;
  const std::string dir = RenderInto(temp, {"camera.video.enabled=true"}, 4);
  const CameraOutputStats s = MeasureCameraOutput(Dataset::Open(dir));
  EXPECT_TRUE(s.video_mode);
  EXPECT_TRUE(s.thermal_is_video);
  EXPECT_GT(s.psnr_mean_db, 30.0);
  EXPECT_LT(s.psnr_mean_db, 60.0);
  WriteFileAtomic(dir + "/thermal.mp4", "broken");
  const CameraOutputStats broken = MeasureCameraOutput(Dataset::Open(dir));
  EXPECT_NE(broken.video_problem.find("not a readable thermal video"), std::string::npos) << broken.video_problem;
  EXPECT_EQ(CameraOutputSection(broken).Find("video_readable")->value, 0);
  EXPECT_EQ(broken.frames_compared, 4);
  EXPECT_EQ(broken.video_frames, 0);
}

}  // namespace
}  // namespace hoilcd
