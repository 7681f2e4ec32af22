// The ROS 2 messages of hoilcd's bags (Humble's definitions): their CDR encoding (cdr_writer.h) and
// their schemas as rosbag2 stores them, encoding "ros2msg": the type's .msg text, then each type it
// uses, once, after a line of 80 '=' and a line "MSG: pkg/Type".
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace hoilcd {

struct Ros2Time {
  int32_t sec = 0;       // s
  uint32_t nanosec = 0;  // ns, < 1e9
  static Ros2Time FromNanoseconds(uint64_t ns);
};

struct Ros2Header {
  Ros2Time stamp;
  std::string frame_id;
};

struct Ros2Pose {                                 // geometry_msgs/Pose
  std::array<double, 3> position{};               // m
  std::array<double, 4> orientation{0, 0, 0, 1};  // quaternion x, y, z, w
};

// "sensor_msgs/msg/Image" for "sensor_msgs/Image": the name of an MCAP schema in the ros2 profile.
std::string Ros2SchemaName(const std::string& type);
// The ros2msg schema text of a type ("sensor_msgs/Image") with every type it uses; HOILCD_CHECK
// for a type not listed here.
std::string Ros2MessageDefinition(const std::string& type);

// sensor_msgs/Image; data holds height rows of step bytes.
std::string SerializeImage(const Ros2Header& header, uint32_t height, uint32_t width, const std::string& encoding,
                           uint32_t step, const void* data, size_t bytes);

// sensor_msgs/CameraInfo of a pinhole camera: distortion model "plumb_bob" with the given d, K from
// (fx, fy, cx, cy), R the identity, P = [K | 0], no binning, the full image as ROI.
struct PinholeCamera {
  uint32_t width = 0, height = 0;         // px
  double fx = 0, fy = 0, cx = 0, cy = 0;  // px
  std::array<double, 5> d{};              // plumb_bob k1, k2, t1, t2, k3
};
std::string SerializeCameraInfo(const Ros2Header& header, const PinholeCamera& camera);

// nav_msgs/Odometry; covariances row-major 6x6 over (x, y, z, rot x, rot y, rot z).
struct Ros2Odometry {
  std::string child_frame_id;
  Ros2Pose pose;
  std::array<double, 36> pose_covariance{};
  std::array<double, 3> linear{};   // m/s, in child_frame_id
  std::array<double, 3> angular{};  // rad/s, in child_frame_id
  std::array<double, 36> twist_covariance{};
};
std::string SerializeOdometry(const Ros2Header& header, const Ros2Odometry& odometry);

// geometry_msgs/TransformStamped: child_frame_id's pose in header.frame_id.
struct Ros2Transform {
  Ros2Header header;
  std::string child_frame_id;
  Ros2Pose transform;
};
// tf2_msgs/TFMessage
std::string SerializeTfMessage(const std::vector<Ros2Transform>& transforms);

// geometry_msgs/PoseStamped
std::string SerializePoseStamped(const Ros2Header& header, const Ros2Pose& pose);

// One vision_msgs/Detection2D: one hypothesis (class_id, score) with an identity pose and zero
// covariance, an axis-aligned box (theta 0), its id.
struct Ros2Detection {
  std::string id;
  std::string class_id;
  double score = 0;
  double center_x = 0, center_y = 0;  // px
  double size_x = 0, size_y = 0;      // px
};
// vision_msgs/Detection2DArray; each detection carries the array's header.
std::string SerializeDetection2DArray(const Ros2Header& header, const std::vector<Ros2Detection>& detections);

}  // namespace hoilcd
