// Maps a resolved Scene onto the options structs of the simulator's modules, so every value a
// module uses comes from the scene file (defaults from scenes/scene.schema.json).
#pragma once

#include "hoilcd/core/dataset/video.h"
#include "hoilcd/core/geometry/camera.h"
#include "hoilcd/sim/robot/robot.h"
#include "hoilcd/sim/scene/render_options.h"
#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/sensor/sensor.h"

namespace hoilcd {

CameraIntrinsics IntrinsicsFromScene(const Scene& scene);
SensorOptions SensorOptionsFromScene(const Scene& scene);
// Also checks that thermal.mp4 can carry the scene's frame rate and frame size.
VideoOptions VideoOptionsFromScene(const Scene& scene);
RenderOptions RenderOptionsFromScene(const Scene& scene, int threads);
TricycleOptions TricycleOptionsFromScene(const Scene& scene);
RouteOptions RouteOptionsFromScene(const Scene& scene);  // frames = scene.frames

// The robot run a scene's sequence drives among `obstacles` (the World's); route and robot
// problems are InputErrors that name the scene file.
RobotRun SimulateSceneRobot(const Scene& scene, const std::vector<Obstacle2D>& obstacles);
OdometryErrorOptions OdometryOptionsFromScene(const Scene& scene);

}  // namespace hoilcd
