#include "hoilcd/bench/export/mcap_export.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>

#include "hoilcd/bench/export/ros2_messages.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/util/allocator.h"
#include "hoilcd/core/util/atomic_file.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/json_reader.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/progress.h"

namespace hoilcd {
namespace {

// The frames of docs/guide/ros2.md: REP 105's map, odom and base_link; the camera's mount in body
// axes (x forward, y left, z up) and its optical frame (x right, y down, z forward), as REP 103 asks.
constexpr char kMapFrame[] = "map";
constexpr char kOdomFrame[] = "odom";
constexpr char kBaseFrame[] = "base_link";
constexpr char kCameraFrame[] = "thermal_camera";
constexpr char kOpticalFrame[] = "thermal_camera_optical";

// The topics, in channel order (within a frame's time, messages follow this order too).
enum Topic {
  kTfStatic,
  kCameraInfo,
  kImageRaw,
  kImageMono8,
  kDepth,
  kInstance,
  kOdom,
  kTf,
  kGroundTruthPose,
  kGroundTruthCameraPose,
  kPersons,
  kTopicCount
};
struct TopicSpec {
  const char* topic;
  const char* type;
};
constexpr TopicSpec kTopics[kTopicCount] = {
    {"/tf_static", "tf2_msgs/TFMessage"},
    {"/thermal/camera_info", "sensor_msgs/CameraInfo"},
    {"/thermal/image_raw", "sensor_msgs/Image"},
    {"/thermal/image_mono8", "sensor_msgs/Image"},
    {"/thermal/depth", "sensor_msgs/Image"},
    {"/thermal/instance", "sensor_msgs/Image"},
    {"/odom", "nav_msgs/Odometry"},
    {"/tf", "tf2_msgs/TFMessage"},
    {"/ground_truth/pose", "geometry_msgs/PoseStamped"},
    {"/ground_truth/camera_pose", "geometry_msgs/PoseStamped"},
    {"/persons", "vision_msgs/Detection2DArray"},
};

// rosbag2's record of the QoS a topic was offered with (its channel metadata "offered_qos_profiles"),
// which ros2 bag play offers again: reliable, keep-last, and /tf_static transient local (latched).
std::string OfferedQos(bool transient_local) {
  const std::string infinite = "    sec: 2147483647\n    nsec: 4294967295\n";
  return std::string("- history: 1\n  depth: ") + (transient_local ? "1" : "10") +
         "\n  reliability: 1\n  durability: " + (transient_local ? "1" : "2") + "\n  deadline:\n" + infinite +
         "  lifespan:\n" + infinite + "  liveliness: 1\n  liveliness_lease_duration:\n" + infinite +
         "  avoid_ros_namespace_conventions: false";
}

// The numbers export-mcap takes from scene.json (the resolved scene: every default filled in).
class SceneNumbers {
 public:
  explicit SceneNumbers(const Dataset& dataset)
      : path_(dataset.dir() + "/scene.json"), scene_(ParseJson(dataset.scene_json(), path_)) {}
  double Number(const std::string& pointer) const {
    const nlohmann::json::json_pointer p(pointer);
    if (!scene_.contains(p) || !scene_.at(p).is_number()) {
      throw InputError(path_ + ": " + pointer, "expected a number (the resolved scene a render writes)");
    }
    return scene_.at(p).get<double>();
  }
  bool Flag(const std::string& pointer) const {
    const nlohmann::json::json_pointer p(pointer);
    if (!scene_.contains(p) || !scene_.at(p).is_boolean()) {
      throw InputError(path_ + ": " + pointer, "expected true or false (the resolved scene a render writes)");
    }
    return scene_.at(p).get<bool>();
  }

