#include "hoilcd/bench/export/ros2_messages.h"

#include <map>
#include <set>
#include <sstream>

#include "hoilcd/bench/export/cdr_writer.h"
#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

// Each type's fields as in ROS 2 Humble's .msg files (comments and default values left out), types
// of other messages written in full (pkg/Type).
const std::map<std::string, std::string>& Definitions() {
  static const std::map<std::string, std::string> kDefinitions = {
      {"builtin_interfaces/Time", "int32 sec\nuint32 nanosec\n"},
      {"std_msgs/Header", "builtin_interfaces/Time stamp\nstring frame_id\n"},
      {"sensor_msgs/Image",
       "std_msgs/Header header\nuint32 height\nuint32 width\nstring encoding\nuint8 is_bigendian\nuint32 step\n"
       "uint8[] data\n"},
      {"sensor_msgs/RegionOfInterest",
       "uint32 x_offset\nuint32 y_offset\nuint32 height\nuint32 width\nbool do_rectify\n"},
      {"sensor_msgs/CameraInfo",
       "std_msgs/Header header\nuint32 height\nuint32 width\nstring distortion_model\nfloat64[] d\nfloat64[9] k\n"
       "float64[9] r\nfloat64[12] p\nuint32 binning_x\nuint32 binning_y\nsensor_msgs/RegionOfInterest roi\n"},
      {"geometry_msgs/Point", "float64 x\nfloat64 y\nfloat64 z\n"},
      {"geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n"},
      {"geometry_msgs/Quaternion", "float64 x\nfloat64 y\nfloat64 z\nfloat64 w\n"},
      {"geometry_msgs/Pose", "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n"},
      {"geometry_msgs/PoseWithCovariance", "geometry_msgs/Pose pose\nfloat64[36] covariance\n"},
      {"geometry_msgs/Twist", "geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n"},
      {"geometry_msgs/TwistWithCovariance", "geometry_msgs/Twist twist\nfloat64[36] covariance\n"},
      {"geometry_msgs/PoseStamped", "std_msgs/Header header\ngeometry_msgs/Pose pose\n"},
      {"geometry_msgs/Transform", "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n"},
      {"geometry_msgs/TransformStamped",
       "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n"},
      {"nav_msgs/Odometry",
       "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n"
       "geometry_msgs/TwistWithCovariance twist\n"},
      {"tf2_msgs/TFMessage", "geometry_msgs/TransformStamped[] transforms\n"},
      {"vision_msgs/Point2D", "float64 x\nfloat64 y\n"},
      {"vision_msgs/Pose2D", "vision_msgs/Point2D position\nfloat64 theta\n"},
      {"vision_msgs/BoundingBox2D", "vision_msgs/Pose2D center\nfloat64 size_x\nfloat64 size_y\n"},
      {"vision_msgs/ObjectHypothesis", "string class_id\nfloat64 score\n"},
      {"vision_msgs/ObjectHypothesisWithPose",
       "vision_msgs/ObjectHypothesis hypothesis\ngeometry_msgs/PoseWithCovariance pose\n"},
      {"vision_msgs/Detection2D",
       "std_msgs/Header header\nvision_msgs/ObjectHypothesisWithPose[] results\nvision_msgs/BoundingBox2D bbox\n"
       "string id\n"},
      {"vision_msgs/Detection2DArray", "std_msgs/Header header\nvision_msgs/Detection2D[] detections\n"},
  };
  return kDefinitions;
}

const std::string& DefinitionOf(const std::string& type) {
  const auto it = Definitions().find(type);
  HOILCD_CHECK_MSG(it != Definitions().end(), "no ROS 2 definition of " << type);
  return it->second;
}

// The message types a definition's fields name (pkg/Type, array suffixes dropped), in field order.
std::vector<std::string> UsedTypes(const std::string& definition) {
  std::vector<std::string> types;
  std::istringstream lines(definition);
  for (std::string line; std::getline(lines, line);) {
    std::string type = line.substr(0, line.find(' '));
    if (type.find('/') == std::string::npos) continue;
    types.push_back(type.substr(0, type.find('[')));
  }
  return types;
}

// Depth first, each type once, in the order its fields first name it.
void AddDependencies(const std::string& type, std::set<std::string>* seen, std::vector<std::string>* order) {
  for (const std::string& used : UsedTypes(DefinitionOf(type))) {
    if (!seen->insert(used).second) continue;
    order->push_back(used);
    AddDependencies(used, seen, order);
  }
}

void Time(CdrWriter* w, const Ros2Time& t) {
  w->Int32(t.sec);
  w->Uint32(t.nanosec);
}

void Header(CdrWriter* w, const Ros2Header& h) {
  Time(w, h.stamp);
  w->String(h.frame_id);
}

