// Reading /runs into Scene::runs (scene.cpp calls it while typing a scene; SceneOfRun is in
// scene_runs.cpp).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/core/util/error.h"
#include "hoilcd/sim/scene/scene.h"

namespace hoilcd {

// An override's KEY ("crowd.people_per_table" or "/crowd/people_per_table") as a JSON pointer.
std::string OverridePointer(const std::string& key);

// Types doc's /runs (defaults filled) into s->runs, and s->frames becomes the runs' total; the sun's
// time of day (doc's and s's) becomes the first run's. Problems (a run before the previous ended,
// an override of what is one for all runs, another time of day in /room/sun) go to `problems` at
// their pointers. `written` is the scene as written, and
// `overrides` the command line's, to tell an explicit room.sun.time_of_day_h from its default.
void ReadRuns(nlohmann::json* doc, const nlohmann::json& written, const std::vector<std::string>& overrides, Scene* s,
              ProblemCollector* problems);

// Builds every run's scene once (SceneOfRun), so that a run whose overrides make a bad scene is
// reported when the scene loads, each problem under /runs/N.
void CheckRunScenes(const Scene& s, ProblemCollector* problems);

}  // namespace hoilcd