 private:
  std::string path_;
  nlohmann::json scene_;
};

// The odometry's uncertainty, from the error model the dataset was rendered with (scene.json's
// /odometry), as docs/guide/ros2.md states it: the along-track error grows as
// wheel_radius_error_frac per metre driven, the heading as a random walk of
// heading_noise_deg_sqrt_m, both times error_scale; z, roll and pitch are fixed (planar robot).
struct OdometryNoise {
  double along_frac = 0;          // sd of the distance driven / distance
  double heading_rad_sqrt_m = 0;  // rad/sqrt(m)
};
constexpr double kVarianceFloor = 1e-9;  // keeps every covariance positive definite

OdometryNoise ReadOdometryNoise(const SceneNumbers& scene) {
  if (!scene.Flag("/odometry/enabled")) return {};
  const double scale = scene.Number("/odometry/error_scale");
  return {std::abs(scene.Number("/odometry/wheel_radius_error_frac")) * scale,
          scene.Number("/odometry/heading_noise_deg_sqrt_m") * M_PI / 180 * scale};
}

Ros2Pose PoseOf(const Rigid3& t) {
  return {{t.translation.x(), t.translation.y(), t.translation.z()},
          {t.rotation.x(), t.rotation.y(), t.rotation.z(), t.rotation.w()}};
}

Ros2Pose PlanarPose(double x_m, double y_m, double theta_rad) {
  return {{x_m, y_m, 0}, {0, 0, std::sin(theta_rad / 2), std::cos(theta_rad / 2)}};
}

uint64_t FrameTimeNs(const PoseRecord& pose) {
  return static_cast<uint64_t>(std::llround(std::max(0.0, pose.time_s) * 1e9));
}

// Everything a frame's messages need, read once.
struct ExportInputs {
  const Dataset* dataset = nullptr;
  bool topic[kTopicCount] = {};
  PinholeCamera camera;
  OdometryNoise noise;
  Rigid3 base_from_camera;                   // the rigid mount (body axes)
  std::vector<double> odometry_distance_m;   // per frame: odometry path length since its run began
  std::vector<const FramePersons*> persons;  // per frame (nullptr: nobody listed)
};

ExportInputs ReadInputs(const Dataset& dataset) {
  ExportInputs in;
  in.dataset = &dataset;
  const DatasetOutputs& outputs = dataset.manifest().outputs;
  for (int t = 0; t < kTopicCount; ++t) in.topic[t] = true;
  in.topic[kImageRaw] = outputs.radiometric;
  in.topic[kImageMono8] = outputs.thermal;
  in.topic[kDepth] = in.topic[kInstance] = outputs.exr;
  in.topic[kPersons] = outputs.persons;
  const CameraIntrinsics& k = dataset.manifest().intrinsics;
  in.camera = {static_cast<uint32_t>(k.width), static_cast<uint32_t>(k.height), k.fx, k.fy, k.cx, k.cy, {}};
  const SceneNumbers scene(dataset);
  in.noise = ReadOdometryNoise(scene);
  const double deg = M_PI / 180;
  const CameraPose mount{scene.Number("/robot/camera_forward_m"),       scene.Number("/robot/camera_lateral_m"),
                         scene.Number("/robot/camera_height_m"),        scene.Number("/robot/camera_yaw_deg") * deg,
                         scene.Number("/robot/camera_pitch_deg") * deg, scene.Number("/robot/camera_roll_deg") * deg};
  in.base_from_camera = mount.WorldFromCam();
  in.base_from_camera.rotation = in.base_from_camera.rotation * Eigen::Quaterniond(BodyFromCamRotation()).conjugate();
  const std::vector<PoseRecord>& poses = dataset.poses();
  in.odometry_distance_m.assign(poses.size(), 0.0);
  for (size_t f = 1; f < poses.size(); ++f) {
    if (poses[f].run != poses[f - 1].run) continue;
    const double step_m = std::hypot(poses[f].odo_x_m - poses[f - 1].odo_x_m, poses[f].odo_y_m - poses[f - 1].odo_y_m);
    in.odometry_distance_m[f] = in.odometry_distance_m[f - 1] + step_m;
  }
  in.persons.assign(poses.size(), nullptr);
  if (outputs.persons) {
    for (const FramePersons& p : dataset.persons()) {
      if (p.frame >= 0 && p.frame < static_cast<int>(poses.size())) in.persons[static_cast<size_t>(p.frame)] = &p;
    }
  }
  return in;
}

// The wheel odometry of frame f: its pose, the model's covariance, and the motion since the frame
// before (base_link axes; zero at a run's first frame).
Ros2Odometry OdometryOf(const ExportInputs& in, size_t f) {
  const std::vector<PoseRecord>& poses = in.dataset->poses();
  const PoseRecord& p = poses[f];
  Ros2Odometry o;
  o.child_frame_id = kBaseFrame;
  o.pose = PlanarPose(p.odo_x_m, p.odo_y_m, p.odo_theta_rad);
  const double s = in.odometry_distance_m[f];
  const double var_heading = in.noise.heading_rad_sqrt_m * in.noise.heading_rad_sqrt_m * s + kVarianceFloor;
  const double var_along = std::pow(in.noise.along_frac * s, 2);
  const double var_xy = var_along + var_heading * s * s / 3 + kVarianceFloor;  // heading error integrated
  o.pose_covariance[0] = o.pose_covariance[7] = var_xy;
  o.pose_covariance[14] = o.pose_covariance[21] = o.pose_covariance[28] = kVarianceFloor;
  o.pose_covariance[35] = var_heading;
  if (f > 0 && poses[f - 1].run == p.run && p.time_s > poses[f - 1].time_s) {
    const PoseRecord& q = poses[f - 1];
    const double dt = p.time_s - q.time_s, dx = p.odo_x_m - q.odo_x_m, dy = p.odo_y_m - q.odo_y_m;
    const double c = std::cos(q.odo_theta_rad), sn = std::sin(q.odo_theta_rad);
    o.linear = {(c * dx + sn * dy) / dt, (-sn * dx + c * dy) / dt, 0};
    o.angular = {0, 0, std::remainder(p.odo_theta_rad - q.odo_theta_rad, 2 * M_PI) / dt};
  }
  const double speed = std::hypot(o.linear[0], o.linear[1]);
  o.twist_covariance[0] = o.twist_covariance[7] = std::pow(in.noise.along_frac * speed, 2) + kVarianceFloor;
  o.twist_covariance[14] = o.twist_covariance[21] = o.twist_covariance[28] = kVarianceFloor;
  o.twist_covariance[35] = in.noise.heading_rad_sqrt_m * in.noise.heading_rad_sqrt_m * speed + kVarianceFloor;
  return o;
}

std::vector<Ros2Transform> StaticTransforms(const ExportInputs& in, const Ros2Time& stamp) {
  Rigid3 camera_from_optical;
  camera_from_optical.rotation = Eigen::Quaterniond(BodyFromCamRotation());
  return {{{stamp, kBaseFrame}, kCameraFrame, PoseOf(in.base_from_camera)},
          {{stamp, kCameraFrame}, kOpticalFrame, PoseOf(camera_from_optical)}};
}

std::string ImageMessage(const Ros2Header& header, const cv::Mat& image, const char* encoding) {
  HOILCD_CHECK(image.isContinuous());
  const size_t step = image.cols * image.elemSize();
  return SerializeImage(header, static_cast<uint32_t>(image.rows), static_cast<uint32_t>(image.cols), encoding,
                        static_cast<uint32_t>(step), image.data, step * image.rows);
}

std::vector<Ros2Detection> DetectionsOf(const FramePersons* frame) {
  std::vector<Ros2Detection> detections;
  if (frame == nullptr) return detections;
  for (const PersonRecord& p : frame->persons) {
    const cv::Rect2f& b = p.box_px;
    detections.push_back({std::to_string(p.id), "person", p.visible_fraction, b.x + b.width / 2.0, b.y + b.height / 2.0,
                          b.width, b.height});
  }
  return detections;
}

using FrameMessages = std::vector<std::pair<Topic, std::string>>;

// Frame f's messages in topic order; the EXR and the PNGs are decoded here (worker threads).
FrameMessages MessagesOf(const ExportInputs& in, int f) {
  const Dataset& d = *in.dataset;
  const PoseRecord& pose = d.poses()[static_cast<size_t>(f)];
  const Ros2Time stamp = Ros2Time::FromNanoseconds(FrameTimeNs(pose));
  const Ros2Header optical{stamp, kOpticalFrame};
  FrameMessages m;
  if (f == 0) m.emplace_back(kTfStatic, SerializeTfMessage(StaticTransforms(in, stamp)));
  m.emplace_back(kCameraInfo, SerializeCameraInfo(optical, in.camera));
  if (in.topic[kImageRaw]) m.emplace_back(kImageRaw, ImageMessage(optical, d.RadiometricCentikelvin(f), "mono16"));
  if (in.topic[kImageMono8]) m.emplace_back(kImageMono8, ImageMessage(optical, d.Thermal(f), "mono8"));
  if (in.topic[kDepth]) {
    const ExrChannels exr = ReadDatasetExr(d, f, {"Z", "id"});
    const std::string path = DatasetExrPath(d, f);
    m.emplace_back(kDepth, ImageMessage(optical, ExrChannel(exr, "Z", path), "32FC1"));
    cv::Mat instance;
    ExrChannel(exr, "id", path).convertTo(instance, CV_32S);  // the reader's float holds the int32 exactly
    m.emplace_back(kInstance, ImageMessage(optical, instance, "32SC1"));
  }
  const Ros2Odometry odometry = OdometryOf(in, static_cast<size_t>(f));
  m.emplace_back(kOdom, SerializeOdometry({stamp, kOdomFrame}, odometry));
  m.emplace_back(kTf, SerializeTfMessage({{{stamp, kOdomFrame}, kBaseFrame, odometry.pose}}));
  const Ros2Header map{stamp, kMapFrame};
  m.emplace_back(kGroundTruthPose, SerializePoseStamped(map, PlanarPose(pose.x_m, pose.y_m, pose.theta_rad)));
  m.emplace_back(kGroundTruthCameraPose, SerializePoseStamped(map, PoseOf(pose.Camera().WorldFromCam())));
  if (in.topic[kPersons]) {
    m.emplace_back(kPersons, SerializeDetection2DArray(optical, DetectionsOf(in.persons[static_cast<size_t>(f)])));
  }
  return m;
}

void CheckOutputPath(const std::string& out_path) {
  std::error_code ec;
  if (std::filesystem::is_directory(out_path, ec)) {
    throw InputError(out_path, "is a folder: -o names the .mcap file to write");
  }
}

}  // namespace

McapExportResult ExportMcap(const std::string& dataset_dir, const std::string& out_path,
                            const McapExportOptions& options) {
  const auto start = std::chrono::steady_clock::now();  // the result's seconds: opening the dataset included
  CheckOutputPath(out_path);
  KeepFreedMemoryForReuse();  // frames, messages and chunks of a few MB come and go on every thread
  const Dataset dataset = Dataset::Open(dataset_dir, Verify::kOnRead, options.threads);
  const ExportInputs in = ReadInputs(dataset);
  const int frames = dataset.num_frames();
  AtomicFile file(out_path);
  McapWriterOptions writer_options;
  writer_options.compression = options.compression;
  writer_options.library = std::string("hoilcd ") + HOILCD_VERSION;
  writer_options.threads = options.threads;
  McapWriter writer([&file](std::string_view bytes) { file.Write(bytes); }, writer_options);
  uint16_t channel[kTopicCount] = {};
  std::map<std::string, uint16_t> schema;
  for (int t = 0; t < kTopicCount; ++t) {
    if (!in.topic[t]) continue;
    const std::string type = kTopics[t].type;
    if (!schema.count(type)) {
      schema[type] = writer.AddSchema(Ros2SchemaName(type), "ros2msg", Ros2MessageDefinition(type));
    }
    channel[t] = writer.AddChannel(schema[type], kTopics[t].topic, "cdr",
                                   {{"offered_qos_profiles", OfferedQos(t == kTfStatic)}});
  }
  ProgressReporter progress("export-mcap", frames, "frames", options.quiet);
  const int batch = 16 * ResolveThreadCount(options.threads);
  std::vector<FrameMessages> messages;
  for (int first = 0; first < frames; first += batch) {
    messages.assign(static_cast<size_t>(std::min(batch, frames - first)), {});
    ParallelFor(static_cast<int64_t>(messages.size()), options.threads,
                [&](int64_t i) { messages[static_cast<size_t>(i)] = MessagesOf(in, first + static_cast<int>(i)); });
    for (size_t i = 0; i < messages.size(); ++i) {
      const uint64_t time_ns = FrameTimeNs(dataset.poses()[first + i]);
      for (const auto& [topic, bytes] : messages[i]) writer.AddMessage(channel[topic], time_ns, time_ns, bytes);
    }
    progress.Update(static_cast<int64_t>(messages.size()));
  }
  const McapStatistics statistics = writer.Finish();
  file.Commit();
  progress.Done();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  McapExportResult result{out_path,
                          frames,
                          {},
                          statistics.message_count,
                          statistics.bytes,
                          statistics.message_start_time,
                          statistics.message_end_time,
                          seconds};
  for (int t = 0; t < kTopicCount; ++t) {
    const auto count = statistics.channel_message_counts.find(channel[t]);
    const uint64_t n = count == statistics.channel_message_counts.end() ? 0 : count->second;
    if (in.topic[t]) result.topics.emplace_back(kTopics[t].topic, n);
  }
  return result;
}

}  // namespace hoilcd
