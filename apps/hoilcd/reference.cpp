// hoilcd reference scene|cameras: the scene file's reference (docs/guide/scenes.md) or the camera
// profiles with their sources (docs/models/camera_profiles.md), as Markdown.
#include <cstdio>
#include <memory>

#include "command.h"
#include "hoilcd/sim/scene/camera_profiles.h"
#include "hoilcd/sim/scene/scene_reference.h"
#include "shared.h"

namespace hoilcd {

Command AddReferenceCommand(CLI::App* app) {
  auto topic = std::make_shared<std::string>();
  CLI::App* cmd = app->add_subcommand(
      "reference", "print a reference generated from the code as Markdown (scene: every scene file field; cameras: "
      "the camera profiles and their datasheets)");
  cmd->add_option("topic", *topic, "what to print: scene or cameras")
      ->required()
      ->check(CLI::IsMember({"scene", "cameras"}));
  return {cmd, [topic] {
            std::printf("%s", (*topic == "cameras" ? CameraProfilesMarkdown() : SceneReferenceMarkdown()).c_str());
            return 0;
          }};
}

}  // namespace hoilcd
