// hoilcd validate SCENE: check a scene file and print every problem with its JSON path.
#include <cstdio>
#include <memory>

#include "command.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/sim/output/sequence.h"
#include "shared.h"

namespace hoilcd {

Command AddValidateCommand(CLI::App* app) {
  auto args = std::make_shared<SceneArgs>();
  CLI::App* cmd = app->add_subcommand("validate", "check a scene file; print every problem with its JSON path");
  AddSceneFlags(cmd, args.get(), true);
  return {cmd, [args] {
            // Print every problem, not only the first: validation is the point of this command.
            const Scene scene = LoadSceneArgs(*args);
            PrintWarnings(CheckSceneRenders(scene));  // what render checks before its first frame
            std::printf("%s: valid scene '%s' (%d frames at %g Hz, %zu tables, hash %s)\n", args->path.c_str(),
                        scene.name.c_str(), scene.frames, scene.frame_rate_hz, scene.tables.size(), scene.hash.c_str());
            return 0;
          }};
}

}  // namespace hoilcd
