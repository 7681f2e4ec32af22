#include "hoilcd/sim/scene/scene_options.h"

#include <cmath>

namespace hoilcd {
namespace {
// A problem found while mapping the scene onto a module: an input error at that section.
void Require(const std::string& problem, const Scene& scene, const char* section) {
  if (!problem.empty()) throw InputError(scene.file + ": /" + section, problem);
}
}  // namespace

CameraOptions::CameraOptions() { Table().FillDefaults(this); }

const OptionTable<CameraOptions>& CameraOptions::Table() {
  using O = CameraOptions;
  static const OptionTable<O> table =
      OptionTable<O>()
          .External("profile",
                    "a real camera whose datasheet sets the image size, field of view, frame rate, NETD, FFC and "
                    "output step, unless the scene gives them; left out, the defaults here (the paper's camera). "
                    "Names and values: docs/models/camera_profiles.md")
          .Add("width_px", &O::width_px, 256, "px", OptionRange::Closed(8, 4096), "image width")
          .Add("height_px", &O::height_px, 192, "px", OptionRange::Closed(8, 4096), "image height")
          .Add("hfov_deg", &O::hfov_deg, 50.0, "deg", OptionRange::Closed(1, 170), "horizontal field of view")
          .Flatten(&O::sensor, SensorOptions::Table())
          .Flatten(&O::render, RenderOptions::Table())
          .Nest("video", &O::video, VideoOptions::Table());
  return table;
}

CameraIntrinsics IntrinsicsFromScene(const Scene& scene) {
  return CameraIntrinsics::FromHorizontalFov(scene.camera.width_px, scene.camera.height_px, scene.camera.hfov_deg);
}

SensorOptions SensorOptionsFromScene(const Scene& scene) { return scene.camera.sensor; }

VideoOptions VideoOptionsFromScene(const Scene& scene) {
  Require(VideoFrameRateProblem(scene.frame_rate_hz), scene, "frame_rate_hz");
  Require(VideoFrameSizeProblem(scene.camera.width_px, scene.camera.height_px), scene, "camera");
  return scene.camera.video;
}

RenderOptions RenderOptionsFromScene(const Scene& scene, int threads) {
  RenderOptions o = scene.camera.render;
  o.threads = threads;
  Require(o.Check(), scene, "camera");
  return o;
}

TricycleOptions TricycleOptionsFromScene(const Scene& scene) { return scene.robot; }

RouteOptions RouteOptionsFromScene(const Scene& scene) { return scene.route; }

OdometryErrorOptions OdometryOptionsFromScene(const Scene& scene) {
  const OdometryErrorOptions& o = scene.odometry;
  // A steering offset is only meaningful inside the steering range.
  const double max_steer_deg = scene.robot.max_steer_deg;
  if (std::abs(o.steer_offset_deg * o.error_scale) >= max_steer_deg) {
    throw InputError(scene.file + ": /odometry/steer_offset_deg",
                     "steer_offset_deg times error_scale must stay below /robot/max_steer_deg (" +
                         std::to_string(max_steer_deg) + " deg)");
  }
  return o;
}

RobotRun SimulateSceneRobot(const Scene& scene, const std::vector<Obstacle2D>& obstacles) {
  try {
    return SimulateRobot(TricycleOptionsFromScene(scene), RouteOptionsFromScene(scene), OdometryOptionsFromScene(scene),
                         obstacles, scene.frame_rate_hz, scene.run_seed);
  } catch (const InputError& e) {
    throw LocatedInScene(scene, e);
  }
}

}  // namespace hoilcd
