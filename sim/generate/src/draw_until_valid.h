// The generators' draw loop (rooms in generator.cpp, floors in floor_layout.cpp): draw a scene,
// keep the first draw that passes its own checks and what `hoilcd validate` checks, else draw
// again, up to options.attempts.
#pragma once

#include <functional>
#include <string>

#include <nlohmann/json.hpp>

namespace hoilcd {

// draw(attempt, &problem) returns a scene document, or null with `problem` set when the draw fails
// the generator's own checks; an InputError it throws fails that draw too. A document is returned
// once it loads and SceneFromJson + CheckSceneRenders find nothing (its robot runs clear, its crowd
// plans). InputError naming `where` when no attempt passes: "a <what> passing every check within
// generator.attempts = N draws; the last draw failed: <problem>".
nlohmann::ordered_json DrawUntilValid(const std::string& where, const std::string& what, int attempts,
                                      const std::function<nlohmann::ordered_json(int, std::string*)>& draw);

}  // namespace hoilcd
