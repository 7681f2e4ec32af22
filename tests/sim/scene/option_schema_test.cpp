// The scene schema and the C++ option tables describe the same options: same names, types,
// defaults, minimum/maximum (and whether each is exclusive), string choices. Any drift fails here.
#include <algorithm>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hoilcd/core/util/option_table.h"
#include "hoilcd/sim/generate/generator.h"
#include "hoilcd/sim/robot/robot.h"
#include "hoilcd/sim/scene/camera_options.h"
#include "hoilcd/sim/scene/camera_profiles.h"
#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/world/crowd.h"

namespace hoilcd {
namespace {

using nlohmann::json;

// The schema node of an object property path ("/robot/vibration"), or null.
const json* SchemaNode(const json& root, const std::string& path) {
  const json* node = &root;
  size_t at = 1;
  while (at <= path.size() && at > 0) {
    const size_t slash = path.find('/', at);
    const std::string key = path.substr(at, slash == std::string::npos ? std::string::npos : slash - at);
    if (!node->contains("properties") || !(*node)["properties"].contains(key)) return nullptr;
    node = &(*node)["properties"][key];
    if (slash == std::string::npos) break;
    at = slash + 1;
  }
  return node;
}

// Every leaf (non-object) property below an object node, as paths relative to it.
void SchemaLeaves(const json& node, const std::string& prefix, std::set<std::string>* out) {
  for (const auto& [key, sub] : node["properties"].items()) {
    const std::string path = prefix.empty() ? key : prefix + "/" + key;
    if (sub.value("type", "") == "object" && sub.contains("properties")) {
      SchemaLeaves(sub, path, out);
    } else {
      out->insert(path);
    }
  }
}

std::string Bound(const json& node, const char* inclusive, const char* exclusive) {
  if (node.contains(exclusive)) return "(" + json(node[exclusive].get<double>()).dump() + " exclusive)";
  if (node.contains(inclusive)) return json(node[inclusive].get<double>()).dump();
  return "none";
}

std::string Bound(const std::optional<OptionRange::Bound>& bound) {
  if (!bound) return "none";
  const std::string value = json(bound->value).dump();
  return bound->exclusive ? "(" + value + " exclusive)" : value;
}

// Every disagreement between the schema object at `pointer` and `options`, one line each.
std::vector<std::string> Disagreements(const json& schema, const std::string& pointer,
                                       const std::vector<OptionInfo>& options) {
  std::vector<std::string> out;
  const json* object = SchemaNode(schema, pointer);
  if (object == nullptr) return {pointer + ": not in the schema"};
  std::set<std::string> leaves;
  SchemaLeaves(*object, "", &leaves);
  std::set<std::string> in_table;
  for (const OptionInfo& o : options) {
    const std::string where = pointer + "/" + o.name;
    const json* node = SchemaNode(schema, where);
    if (o.code_only) {
      if (node != nullptr) out.push_back(where + ": code-only in C++ but a scene key in the schema");
      continue;
    }
    in_table.insert(o.name);
    if (node == nullptr) {
      out.push_back(where + ": in the C++ table, missing in the schema");
      continue;
    }
    if (o.kind == OptionInfo::Kind::kExternal) continue;  // arrays and maps read by hand
    static const std::map<OptionInfo::Kind, std::string> kType = {{OptionInfo::Kind::kNumber, "number"},
                                                                  {OptionInfo::Kind::kInteger, "integer"},
                                                                  {OptionInfo::Kind::kBoolean, "boolean"},
                                                                  {OptionInfo::Kind::kString, "string"}};
    if (node->value("type", "") != kType.at(o.kind)) {
      out.push_back(where + ": type " + kType.at(o.kind) + " in C++, " + node->value("type", "?") + " in the schema");
    }
    const json cpp_default = json::parse(o.default_json);
    const bool required =
        object->contains("required") && (*object)["required"].is_array() &&
        std::find((*object)["required"].begin(), (*object)["required"].end(), o.name) != (*object)["required"].end();
    if (required) {
      // A required key has no schema default; the table's only fills a struct made in code.
    } else if (o.optional) {
      if (node->contains("default")) {
        out.push_back(where + ": optional in C++ (left out means " + o.default_json +
                      ") but the schema gives a default, which every resolved scene would then hold");
      }
    } else if (!node->contains("default")) {
      out.push_back(where + ": no default in the schema (C++: " + o.default_json + ")");
    } else if (cpp_default.is_number() ? (*node)["default"].get<double>() != cpp_default.get<double>()
                                       : (*node)["default"] != cpp_default) {
      out.push_back(where + ": default " + o.default_json + " in C++, " + (*node)["default"].dump() + " in the schema");
    }
    if (o.kind == OptionInfo::Kind::kNumber || o.kind == OptionInfo::Kind::kInteger) {
      const std::string schema_min = Bound(*node, "minimum", "exclusiveMinimum");
      const std::string schema_max = Bound(*node, "maximum", "exclusiveMaximum");
      if (schema_min != Bound(o.range.min)) {
        out.push_back(where + ": minimum " + Bound(o.range.min) + " in C++, " + schema_min + " in the schema");
      }
      if (schema_max != Bound(o.range.max)) {
        out.push_back(where + ": maximum " + Bound(o.range.max) + " in C++, " + schema_max + " in the schema");
      }
    }
    if (o.kind == OptionInfo::Kind::kString) {
      std::vector<std::string> schema_choices;
      if (node->contains("enum")) schema_choices = (*node)["enum"].get<std::vector<std::string>>();
      if (schema_choices != o.choices) out.push_back(where + ": string choices differ");
    }
  }
  for (const std::string& leaf : leaves) {
    if (!in_table.count(leaf)) out.push_back(pointer + "/" + leaf + ": in the schema, missing in the C++ table");
  }
  return out;
}

std::string Lines(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

TEST(OptionSchema, EverySimOptionTableAgreesWithTheSceneSchema) {
  const std::vector<std::pair<std::string, std::vector<OptionInfo>>> tables = {
      {"/camera", CameraOptions::Table().List()},       {"/robot", TricycleOptions::Table().List()},
      {"/route", RouteOptions::Table().List()},         {"/odometry", OdometryErrorOptions::Table().List()},
      {"/crowd", CrowdOptions::Table().List()},         {"/room", RoomOptions::Table().List()},
      {"/furniture", FurnitureOptions::Table().List()}, {"/generator/options", GeneratorOptions::Table().List()},
  };
  for (const auto& [pointer, options] : tables) {
    const std::vector<std::string> problems = Disagreements(SceneSchema(), pointer, options);
    EXPECT_TRUE(problems.empty()) << Lines(problems);
  }
}

// The schema's enum of camera profiles is the registry's list, in its order.
TEST(OptionSchema, TheCameraProfileEnumIsTheRegisteredProfiles) {
  const json& profile = SceneSchema()["properties"]["camera"]["properties"]["profile"];
  EXPECT_EQ(profile["enum"].get<std::vector<std::string>>(), CameraProfileNames());
  EXPECT_FALSE(profile.contains("default")) << "a default would put a profile into every resolved scene";
}

// Array elements have a table too: one window of /room/windows against the schema's items.
TEST(OptionSchema, TheWindowTableAgreesWithTheSchemasWindowItems) {
  const json items = SceneSchema()["properties"]["room"]["properties"]["windows"]["items"];
  const json wrapped = {{"properties", {{"window", items}}}};
  const std::vector<std::string> problems = Disagreements(wrapped, "/window", WindowSpec::Table().List());
  EXPECT_TRUE(problems.empty()) << Lines(problems);
}

// Defaults that are arrays (read by hand, so outside the tables) agree with the schema too.
TEST(OptionSchema, ArrayDefaultsAgreeWithTheSchema) {
  const json& properties = SceneSchema()["properties"];
  json waypoints = json::array();
  for (const Eigen::Vector2d& p : RouteOptions().waypoints_m) waypoints.push_back({p.x(), p.y()});
  EXPECT_EQ(waypoints, properties["route"]["properties"]["waypoints_m"]["default"]);
  const RoomOptions room;
  EXPECT_EQ(json({room.size_m.x(), room.size_m.y(), room.size_m.z()}),
            properties["room"]["properties"]["size_m"]["default"]);
  const json window_default = properties["room"]["properties"]["windows"]["default"];
  ASSERT_EQ(room.windows.size(), window_default.size());
  for (size_t i = 0; i < room.windows.size(); ++i) {
    const WindowSpec& w = room.windows[i];
    const json& d = window_default[i];
    EXPECT_EQ(w.wall, d["wall"]);
    EXPECT_EQ(w.center_m, d["center_m"].get<double>());
    EXPECT_EQ(w.bottom_m, d["bottom_m"].get<double>());
    EXPECT_EQ(w.width_m, d["width_m"].get<double>());
    EXPECT_EQ(w.height_m, d["height_m"].get<double>());
  }
}

// The comparison itself: a schema that drifted from a table in each way is caught.
TEST(OptionSchema, ADriftedDefaultRangeOrFieldIsReported) {
  const std::vector<OptionInfo> robot = TricycleOptions::Table().List();
  const auto drifted = [&](const std::function<void(json*)>& edit) {
    json schema = SceneSchema();
    edit(&schema);
    return Lines(Disagreements(schema, "/robot", robot));
  };
  EXPECT_EQ(drifted([](json*) {}), "");
  EXPECT_NE(drifted([](json* s) {
              (*s)["properties"]["robot"]["properties"]["camera_height_m"]["default"] = 0.55;
            }).find("/robot/camera_height_m: default 0.95 in C++, 0.55 in the schema"),
            std::string::npos);
  EXPECT_NE(drifted([](json* s) {
              json& node = (*s)["properties"]["robot"]["properties"]["max_steer_deg"];
              node.erase("exclusiveMaximum");
              node["maximum"] = 89;
            }).find("/robot/max_steer_deg: maximum (89.0 exclusive) in C++, 89.0 in the schema"),
            std::string::npos);
  EXPECT_NE(drifted([](json* s) {
              json& node = (*s)["properties"]["robot"]["properties"]["wheelbase_m"];
              node.erase("exclusiveMinimum");
              node["minimum"] = 0;
            }).find("/robot/wheelbase_m: minimum (0.0 exclusive) in C++, 0.0 in the schema"),
            std::string::npos);
  EXPECT_NE(drifted([](json* s) {
              (*s)["properties"]["robot"]["properties"]["width_m"]["maximum"] = 2;
            }).find("/robot/width_m: maximum none in C++, 2.0 in the schema"),
            std::string::npos);
  EXPECT_NE(drifted([](json* s) {
              (*s)["properties"]["robot"]["properties"]["vibration"]["properties"].erase("damping_ratio");
            }).find("/robot/vibration/damping_ratio: in the C++ table, missing in the schema"),
            std::string::npos);
  EXPECT_NE(drifted([](json* s) {
              (*s)["properties"]["robot"]["properties"]["tilt_deg"] = {{"type", "number"}, {"default", 0}};
            }).find("/robot/tilt_deg: in the schema, missing in the C++ table"),
            std::string::npos);
  const std::vector<OptionInfo> camera = CameraOptions::Table().List();
  json with_default = SceneSchema();
  with_default["properties"]["camera"]["properties"]["ffc_temperature_delta_k"]["default"] = 0.0;
  EXPECT_NE(
      Lines(Disagreements(with_default, "/camera", camera))
          .find("/camera/ffc_temperature_delta_k: optional in C++ (left out means 0.0) but the schema gives a default"),
      std::string::npos);
  EXPECT_NE(drifted([](json* s) {
              (*s)["properties"]["robot"]["properties"]["navigation"]["enum"].erase(2);
            }).find("/robot/navigation: string choices differ"),
            std::string::npos);
}

}  // namespace
}  // namespace hoilcd
