// hoilcd reference scene: the scene file's reference as Markdown (docs/guide/scenes.md).
#include <cstdio>
#include <memory>

#include "command.h"
#include "hoilcd/sim/scene/scene_reference.h"
#include "shared.h"

namespace hoilcd {

Command AddReferenceCommand(CLI::App* app) {
  auto topic = std::make_shared<std::string>();
  CLI::App* cmd = app->add_subcommand(
      "reference", "print a reference generated from the code as Markdown (scene: every scene file field)");
  cmd->add_option("topic", *topic, "what to print: scene")->required()->check(CLI::IsMember({"scene"}));
  return {cmd, [topic] {
            std::printf("%s", SceneReferenceMarkdown().c_str());
            return 0;
          }};
}

}  // namespace hoilcd
