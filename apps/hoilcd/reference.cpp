// hoilcd reference scene|cameras|generate: the scene file's reference (docs/guide/scenes.md), the
// camera profiles with their sources (docs/models/camera_profiles.md) or the generator's options,
// as Markdown.
#include <cstdio>
#include <memory>

#include "command.h"
#include "hoilcd/core/util/option_table.h"
#include "hoilcd/sim/generate/generator.h"
#include "hoilcd/sim/scene/camera_profiles.h"
#include "hoilcd/sim/scene/scene_reference.h"
#include "shared.h"

namespace hoilcd {

Command AddReferenceCommand(CLI::App* app) {
  auto topic = std::make_shared<std::string>();
  CLI::App* cmd = app->add_subcommand(
      "reference",
      "print a reference generated from the code as Markdown (scene: every scene file field; cameras: the camera "
      "profiles and their datasheets; generate: every option of hoilcd generate, a scene's /generator/options)");
  cmd->add_option("topic", *topic, "what to print: scene, cameras or generate")
      ->required()
      ->check(CLI::IsMember({"scene", "cameras", "generate"}));
  return {cmd, [topic] {
            const std::string text = *topic == "scene" ? SceneReferenceMarkdown()
                                     : *topic == "cameras"
                                         ? CameraProfilesMarkdown()
                                         : FormatOptionTableMarkdown(GeneratorOptions::Table().List());
            std::printf("%s", text.c_str());
            return 0;
          }};
}

}  // namespace hoilcd
