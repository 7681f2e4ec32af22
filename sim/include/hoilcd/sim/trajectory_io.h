// The dataset folder's trajectory files (SPEC.md "Dataset folder"): poses.csv (per frame: ground-
// truth base pose, camera pose and noisy wheel odometry) and poses_tum.txt (camera poses in TUM
// format). Writers return the file text so callers can write atomically; readers name file:line.
#pragma once

#include <string>
#include <vector>

#include "hoilcd/core/camera.h"
#include "hoilcd/sim/robot.h"

namespace hoilcd {

// The header line of poses.csv.
inline constexpr const char* kPosesCsvHeader =
    "frame,t,x,y,theta,cam_x,cam_y,cam_z,cam_yaw,cam_pitch,odo_x,odo_y,odo_theta";

// One row of poses.csv. Angles in radians; the camera's roll is not stored (reads back as 0):
// poses_tum.txt carries the full camera orientation.
struct PoseRecord {
  int frame = 0;
  double time_s = 0;  // s
  Pose2 base;         // ground truth, robot base (rear-axle midpoint)
  CameraPose camera;  // ground truth camera position and yaw/pitch (REP 103)
  Pose2 odometry;     // noisy wheel odometry
};

std::vector<PoseRecord> PoseRecordsFromRun(const RobotRun& run);
// poses.csv text: the header, then one row per record, numbers with 9 significant digits.
std::string FormatPosesCsv(const std::vector<PoseRecord>& records);
// Parses poses.csv text; throws InputError listing every problem as "file_name:LINE".
std::vector<PoseRecord> ParsePosesCsv(const std::string& text, const std::string& file_name);
std::vector<PoseRecord> ReadPosesCsv(const std::string& path);

// One line of poses_tum.txt: "t tx ty tz qx qy qz qw", the camera's world_from_cam pose with the
// camera frame of OpenCV (x right, y down, z forward) and the world frame of REP 103 (z up).
struct TumPose {
  double time_s = 0;  // s
  Rigid3 world_from_cam;
};

std::vector<TumPose> TumPosesFromRun(const RobotRun& run);
// poses_tum.txt text: a '#' comment line naming the frames and columns, then one line per pose,
// 9 significant digits, quaternion with qw >= 0.
std::string FormatTumPoses(const std::vector<TumPose>& poses);
// Parses TUM text ('#' lines and blank lines skipped; quaternions normalised); throws InputError
// listing every problem as "file_name:LINE".
std::vector<TumPose> ParseTumPoses(const std::string& text, const std::string& file_name);
std::vector<TumPose> ReadTumPoses(const std::string& path);

}  // namespace hoilcd
