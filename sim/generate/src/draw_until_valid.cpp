#include "draw_until_valid.h"

#include "hoilcd/core/util/error.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/scene/scene.h"

namespace hoilcd {

nlohmann::ordered_json DrawUntilValid(const std::string& where, const std::string& what, int attempts,
                                      const std::function<nlohmann::ordered_json(int, std::string*)>& draw) {
  std::string last_problem;
  for (int attempt = 0; attempt < attempts; ++attempt) {
    try {
      nlohmann::ordered_json doc = draw(attempt, &last_problem);
      if (doc.is_null()) continue;
      const std::vector<std::string> warnings =
          CheckSceneRenders(SceneFromJson(nlohmann::json::parse(doc.dump()), where));
      if (!warnings.empty()) {
        last_problem = warnings.front();
        continue;
      }
      return doc;
    } catch (const InputError& e) {
      last_problem = e.what();
    }
  }
  throw InputError(where, "a " + what + " passing every check within generator.attempts = " + std::to_string(attempts) +
                              " draws; the last draw failed: " + last_problem);
}

}  // namespace hoilcd
