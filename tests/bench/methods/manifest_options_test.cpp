#include "hoilcd/bench/methods/manifest_options.h"

#include <gtest/gtest.h>

namespace hoilcd {
namespace {

TEST(WithManifest, DetectorWindowAndTrackerRateComeFromTheManifest) {
  DatasetManifest manifest;
  manifest.intrinsics.height = 120;
  manifest.window_min_c = 15;
  manifest.window_max_c = 45;
  manifest.frame_rate_hz = 10;
  BenchOptions asked;
  asked.detector.threshold_c = 27;
  asked.tracker.track_buffer_frames = 60;
  const BenchOptions used = WithManifest(asked, manifest);
  EXPECT_EQ(used.detector.u8_min_c, 15);
  EXPECT_EQ(used.detector.u8_max_c, 45);
  EXPECT_EQ(used.tracker.frame_rate_hz, 10);
  // What the user asked for stays.
  EXPECT_EQ(used.detector.threshold_c, 27);
  EXPECT_EQ(used.tracker.track_buffer_frames, 60);
  // A 10 Hz dataset keeps a lost track int(10 / 30 * 60) = 20 frames, not the 50 of 25 Hz.
  EXPECT_EQ(ByteTracker(used.tracker).max_time_lost_frames(), 20);
}

}  // namespace
}  // namespace hoilcd
