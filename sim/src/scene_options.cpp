#include "hoilcd/sim/scene_options.h"

#include <cmath>

namespace hoilcd {
namespace {
double D(const nlohmann::json& j, const char* key) { return j.at(key).get<double>(); }
bool B(const nlohmann::json& j, const char* key) { return j.at(key).get<bool>(); }

// Options structs report problems as strings whose first word names the field ("a.b must ...");
// in a scene they are input errors at that field's JSON pointer when the scene has that field.
void Require(const std::string& problem, const Scene& scene, const char* section) {
  if (problem.empty()) return;
  std::string pointer = std::string("/") + section;
  std::string field_pointer = pointer + "/" + problem.substr(0, problem.find(' '));
  for (char& c : field_pointer) c = c == '.' ? '/' : c;
  try {
    if (scene.resolved.contains(nlohmann::json::json_pointer(field_pointer))) pointer = field_pointer;
  } catch (const nlohmann::json::exception&) {
    // Not a valid pointer: the message does not start with a field name.
  }
  throw InputError(scene.file + ": " + pointer, problem);
}
}  // namespace

CameraIntrinsics IntrinsicsFromScene(const Scene& scene) {
  const nlohmann::json& c = scene.camera;
  return CameraIntrinsics::FromHorizontalFov(c.at("width_px").get<int>(), c.at("height_px").get<int>(),
                                             D(c, "hfov_deg"));
}

SensorOptions SensorOptionsFromScene(const Scene& scene) {
  const nlohmann::json& c = scene.camera;
  SensorOptions o;
  o.optics_blur = B(c, "optics_blur");
  o.psf_sigma_px = D(c, "psf_sigma_px");
  o.temporal_noise = B(c, "temporal_noise");
  o.netd_k = D(c, "netd_k");
  o.fixed_pattern = B(c, "fixed_pattern");
  o.fpn_offset_k = D(c, "fpn_offset_k");
  o.fpn_gain_sigma = D(c, "fpn_gain_sigma");
  o.column_stripe_k = D(c, "column_stripe_k");
  o.drift = B(c, "drift");
  o.drift_k_per_min = D(c, "drift_k_per_min");
  o.ffc_interval_s = D(c, "ffc_interval_s");
  o.lens_shading = B(c, "lens_shading");
  o.housing_warming_k_per_min = D(c, "housing_warming_k_per_min");
  o.vignetting_k_per_k = D(c, "vignetting_k_per_k");
  o.narcissus_k_per_k = D(c, "narcissus_k_per_k");
  o.narcissus_sigma = D(c, "narcissus_sigma");
  o.ffc_freeze = B(c, "ffc_freeze");
  o.ffc_freeze_s = D(c, "ffc_freeze_s");
  o.time_constant = B(c, "time_constant");
  o.time_constant_s = D(c, "time_constant_s");
  o.quantisation = B(c, "quantisation");
  o.quantisation_step_k = D(c, "quantisation_step_k");
  o.emissivity_setting = D(c, "emissivity_setting");
  o.reflected_temperature_c = scene.environment_temperature_c;
  o.display_min_c = D(c, "display_min_c");
  o.display_max_c = D(c, "display_max_c");
  Require(o.Check(), scene, "camera");
  return o;
}

VideoOptions VideoOptionsFromScene(const Scene& scene) {
  const nlohmann::json& v = scene.camera.at("video");
  VideoOptions o;
  o.enabled = B(v, "enabled");
  o.crf = v.at("crf").get<int>();
  o.bitrate_kbps = v.at("bitrate_kbps").get<int>();
  o.gop_frames = v.at("gop_frames").get<int>();
  o.preset = v.at("preset").get<std::string>();
  Require(o.Check(), scene, "camera/video");
  Require(VideoFrameRateProblem(scene.frame_rate_hz), scene, "frame_rate_hz");
  const CameraIntrinsics intrinsics = IntrinsicsFromScene(scene);
  Require(VideoFrameSizeProblem(intrinsics.width, intrinsics.height), scene, "camera");
  return o;
}

RenderOptions RenderOptionsFromScene(const Scene& scene, int threads) {
  const nlohmann::json& c = scene.camera;
  RenderOptions o;
  o.edge_supersampling = B(c, "edge_supersampling");
  o.edge_samples_per_axis = c.at("edge_samples_per_axis").get<int>();
  o.specular_reflections = B(c, "specular_reflections");
  o.threads = threads;
  Require(o.Check(), scene, "camera");
  return o;
}

TricycleOptions TricycleOptionsFromScene(const Scene& scene) {
  const nlohmann::json& r = scene.robot;
  TricycleOptions o;
  o.wheelbase_m = D(r, "wheelbase_m");
  o.max_steer_deg = D(r, "max_steer_deg");
  o.max_steer_rate_deg_s = D(r, "max_steer_rate_deg_s");
  o.max_speed_m_s = D(r, "max_speed_m_s");
  o.max_accel_m_s2 = D(r, "max_accel_m_s2");
  o.integration_rate_hz = D(r, "integration_rate_hz");
  o.length_m = D(r, "length_m");
  o.width_m = D(r, "width_m");
  o.base_to_rear_m = D(r, "base_to_rear_m");
  o.camera_forward_m = D(r, "camera_forward_m");
  o.camera_lateral_m = D(r, "camera_lateral_m");
  o.camera_height_m = D(r, "camera_height_m");
  o.camera_pitch_deg = D(r, "camera_pitch_deg");
  o.camera_yaw_deg = D(r, "camera_yaw_deg");
  o.camera_roll_deg = D(r, "camera_roll_deg");
  const std::string navigation = r.at("navigation").get<std::string>();
  o.navigation = navigation == "ground_truth" ? TricycleOptions::Navigation::kGroundTruth
                 : navigation == "odometry"   ? TricycleOptions::Navigation::kOdometry
                                              : TricycleOptions::Navigation::kLocalized;
  const nlohmann::json& l = r.at("localization");
  o.localization.interval_s = D(l, "interval_s");
  o.localization.position_sd_m = D(l, "position_sd_m");
  o.localization.heading_sd_deg = D(l, "heading_sd_deg");
  o.localization.correlation_s = D(l, "correlation_s");
  const nlohmann::json& v = r.at("vibration");
  o.vibration.enabled = B(v, "enabled");
  o.vibration.natural_frequency_hz = D(v, "natural_frequency_hz");
  o.vibration.damping_ratio = D(v, "damping_ratio");
  o.vibration.roll_sd_deg = D(v, "roll_sd_deg");
  o.vibration.pitch_sd_deg = D(v, "pitch_sd_deg");
  o.vibration.height_sd_m = D(v, "height_sd_m");
  o.vibration.reference_speed_m_s = D(v, "reference_speed_m_s");
  o.vibration.pitch_per_accel_deg_s2_m = D(v, "pitch_per_accel_deg_s2_m");
  o.vibration.roll_per_lat_accel_deg_s2_m = D(v, "roll_per_lat_accel_deg_s2_m");
  Require(o.Check(), scene, "robot");
  return o;
}

RouteOptions RouteOptionsFromScene(const Scene& scene) {
  const nlohmann::json& r = scene.route;
  RouteOptions o;
  o.waypoints_m.clear();
  for (const nlohmann::json& p : r.at("waypoints_m")) {
    o.waypoints_m.emplace_back(p.at(0).get<double>(), p.at(1).get<double>());
  }
  o.frames = scene.frames;
  o.cruise_speed_m_s = D(r, "cruise_speed_m_s");
  o.lookahead_m = D(r, "lookahead_m");
  o.max_lateral_accel_m_s2 = D(r, "max_lateral_accel_m_s2");
  o.corner_radius_m = D(r, "corner_radius_m");
  Require(o.Check(), scene, "route");
  return o;
}

OdometryErrorOptions OdometryOptionsFromScene(const Scene& scene) {
  const nlohmann::json& r = scene.odometry;
  OdometryErrorOptions o;
  o.enabled = B(r, "enabled");
  o.error_scale = D(r, "error_scale");
  o.wheel_radius_error_frac = D(r, "wheel_radius_error_frac");
  o.steer_offset_deg = D(r, "steer_offset_deg");
  o.wheelbase_error_frac = D(r, "wheelbase_error_frac");
  o.encoder_counts_per_rev = D(r, "encoder_counts_per_rev");
  o.wheel_radius_m = D(r, "wheel_radius_m");
  o.slip_per_accel_s2_m = D(r, "slip_per_accel_s2_m");
  o.turn_slip_per_lat_accel_s2_m = D(r, "turn_slip_per_lat_accel_s2_m");
  o.slip_noise_frac = D(r, "slip_noise_frac");
  o.heading_noise_deg_sqrt_m = D(r, "heading_noise_deg_sqrt_m");
  Require(o.Check(), scene, "odometry");
  // A steering offset is only meaningful inside the steering range.
  const double max_steer_deg = D(scene.robot, "max_steer_deg");
  if (std::abs(o.steer_offset_deg * o.error_scale) >= max_steer_deg) {
    throw InputError(scene.file + ": /odometry/steer_offset_deg",
                     "steer_offset_deg times error_scale must stay below /robot/max_steer_deg (" +
                         std::to_string(max_steer_deg) + " deg)");
  }
  return o;
}

RobotRun SimulateSceneRobot(const Scene& scene, const std::vector<Obstacle2D>& obstacles) {
  try {
    return SimulateRobot(TricycleOptionsFromScene(scene), RouteOptionsFromScene(scene),
                         OdometryOptionsFromScene(scene), obstacles, scene.frame_rate_hz, scene.seed);
  } catch (const InputError& e) {
    throw LocatedInScene(scene, e);
  }
}

}  // namespace hoilcd
