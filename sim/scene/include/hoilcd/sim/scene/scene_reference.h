// The scene file's reference for users, as Markdown: every object's fields from the option tables
// that read them (name, default, accepted values, description) and the hand-read parts (top-level
// keys, tables, objects) from the compiled-in schema. `hoilcd reference scene` prints it; it is
// docs/guide/scenes.md, and a test fails when that file is stale.
#pragma once

#include <string>

namespace hoilcd {

std::string SceneReferenceMarkdown();

}  // namespace hoilcd