void Pose(CdrWriter* w, const Ros2Pose& p) {
  w->Float64Array(p.position.data(), 3);
  w->Float64Array(p.orientation.data(), 4);
}

}  // namespace

Ros2Time Ros2Time::FromNanoseconds(uint64_t ns) {
  HOILCD_CHECK_MSG(ns / 1000000000u <= static_cast<uint64_t>(INT32_MAX), "time beyond ROS 2's int32 seconds");
  return {static_cast<int32_t>(ns / 1000000000u), static_cast<uint32_t>(ns % 1000000000u)};
}

std::string Ros2SchemaName(const std::string& type) {
  const size_t slash = type.find('/');
  HOILCD_CHECK(slash != std::string::npos);
  return type.substr(0, slash) + "/msg/" + type.substr(slash + 1);
}

std::string Ros2MessageDefinition(const std::string& type) {
  std::string text = DefinitionOf(type);
  std::set<std::string> seen{type};
  std::vector<std::string> order;
  AddDependencies(type, &seen, &order);
  for (const std::string& used : order) {
    text += std::string(80, '=') + "\nMSG: " + used + "\n" + DefinitionOf(used);
  }
  return text;
}

std::string SerializeImage(const Ros2Header& header, uint32_t height, uint32_t width, const std::string& encoding,
                           uint32_t step, const void* data, size_t bytes) {
  HOILCD_CHECK_MSG(bytes == static_cast<size_t>(height) * step, "Image data must be height x step bytes");
  CdrWriter w(bytes + 64 + header.frame_id.size() + encoding.size());
  Header(&w, header);
  w.Uint32(height);
  w.Uint32(width);
  w.String(encoding);
  w.Uint8(0);  // is_bigendian: little-endian pixels
  w.Uint32(step);
  w.Bytes(data, bytes);
  return w.Take();
}

std::string SerializeCameraInfo(const Ros2Header& header, const PinholeCamera& c) {
  CdrWriter w(512);
  Header(&w, header);
  w.Uint32(c.height);
  w.Uint32(c.width);
  w.String("plumb_bob");
  w.Float64Sequence(c.d.data(), c.d.size());
  const double k[9] = {c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1};
  const double r[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const double p[12] = {c.fx, 0, c.cx, 0, 0, c.fy, c.cy, 0, 0, 0, 1, 0};
  w.Float64Array(k, 9);
  w.Float64Array(r, 9);
  w.Float64Array(p, 12);
  w.Uint32(0);  // binning_x
  w.Uint32(0);  // binning_y
  w.Uint32(0);  // roi: x_offset, y_offset, height, width (0: the full image), do_rectify
  w.Uint32(0);
  w.Uint32(0);
  w.Uint32(0);
  w.Bool(false);
  return w.Take();
}

std::string SerializeOdometry(const Ros2Header& header, const Ros2Odometry& o) {
  CdrWriter w(768);
  Header(&w, header);
  w.String(o.child_frame_id);
  Pose(&w, o.pose);
  w.Float64Array(o.pose_covariance.data(), 36);
  w.Float64Array(o.linear.data(), 3);
  w.Float64Array(o.angular.data(), 3);
  w.Float64Array(o.twist_covariance.data(), 36);
  return w.Take();
}

std::string SerializeTfMessage(const std::vector<Ros2Transform>& transforms) {
  CdrWriter w(128 * transforms.size());
  w.Uint32(static_cast<uint32_t>(transforms.size()));
  for (const Ros2Transform& t : transforms) {
    Header(&w, t.header);
    w.String(t.child_frame_id);
    Pose(&w, t.transform);  // Transform: translation (Vector3), rotation (Quaternion): a Pose's layout
  }
  return w.Take();
}

std::string SerializePoseStamped(const Ros2Header& header, const Ros2Pose& pose) {
  CdrWriter w(128);
  Header(&w, header);
  Pose(&w, pose);
  return w.Take();
}

std::string SerializeDetection2DArray(const Ros2Header& header, const std::vector<Ros2Detection>& detections) {
  CdrWriter w(64 + 512 * detections.size());
  Header(&w, header);
  w.Uint32(static_cast<uint32_t>(detections.size()));
  const Ros2Pose identity;
  const std::array<double, 36> no_covariance{};
  for (const Ros2Detection& d : detections) {
    Header(&w, header);
    w.Uint32(1);  // results: one hypothesis
    w.String(d.class_id);
    w.Float64(d.score);
    Pose(&w, identity);
    w.Float64Array(no_covariance.data(), 36);
    w.Float64(d.center_x);  // bbox.center.position
    w.Float64(d.center_y);
    w.Float64(0);  // bbox.center.theta
    w.Float64(d.size_x);
    w.Float64(d.size_y);
    w.String(d.id);
  }
  return w.Take();
}

}  // namespace hoilcd
