#include "hoilcd/sim/trajectory_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "hoilcd/core/error.h"

namespace hoilcd {
namespace {

RobotRun ShortRun() {
  TricycleOptions robot;
  robot.camera_yaw_deg = 10;
  robot.camera_roll_deg = 3;
  RouteOptions route;
  route.frames = 300;  // the first straight and the first corner
  return SimulateRobot(robot, route, {}, {}, 25.0, 3);
}

// The problems an InputError lists, one "where: message" per line ("" when parsing succeeds).
std::string ParseCsvError(const std::string& text) {
  try {
    ParsePosesCsv(text, "poses.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string ParseTumError(const std::string& text) {
  try {
    ParseTumPoses(text, "poses_tum.txt");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// "" when haystack contains needle, else a message showing both.
std::string MissingText(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos ? ""
                                                    : "'" + needle + "' not in '" + haystack + "'";
}

TEST(PosesCsv, StartsWithTheSpecHeaderAndHasOneRowPerFrame) {
  const RobotRun run = ShortRun();
  const std::string text = FormatPosesCsv(PoseRecordsFromRun(run));
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "frame,t,x,y,theta,cam_x,cam_y,cam_z,cam_yaw,cam_pitch,odo_x,odo_y,odo_theta");
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 301);
}

TEST(PosesCsv, RoundTripKeepsNineSignificantDigits) {
  const std::vector<PoseRecord> records = PoseRecordsFromRun(ShortRun());
  const std::vector<PoseRecord> back = ParsePosesCsv(FormatPosesCsv(records), "poses.csv");
  ASSERT_EQ(back.size(), records.size());
  auto near = [](double a, double b) {
    return std::abs(a - b) <= 1e-8 * std::max(1.0, std::abs(a));
  };
  for (size_t k = 0; k < records.size(); ++k) {
    const PoseRecord &a = records[k], &b = back[k];
    ASSERT_EQ(a.frame, b.frame);
    ASSERT_TRUE(near(a.time_s, b.time_s));
    ASSERT_TRUE(near(a.base.x_m, b.base.x_m));
    ASSERT_TRUE(near(a.base.y_m, b.base.y_m));
    ASSERT_TRUE(near(a.base.theta_rad, b.base.theta_rad));
    ASSERT_TRUE(near(a.camera.x_m, b.camera.x_m));
    ASSERT_TRUE(near(a.camera.y_m, b.camera.y_m));
    ASSERT_TRUE(near(a.camera.z_m, b.camera.z_m));
    ASSERT_TRUE(near(a.camera.yaw_rad, b.camera.yaw_rad));
    ASSERT_TRUE(near(a.camera.pitch_rad, b.camera.pitch_rad));
    ASSERT_TRUE(near(a.odometry.x_m, b.odometry.x_m));
    ASSERT_TRUE(near(a.odometry.y_m, b.odometry.y_m));
    ASSERT_TRUE(near(a.odometry.theta_rad, b.odometry.theta_rad));
    ASSERT_EQ(b.camera.roll_rad, 0.0);  // not stored in poses.csv
  }
  // Formatting what was read gives the same text again.
  EXPECT_EQ(FormatPosesCsv(back), FormatPosesCsv(records));
}

TEST(PosesCsv, FileRoundTripThroughReadPosesCsv) {
  const std::vector<PoseRecord> records = PoseRecordsFromRun(ShortRun());
  const std::string path = ::testing::TempDir() + "hoilcd_trajectory_io_poses.csv";
  {
    std::ofstream out(path, std::ios::binary);
    out << FormatPosesCsv(records);
  }
  const std::vector<PoseRecord> back = ReadPosesCsv(path);
  std::remove(path.c_str());
  ASSERT_EQ(back.size(), records.size());
  EXPECT_NEAR(back.back().base.x_m, records.back().base.x_m, 1e-8);
}

TEST(PosesCsv, ReaderErrorsNameFileAndLine) {
  const std::string header = std::string(kPosesCsvHeader) + "\n";
  const std::string good = "0,0,0.4,0.4,1.57,0.4,0.6,0.55,1.57,0.087,0.4,0.4,1.57\n";
  EXPECT_EQ(ParseCsvError(header + good), "");
  EXPECT_EQ(MissingText(ParseCsvError("frame,t,x\n" + good), "poses.csv:1: expected the header"),
            "");
  EXPECT_EQ(MissingText(ParseCsvError(""), "poses.csv:1: expected the header"), "");
  EXPECT_EQ(MissingText(ParseCsvError(header + good + "1,0.04,0.4\n"),
                        "poses.csv:3: expected 13 comma-separated values, found 3"),
            "");
  const std::string bad_y = "1,0.04,0.4,abc,1.57,0.4,0.6,0.55,1.57,0.087,0.4,0.4,1.57\n";
  EXPECT_EQ(MissingText(ParseCsvError(header + good + bad_y),
                        "poses.csv:3: column 'y': 'abc' is not a finite number"),
            "");
  const std::string nan_odo = "1,0.04,0.4,0.4,1.57,0.4,0.6,0.55,1.57,0.087,0.4,0.4,nan\n";
  EXPECT_EQ(MissingText(ParseCsvError(header + good + nan_odo),
                        "poses.csv:3: column 'odo_theta': 'nan' is not a finite number"),
            "");
  const std::string bad_frame = "-1" + good.substr(1);
  EXPECT_EQ(MissingText(ParseCsvError(header + bad_frame),
                        "poses.csv:2: column 'frame': '-1' is not a non-negative integer"),
            "");
  EXPECT_EQ(MissingText(ParseCsvError(header + good + good),
                        "poses.csv:3: frame 0 does not follow frame 0"),
            "");
  // Every problem is reported, not only the first.
  const std::string both = ParseCsvError(header + good + bad_y + "2,1\n");
  EXPECT_EQ(MissingText(both, "poses.csv:3:"), "");
  EXPECT_EQ(MissingText(both, "poses.csv:4:"), "");
}

TEST(PosesCsv, MissingFileIsNamed) {
  try {
    ReadPosesCsv("/nonexistent/poses.csv");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/poses.csv: cannot open file");
  }
}

TEST(TumPoses, RoundTripKeepsCameraPoses) {
  const RobotRun run = ShortRun();
  const std::vector<TumPose> poses = TumPosesFromRun(run);
  const std::string text = FormatTumPoses(poses);
  EXPECT_EQ(text[0], '#');
  const std::vector<TumPose> back = ParseTumPoses(text, "poses_tum.txt");
  ASSERT_EQ(back.size(), run.samples.size());
  for (size_t k = 0; k < back.size(); ++k) {
    const Rigid3 expected = run.samples[k].camera.WorldFromCam();
    ASSERT_NEAR(back[k].time_s, run.samples[k].time_s, 1e-9);
    ASSERT_LT((back[k].world_from_cam.translation - expected.translation).norm(), 1e-7);
    ASSERT_LT(back[k].world_from_cam.rotation.angularDistance(expected.rotation), 1e-7);
  }
}

TEST(TumPoses, PoseIsWorldFromCamInTheOpenCvCameraFrame) {
  const RobotRun run = ShortRun();
  const std::vector<TumPose> back =
      ParseTumPoses(FormatTumPoses(TumPosesFromRun(run)), "poses_tum.txt");
  const RobotSample& s = run.samples.front();
  // Camera +z (optical axis) maps to the world direction the camera looks at; +y (down) has a
  // negative world z component; the translation is the camera centre.
  const Eigen::Vector3d forward = back.front().world_from_cam.rotation * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(std::atan2(forward.y(), forward.x()), s.camera.yaw_rad, 1e-7);
  EXPECT_NEAR(-std::asin(forward.z()), s.camera.pitch_rad, 1e-7);
  EXPECT_LT((back.front().world_from_cam.rotation * Eigen::Vector3d::UnitY()).z(), 0.0);
  EXPECT_NEAR(back.front().world_from_cam.translation.z(), s.camera.z_m, 1e-9);
}

TEST(TumPoses, ReaderErrorsNameFileAndLine) {
  const std::string comment = "# t tx ty tz qx qy qz qw\n";
  const std::string good = "0 1 2 0.5 0 0 0 1\n";
  EXPECT_EQ(ParseTumError(comment + good + "\n"), "");
  EXPECT_EQ(MissingText(ParseTumError(comment + good + "0.04 1 2 0.5 0 0 1\n"),
                        "poses_tum.txt:3: expected 8 values 't tx ty tz qx qy qz qw', found 7"),
            "");
  EXPECT_EQ(MissingText(ParseTumError(comment + "0 1 x 0.5 0 0 0 1\n"),
                        "poses_tum.txt:2: column 'ty': 'x' is not a finite number"),
            "");
  EXPECT_EQ(MissingText(ParseTumError(comment + "0 1 2 0.5 0 0 0 2\n"),
                        "poses_tum.txt:2: quaternion is not unit length"),
            "");
  EXPECT_EQ(MissingText(ParseTumError(comment + good + good),
                        "poses_tum.txt:3: timestamps must increase"),
            "");
}

TEST(TumPoses, MissingFileIsNamed) {
  EXPECT_THROW(ReadTumPoses("/nonexistent/poses_tum.txt"), InputError);
}

}  // namespace
}  // namespace hoilcd
