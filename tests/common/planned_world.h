// A scene's world as the sim tests use it: the robot's run simulated in it and the crowd
// planned on that run (what RenderSequence does before its first frame).
#pragma once

#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/scene/scene_options.h"
#include "hoilcd/sim/world/world.h"

namespace hoilcd::test {

struct PlannedWorld {
  explicit PlannedWorld(const Scene& s)
      : scene(s), world(scene, table), run(SimulateSceneRobot(scene, world.obstacles())) {
    world.PlanCrowd(run.samples);
  }
  Scene scene;
  BandRadianceTable table;  // before world: the world keeps a reference to it
  World world;
  RobotRun run;
};

}  // namespace hoilcd::test
