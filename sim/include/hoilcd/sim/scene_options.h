// Maps a resolved Scene onto the options structs of the simulator's modules, so every value a
// module uses comes from the scene file (defaults from scenes/scene.schema.json).
#pragma once

#include "hoilcd/core/camera.h"
#include "hoilcd/sim/renderer.h"
#include "hoilcd/sim/robot.h"
#include "hoilcd/sim/scene.h"
#include "hoilcd/sim/sensor.h"

namespace hoilcd {

CameraIntrinsics IntrinsicsFromScene(const Scene& scene);
SensorOptions SensorOptionsFromScene(const Scene& scene);
RenderOptions RenderOptionsFromScene(const Scene& scene, int threads);
TricycleOptions TricycleOptionsFromScene(const Scene& scene);
RouteOptions RouteOptionsFromScene(const Scene& scene);  // frames = scene.frames
OdometryErrorOptions OdometryOptionsFromScene(const Scene& scene);

}  // namespace hoilcd
