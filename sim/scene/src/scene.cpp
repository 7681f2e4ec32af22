#include "hoilcd/sim/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validator.hpp>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/json_reader.h"
#include "hoilcd/core/util/text.h"
#include "hoilcd/sim/assets/asset.h"
#include "hoilcd/sim/scene/camera_profiles.h"
#include "scene_runs.h"
#include "scene_schema_text.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const valijson::Schema& CompiledSchema() {
  static const std::unique_ptr<valijson::Schema> schema = [] {
    auto s = std::make_unique<valijson::Schema>();
    valijson::SchemaParser parser;
    valijson::adapters::NlohmannJsonAdapter adapter(SceneSchema());
    parser.populateSchema(adapter, *s);
    return s;
  }();
  return *schema;
}

// valijson context ["<root>", "[room]", "[size_m]", "[0]"] -> JSON pointer "/room/size_m/0".
std::string ContextToPointer(const std::vector<std::string>& context) {
  std::string pointer;
  for (const std::string& part : context) {
    if (part == "<root>") continue;
    std::string key = part;
    if (key.size() >= 2 && key.front() == '[' && key.back() == ']') key = key.substr(1, key.size() - 2);
    pointer += "/" + json::json_pointer::string_t(key);
  }
  return pointer.empty() ? "/" : pointer;
}

// The schema node that describes a JSON pointer inside a document (null when unknown).
const json* SchemaAt(const std::string& pointer) {
  const json* node = &SceneSchema();
  std::stringstream ss(pointer);
  std::string part;
  std::getline(ss, part, '/');
  while (std::getline(ss, part, '/')) {
    if (node->contains("properties") && (*node)["properties"].contains(part)) {
      node = &(*node)["properties"][part];
    } else if (node->contains("items")) {
      node = &(*node)["items"];
    } else {
      return nullptr;
    }
  }
  return node;
}

// Rewrites valijson's messages into "what was expected" phrasing where we can say it better.
std::string Describe(const std::string& pointer, const std::string& description) {
  const std::string marker = "constraints: '";
  const size_t at = description.find(marker);
  if (at != std::string::npos) {
    const std::string key = description.substr(at + marker.size(), description.size() - at - marker.size() - 2);
    std::string expected;
    if (const json* node = SchemaAt(pointer); node && node->contains("properties")) {
      for (const auto& [name, _] : (*node)["properties"].items()) {
        expected += (expected.empty() ? "" : ", ") + name;
      }
    }
    return "unknown key '" + key + "'" + (expected.empty() ? "" : " (expected one of: " + expected + ")");
  }
  std::string out = description;
  const json* node = SchemaAt(pointer);
  if (node && node->contains("enum") && description.find("enum") != std::string::npos) {
    std::string names;
    for (const json& name : (*node)["enum"]) names += (names.empty() ? "" : ", ") + name.get<std::string>();
    out = "expected one of: " + names;
  }
  if (description.find("'type' constraint") != std::string::npos && node && node->contains("type")) {
    static const std::map<std::string, std::string> kExpected = {{"number", "a number"}, {"integer", "a whole number"},
                                                                 {"string", "a string"}, {"boolean", "true or false"},
                                                                 {"array", "an array"},  {"object", "an object"}};
    const std::string type = (*node)["type"].is_string() ? (*node)["type"].get<std::string>() : "";
    if (kExpected.count(type)) out = "expected " + kExpected.at(type);
  }
  if (node && node->contains("description")) {
    out += " (" + (*node)["description"].get<std::string>() + ")";
  }
  return out;
}

// Numbers the schema calls "number" are stored as floating point, so 25 and 25.0 resolve (and
// hash) the same.
void NormaliseNumbers(json* doc, const json& schema) {
  if (schema.value("type", "") == "number" && doc->is_number()) *doc = doc->get<double>();
  if (doc->is_object() && schema.contains("properties")) {
    for (const auto& [key, sub] : schema["properties"].items()) {
      if (doc->contains(key)) NormaliseNumbers(&(*doc)[key], sub);
    }
  } else if (doc->is_array() && schema.contains("items") && schema["items"].is_object()) {
    for (json& item : *doc) NormaliseNumbers(&item, schema["items"]);
  }
}

// The schema's "required" properties, checked on the document as written: FillDefaults would
// otherwise supply them (a table without center_m would silently stand at the default).
void CheckRequired(const json& doc, const json& schema, const std::string& pointer, const std::string& file,
                   ProblemCollector* problems) {
  if (doc.is_object()) {
    if (schema.contains("required")) {
      for (const json& key : schema["required"]) {
        if (!doc.contains(key.get<std::string>())) {
          problems->Add(file + ": " + (pointer.empty() ? "/" : pointer),
                        "missing required property '" + key.get<std::string>() + "'");
        }
      }
    }
    if (schema.contains("properties")) {
      for (const auto& [key, sub] : schema["properties"].items()) {
        if (doc.contains(key)) CheckRequired(doc[key], sub, pointer + "/" + key, file, problems);
      }
    }
  } else if (doc.is_array() && schema.contains("items") && schema["items"].is_object()) {
    for (size_t i = 0; i < doc.size(); ++i) {
      CheckRequired(doc[i], schema["items"], pointer + "/" + std::to_string(i), file, problems);
    }
  }
}

// Lists longer than the schema's maxItems (objects with more keys than its maxProperties), checked
// first: 10^5 tables would otherwise be copied, filled with defaults and validated one by one.
void CheckListLengths(const json& doc, const json& schema, const std::string& pointer, const std::string& file,
                      ProblemCollector* problems) {
  const char* bound = doc.is_array() ? "maxItems" : doc.is_object() ? "maxProperties" : nullptr;
  if (bound != nullptr && schema.contains(bound) && doc.size() > schema[bound].get<size_t>()) {
    problems->Add(file + ": " + (pointer.empty() ? "/" : pointer), "holds " + std::to_string(doc.size()) +
                                                                       (doc.is_array() ? " items" : " keys") +
                                                                       "; expected at most " + schema[bound].dump());
    return;
  }
  if (doc.is_object() && schema.contains("properties")) {
    for (const auto& [key, sub] : schema["properties"].items()) {
      if (doc.contains(key)) CheckListLengths(doc[key], sub, pointer + "/" + key, file, problems);
    }
  } else if (doc.is_array() && schema.contains("items") && schema["items"].is_object()) {
    for (size_t i = 0; i < doc.size(); ++i) {
      CheckListLengths(doc[i], schema["items"], pointer + "/" + std::to_string(i), file, problems);
    }
  }
}

// The schema's integer bounds, compared as integers: valijson compares through a double, which
// rounds 2^53 + 1 down to a maximum of 2^53 and lets it through.
void CheckIntegerBounds(const json& doc, const json& schema, const std::string& pointer, const std::string& file,
                        ProblemCollector* problems) {
  if (doc.is_number_integer() && schema.value("type", "") == "integer") {
    // A long double holds every 64-bit integer exactly.
    const auto exact = [](const json& v) {
      return v.is_number_unsigned() ? static_cast<long double>(v.get<uint64_t>())
                                    : static_cast<long double>(v.get<int64_t>());
    };
    const auto beyond = [&](const json& bound, bool above) {
      if (!bound.is_number_integer()) return false;
      return above ? exact(doc) > exact(bound) : exact(doc) < exact(bound);
    };
    const std::string at = file + ": " + (pointer.empty() ? "/" : pointer);
    if (schema.contains("maximum") && beyond(schema["maximum"], true)) {
      problems->Add(at, "expected at most " + schema["maximum"].dump() + ", got " + doc.dump());
    }
    if (schema.contains("minimum") && beyond(schema["minimum"], false)) {
      problems->Add(at, "expected at least " + schema["minimum"].dump() + ", got " + doc.dump());
    }
  }
  if (doc.is_object() && schema.contains("properties")) {
    for (const auto& [key, sub] : schema["properties"].items()) {
      if (doc.contains(key)) CheckIntegerBounds(doc[key], sub, pointer + "/" + key, file, problems);
    }
  } else if (doc.is_array() && schema.contains("items") && schema["items"].is_object()) {
    for (size_t i = 0; i < doc.size(); ++i) {
      CheckIntegerBounds(doc[i], schema["items"], pointer + "/" + std::to_string(i), file, problems);
    }
  }
}

void FillDefaults(json* doc, const json& schema) {
  if (doc->is_object() && schema.contains("properties")) {
    for (const auto& [key, sub] : schema["properties"].items()) {
      if (!doc->contains(key) && sub.contains("default")) (*doc)[key] = sub["default"];
      if (doc->contains(key)) FillDefaults(&(*doc)[key], sub);
    }
  } else if (doc->is_array() && schema.contains("items") && schema["items"].is_object()) {
    for (json& item : *doc) FillDefaults(&item, schema["items"]);
  }
}

// Asset names stay names; a relative .gltf/.glb path is relative to the scene file's folder.
std::string ResolveAssetRef(const std::string& ref, const fs::path& scene_dir) {
  const std::string ext = fs::path(ref).extension().string();
  if ((ext != ".gltf" && ext != ".glb") || fs::path(ref).is_absolute()) return ref;
  return (scene_dir / ref).lexically_normal().string();
}

Eigen::Vector2d Vec2(const json& j) { return {j.at(0).get<double>(), j.at(1).get<double>()}; }
Eigen::Vector3d Vec3(const json& j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }

// Tables inside the room; seating names existing tables and seats they have.
void CheckTables(const Scene& scene, ProblemCollector* problems) {
  const std::string& f = scene.file;
  for (size_t i = 0; i < scene.tables.size(); ++i) {
    const Eigen::Vector2d& c = scene.tables[i].center_m;
    if (c.x() < 0 || c.y() < 0 || c.x() > scene.room.size_m.x() || c.y() > scene.room.size_m.y()) {
      problems->Add(f + ": /tables/" + std::to_string(i) + "/center_m",
                    "a position inside the room (x in [0, " + std::to_string(scene.room.size_m.x()) + "], y in [0, " +
                        std::to_string(scene.room.size_m.y()) + "])");
    }
  }
  for (size_t i = 0; i < scene.crowd.seating.size(); ++i) {
    const SeatingSpec& seating = scene.crowd.seating[i];
    if (seating.table >= static_cast<int>(scene.tables.size())) {
      problems->Add(f + ": /crowd/seating/" + std::to_string(i) + "/table",
                    "a table index below " + std::to_string(scene.tables.size()));
      continue;
    }
    const std::vector<int> seats = SeatsOf(scene.tables[static_cast<size_t>(seating.table)], 3);
    if (std::find(seats.begin(), seats.end(), seating.seat) == seats.end()) {
      problems->Add(f + ": /crowd/seating/" + std::to_string(i) + "/seat",
                    "a seat table " + std::to_string(seating.table) + " has (" +
                        (seats.empty() ? std::string("it has none") : "0.." + std::to_string(seats.back())) + ")");
    }
  }
}

// Windows fit along their wall below the ceiling; doors sit on a wall (within 1 cm) with the
// whole opening along it.
void CheckOpenings(const Scene& scene, ProblemCollector* problems) {
  const std::string& f = scene.file;
  for (size_t i = 0; i < scene.room.windows.size(); ++i) {
    const WindowSpec& w = scene.room.windows[i];
    const double wall_length = (w.wall == "north" || w.wall == "south") ? scene.room.size_m.x() : scene.room.size_m.y();
    const std::string at = f + ": /room/windows/" + std::to_string(i);
    if (w.center_m - 0.5 * w.width_m < 0 || w.center_m + 0.5 * w.width_m > wall_length) {
      problems->Add(at + "/center_m",
                    "the window to fit along its wall (length " + std::to_string(wall_length) + " m)");
    }
    if (w.bottom_m + w.height_m > scene.room.size_m.z()) {
      problems->Add(at + "/height_m", "the window top below the ceiling");
    }
  }
  const double size_x = scene.room.size_m.x(), size_y = scene.room.size_m.y();
  for (size_t i = 0; i < scene.room.doors.size(); ++i) {
    const DoorSpec& d = scene.room.doors[i];
    const std::string at = f + ": /room/doors/" + std::to_string(i);
    const double x = d.position_m.x(), y = d.position_m.y();
    constexpr double kOnWallM = 0.01;
    const bool in_x = x >= -kOnWallM && x <= size_x + kOnWallM, in_y = y >= -kOnWallM && y <= size_y + kOnWallM;
    const bool on_x_wall = in_y && (std::abs(x) <= kOnWallM || std::abs(x - size_x) <= kOnWallM);  // west, east
    const bool on_y_wall = in_x && (std::abs(y) <= kOnWallM || std::abs(y - size_y) <= kOnWallM);  // south, north
    if (!on_x_wall && !on_y_wall) {
      problems->Add(at + "/position_m", "a point on one of the room's walls (x = 0 or " + ShortestDouble(size_x) +
                                            ", or y = 0 or " + ShortestDouble(size_y) + ", within 1 cm); got (" +
                                            ShortestDouble(x) + ", " + ShortestDouble(y) + ")");
      continue;
    }
    const double along = on_x_wall ? y : x, length = on_x_wall ? size_y : size_x;
    if (along - 0.5 * d.width_m < 0 || along + 0.5 * d.width_m > length) {
      problems->Add(at + "/width_m", "the doorway (" + ShortestDouble(d.width_m) + " m wide, centred " +
                                         ShortestDouble(along) + " m along its wall) to fit along its wall (length " +
                                         ShortestDouble(length) + " m) without reaching a corner");
    }
  }
}

// Objects, standing people and waypoints inside the room; the assets named exist.
void CheckPlacements(const Scene& scene, ProblemCollector* problems) {
  const std::string& f = scene.file;
  auto inside_room = [&](const Eigen::Vector3d& p) {
    return p.x() >= 0 && p.y() >= 0 && p.z() >= 0 && p.x() <= scene.room.size_m.x() && p.y() <= scene.room.size_m.y() &&
           p.z() <= scene.room.size_m.z();
  };
  const std::string room_box = "x in [0, " + std::to_string(scene.room.size_m.x()) + "], y in [0, " +
                               std::to_string(scene.room.size_m.y()) + "], z in [0, " +
                               std::to_string(scene.room.size_m.z()) + "]";
  const json& objects = scene.resolved.at("objects");
  const AssetLibrary assets(scene.assets_dir);
  for (size_t i = 0; i < objects.size(); ++i) {
    const std::string at = f + ": /objects/" + std::to_string(i);
    if (!inside_room(Vec3(objects[i].at("position_m")))) {
      problems->Add(at + "/position_m", "a position inside the room (" + room_box + ")");
    }
    const std::string path = assets.Resolve(objects[i].at("asset").get<std::string>());
    std::error_code ec;
    if (objects[i].at("enabled").get<bool>() && !fs::is_regular_file(path, ec)) {
      problems->Add(at + "/asset",
                    "an asset name in " + scene.assets_dir + " or a .gltf/.glb file; " + path + " does not exist");
    }
  }
  for (const char* key : {"table_asset", "chair_asset"}) {
    const std::string path = assets.Resolve(scene.resolved.at("furniture").at(key).get<std::string>());
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
      problems->Add(f + ": /furniture/" + key,
                    "an asset name in " + scene.assets_dir + " or a .gltf/.glb file; " + path + " does not exist");
    }
  }
  for (size_t i = 0; i < scene.tables.size(); ++i) {
    if (scene.tables[i].asset.empty()) continue;
    const std::string path = assets.Resolve(scene.tables[i].asset);
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
      problems->Add(f + ": /tables/" + std::to_string(i) + "/asset",
                    "an asset name in " + scene.assets_dir + " or a .gltf/.glb file; " + path + " does not exist");
    }
  }
  const std::vector<StandingSpec>& standing = scene.crowd.standing;
  for (size_t i = 0; i < standing.size(); ++i) {
    const Eigen::Vector2d& p = standing[i].position_m;
    if (!inside_room({p.x(), p.y(), 0})) {
      problems->Add(f + ": /crowd/standing/" + std::to_string(i) + "/position_m",
                    "a position inside the room (" + room_box + ")");
    }
  }
  const std::vector<Eigen::Vector2d>& waypoints = scene.route.waypoints_m;
  for (size_t i = 0; i < waypoints.size(); ++i) {
    const Eigen::Vector2d& p = waypoints[i];
    if (p.x() < 0 || p.y() < 0 || p.x() > scene.room.size_m.x() || p.y() > scene.room.size_m.y()) {
      problems->Add(f + ": /route/waypoints_m/" + std::to_string(i), "a waypoint inside the room");
    }
  }
}

// Cross-field checks the schema cannot express.
void CheckConsistency(const Scene& scene, ProblemCollector* problems) {
  CheckTables(scene, problems);
  CheckOpenings(scene, problems);
  CheckPlacements(scene, problems);
  CheckFloorPlan(scene.floor, scene.room.size_m, scene.route.waypoints_m, scene.file, problems);
}

// The camera profile the scene names once the overrides are applied ("" when none).
std::string NamedCameraProfile(json doc, const std::vector<std::string>& overrides) {
  FillDefaults(&doc, SceneSchema());
  for (const std::string& o : overrides) ApplyOverride(&doc, o);
  const json::json_pointer at("/camera/profile");
  if (!doc.is_object() || !doc["camera"].is_object() || !doc.contains(at) || !doc[at].is_string()) return "";
  return doc[at].get<std::string>();
}

bool DistractorEnabled(const json& distractors, const std::string& asset) {
  const std::string name = fs::path(asset).stem().string();
  for (const char* cls : {"cup", "laptop", "monitor", "radiator"}) {
    if (name.rfind(cls, 0) == 0) return distractors.at(std::string(cls) + "s").get<bool>();
  }
  return true;
}

}  // namespace

const json& SceneSchema() {
  static const json schema = json::parse(SceneSchemaText());
  return schema;
}

const std::string& SceneSchemaText() {
  static const std::string text(kSceneSchemaText);
  return text;
}

void ApplyOverride(json* doc, const std::string& key_equals_value) {
  const std::string where = "--set " + key_equals_value;
  const size_t eq = key_equals_value.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError(where, "expected KEY=VALUE");
  const std::string key = OverridePointer(key_equals_value.substr(0, eq));
  const std::string value_text = key_equals_value.substr(eq + 1);
  // Text that is not JSON is a string; JSON nested too deep or with a repeated key is refused.
  json value;
  try {
    value = ParseJson(value_text, where);
  } catch (const JsonSyntaxError&) {
    value = value_text;
  }
  try {
    const json::json_pointer pointer(key);
    // Arrays may be indexed only within their size ("-" appends), at every level of the path.
    json::json_pointer prefix;
    const json* node = doc;
    std::stringstream tokens(key.substr(1));
    std::string token;
    while (std::getline(tokens, token, '/')) {
      // Past the end of the document a numeric token would create an array of that size.
      if ((node == nullptr || node->is_null()) && !token.empty() &&
          (token == "-" || token.find_first_not_of("0123456789") == std::string::npos)) {
        throw InputError(where, "an existing array at " + (prefix.empty() ? "/" : prefix.to_string()) +
                                    " to index with '" + token + "'");
      }
      if (node && node->is_array() && token != "-") {
        if (token.empty() || token.size() > 9 || token.find_first_not_of("0123456789") != std::string::npos ||
            std::stoul(token) >= node->size()) {
          throw InputError(where, "an index below " + std::to_string(node->size()) + " at " +
                                      (prefix.empty() ? "/" : prefix.to_string()));
        }
      }
      prefix /= token;
      node = node && doc->contains(prefix) ? &(*doc)[prefix] : nullptr;
    }
    (*doc)[pointer] = value;
  } catch (const json::exception& e) {
    throw InputError(where, std::string("a valid path into the scene (") + e.what() + ")");
  }
}

std::vector<Problem> ValidateScene(const json& doc, const std::string& file) {
  valijson::Validator validator;
  valijson::ValidationResults results;
  valijson::adapters::NlohmannJsonAdapter target(doc);
  validator.validate(CompiledSchema(), target, &results);
  std::vector<std::pair<std::string, std::string>> errors;
  valijson::ValidationResults::Error error;
  while (results.popError(error)) {
    errors.emplace_back(ContextToPointer(error.context), error.description);
  }
  // valijson also reports each failing ancestor ("Failed to validate against schema associated
  // with property name 'room'"); keep only the deepest messages, which say what was expected.
  // The pointers in order, so that whether one has a deeper one is a search, not a scan of every
  // error (a list of 10^5 bad items gives 10^5 errors).
  std::set<std::string> pointers;
  for (const auto& error_at : errors) pointers.insert(error_at.first);
  std::vector<Problem> problems;
  for (const auto& [pointer, description] : errors) {
    const std::string below = pointer == "/" ? "/" : pointer + "/";
    auto deeper = pointers.lower_bound(below);
    if (deeper != pointers.end() && *deeper == pointer) ++deeper;  // the root is its own "below"
    const bool has_deeper = deeper != pointers.end() && deeper->compare(0, below.size(), below) == 0;
    const bool generic = description.rfind("Failed to validate", 0) == 0;
    if (has_deeper && generic) continue;
    if (generic && errors.size() > 1) continue;
    problems.push_back({file + ": " + pointer, Describe(pointer, description)});
  }
  // What valijson let through, and only that: a value it refused is reported once.
  ProblemCollector integers;
  CheckIntegerBounds(doc, SceneSchema(), "", file, &integers);
  for (const Problem& p : integers.problems()) {
    if (pointers.count(p.where.substr(file.size() + 2)) == 0) problems.push_back(p);
  }
  std::sort(problems.begin(), problems.end(), [](const Problem& a, const Problem& b) { return a.where < b.where; });
  problems.erase(
      std::unique(problems.begin(), problems.end(),
                  [](const Problem& a, const Problem& b) { return a.where == b.where && a.message == b.message; }),
      problems.end());
  return problems;
}

void FillSceneDefaults(json* doc) {
  FillDefaults(doc, SceneSchema());
  NormaliseNumbers(doc, SceneSchema());
}

// One element of /tables; fields the scene leaves out keep their meaning without being written
// into the resolved scene (the schema gives them no default, so older scenes resolve as before).
TableSpec ReadTable(const json& t) {
  static const std::map<std::string, std::pair<SeatArrangement, int>> kArrangements = {
      {"both_sides", {SeatArrangement::kBothSides, 0}},
      {"one_side", {SeatArrangement::kOneSide, 2}},
      {"around", {SeatArrangement::kAround, 4}},
      {"sofa", {SeatArrangement::kSofa, 3}},
      {"none", {SeatArrangement::kNone, 0}}};
  TableSpec spec;
  spec.center_m = Vec2(t["center_m"]);
  spec.yaw_deg = t["yaw_deg"].get<double>();
  spec.asset = t.value("asset", "");
  const auto& [seats, default_count] = kArrangements.at(t.value("seats", "both_sides"));
  spec.seats = seats;
  spec.seat_count = seats == SeatArrangement::kBothSides || seats == SeatArrangement::kNone
                        ? 0
                        : t.value("seat_count", default_count);
  return spec;
}

// Makes the scene's asset paths absolute in the document (relative to the scene file, so a
// dataset's scene.json, written elsewhere, still finds the same assets); sets s->assets_dir.
void ResolveAssetPaths(const std::string& file, json* doc_in, Scene* s) {
  json& doc = *doc_in;
  const fs::path scene_dir = fs::absolute(fs::path(file)).parent_path();
  std::string assets_dir = doc["assets_dir"].get<std::string>();
  if (!assets_dir.empty()) {
    assets_dir = (scene_dir / assets_dir).lexically_normal().string();
    doc["assets_dir"] = assets_dir;
  }
  s->assets_dir = assets_dir.empty() ? ShippedAssetDir() : assets_dir;
  for (const char* key : {"table_asset", "chair_asset"}) {
    doc["furniture"][key] = ResolveAssetRef(doc["furniture"][key].get<std::string>(), scene_dir);
  }
  for (json& t : doc["tables"]) {
    if (t.contains("asset")) t["asset"] = ResolveAssetRef(t["asset"].get<std::string>(), scene_dir);
  }
  for (json& o : doc["objects"]) o["asset"] = ResolveAssetRef(o["asset"].get<std::string>(), scene_dir);
}

// The room (with its windows and doors), tables, furniture and objects, each read by its option
// table or the schema's shape; writes the default doors into the document when it has none.
void ReadRoomAndFurniture(const std::string& file, json* doc_in, Scene* s_out, ProblemCollector* consistency_out) {
  json& doc = *doc_in;
  Scene& s = *s_out;
  ProblemCollector& consistency = *consistency_out;
  const fs::path scene_dir = fs::absolute(fs::path(file)).parent_path();
  RoomOptions::Table().Read(doc["room"], file + ": /room", &s.room, &consistency);
  s.room.size_m = Vec3(doc["room"]["size_m"]);
  s.room.windows.clear();
  for (size_t i = 0; i < doc["room"]["windows"].size(); ++i) {
    WindowSpec w;
    WindowSpec::Table().Read(doc["room"]["windows"][i], file + ": /room/windows/" + std::to_string(i), &w,
                             &consistency);
    s.room.windows.push_back(w);
  }
  // No doors given: a 0.9 m door in the middle of each end wall (west and east, as a seminar
  // room's front and back doors), written into the resolved scene so the dataset's scene.json
  // names the doors walkers used.
  if (doc["room"]["doors"].empty()) {
    const double mid_y = 0.5 * s.room.size_m.y();
    doc["room"]["doors"] = json::array({{{"position_m", {0.0, mid_y}}, {"width_m", 0.9}},
                                        {{"position_m", {s.room.size_m.x(), mid_y}}, {"width_m", 0.9}}});
  }
  for (const json& d : doc["room"]["doors"])
    s.room.doors.push_back({Vec2(d["position_m"]), d["width_m"].get<double>()});
  s.floor = ReadFloorPlan(doc.contains("floor") ? doc["floor"] : json());
  for (const json& t : doc["tables"]) s.tables.push_back(ReadTable(t));
  FurnitureOptions::Table().Read(doc["furniture"], file + ": /furniture", &s.furniture, &consistency);

  for (const json& o : doc["objects"]) {
    ObjectSpec spec{ResolveAssetRef(o["asset"].get<std::string>(), scene_dir), Vec3(o["position_m"]),
                    o["yaw_deg"].get<double>(), o["temperature_offset_c"].get<double>(), o["enabled"].get<bool>()};
    if (spec.enabled && DistractorEnabled(doc["distractors"], spec.asset)) s.objects.push_back(spec);
  }
}

// The camera, robot, route, odometry and crowd, each read by its option table.
void ReadCameraRobotAndCrowd(const std::string& file, const json& doc, Scene* s_out,
                             ProblemCollector* consistency_out) {
  Scene& s = *s_out;
  ProblemCollector& consistency = *consistency_out;
  CameraOptions::Table().Read(doc["camera"], file + ": /camera", &s.camera, &consistency);
  s.camera.sensor.reflected_temperature_c = s.room.environment_temperature_c;
  TricycleOptions::Table().Read(doc["robot"], file + ": /robot", &s.robot, &consistency);
  RouteOptions::Table().Read(doc["route"], file + ": /route", &s.route, &consistency);
  s.route.waypoints_m.clear();
  for (const json& p : doc["route"]["waypoints_m"]) s.route.waypoints_m.push_back(Vec2(p));
  s.route.frames = s.frames;
  OdometryErrorOptions::Table().Read(doc["odometry"], file + ": /odometry", &s.odometry, &consistency);
  CrowdOptions::Table().Read(doc["crowd"], file + ": /crowd", &s.crowd, &consistency);
  for (const json& p : doc["crowd"]["seating"]) {
    s.crowd.seating.push_back({p["table"].get<int>(), p["seat"].get<int>(), p["posture"].get<std::string>()});
  }
  for (const json& p : doc["crowd"]["standing"])
    s.crowd.standing.push_back({Vec2(p["position_m"]), p["yaw_deg"].get<double>()});
}

// Every module's values checked by its option table, each problem at its pointer.
void CheckOptionTables(const std::string& file, const Scene& s, ProblemCollector* consistency_out) {
  ProblemCollector& consistency = *consistency_out;
  RoomOptions::Table().Check(s.room, file + ": /room", &consistency);
  for (size_t i = 0; i < s.room.windows.size(); ++i) {
    WindowSpec::Table().Check(s.room.windows[i], file + ": /room/windows/" + std::to_string(i), &consistency);
  }
  FurnitureOptions::Table().Check(s.furniture, file + ": /furniture", &consistency);
  CameraOptions::Table().Check(s.camera, file + ": /camera", &consistency);
  TricycleOptions::Table().Check(s.robot, file + ": /robot", &consistency);
  RouteOptions::Table().Check(s.route, file + ": /route", &consistency);
  OdometryErrorOptions::Table().Check(s.odometry, file + ": /odometry", &consistency);
  CrowdOptions::Table().Check(s.crowd, file + ": /crowd", &consistency);
}

Scene SceneFromJson(json doc, const std::string& file, const std::vector<std::string>& overrides) {
  if (!doc.is_object()) throw InputError(file + ": /", "a JSON object (the scene)");
  ProblemCollector problems;
  CheckListLengths(doc, SceneSchema(), "", file, &problems);
  problems.ThrowIfAny();
  CheckRequired(doc, SceneSchema(), "", file, &problems);
  // The camera profile's values go in where the scene leaves them out, before the schema's
  // defaults, so an explicit value or an override wins over the profile and the profile over the
  // defaults. Defaults first, so an override of one element of a default array
  // (objects.0.enabled) changes that element instead of replacing the whole array; the profile
  // again after the overrides, for fields an override of a whole object left out.
  const json written = doc;
  const std::string profile = NamedCameraProfile(doc, overrides);
  FillCameraProfile(&doc, profile);
  FillDefaults(&doc, SceneSchema());
  for (const std::string& o : overrides) ApplyOverride(&doc, o);
  FillCameraProfile(&doc, profile);
  for (Problem& p : ValidateScene(doc, file)) problems.Add(p.where, p.message);
  problems.ThrowIfAny();
  FillSceneDefaults(&doc);

  Scene s;
  s.file = file;
  s.name = doc["name"].get<std::string>();
  s.seed = doc["seed"].get<uint64_t>();
  s.frames = doc["frames"].get<int>();
  s.frame_rate_hz = doc["frame_rate_hz"].get<double>();

  ResolveAssetPaths(file, &doc, &s);

  // The module options, each read and checked by its option table (every problem at its pointer).
  ProblemCollector consistency;
  ReadRoomAndFurniture(file, &doc, &s, &consistency);
  ReadCameraRobotAndCrowd(file, doc, &s, &consistency);
  CheckOptionTables(file, s, &consistency);
  s.run_seed = s.seed;
  ReadRuns(&doc, written, overrides, &s, &consistency);
  s.resolved = doc;
  s.hash = ChecksumOf(doc.dump());
  if (profile != NamedCameraProfile(written, {})) s.warnings = CameraProfileOverrides(written, doc, profile, file);

  CheckConsistency(s, &consistency);
  consistency.ThrowIfAny();
  CheckRunScenes(s, &consistency);
  consistency.ThrowIfAny();
  return s;
}

std::vector<int> SeatsOf(const TableSpec& table, int per_side) {
  std::vector<int> seats;
  if (table.seats == SeatArrangement::kBothSides) {
    for (int side = 0; side < 2; ++side)
      for (int k = 0; k < per_side; ++k) seats.push_back(side * 3 + k);
  } else {
    for (int k = 0; k < table.seat_count; ++k) seats.push_back(k);
  }
  return seats;
}

InputError LocatedInScene(const Scene& scene, const InputError& error) {
  std::vector<Problem> problems = error.problems();
  for (Problem& p : problems) {
    if (!p.where.empty() && p.where.find(':') == std::string::npos && p.where.front() != '/') {
      p.where = scene.file + ": /" + p.where;
    }
  }
  return InputError(std::move(problems));
}

Scene LoadScene(const std::string& path, const std::vector<std::string>& overrides) {
  // A folder, FIFO or device is refused by name; a scene of every list at its longest is ~10 MB.
  constexpr uint64_t kMaxSceneBytes = uint64_t{64} << 20;
  return SceneFromJson(ParseJson(ReadFileBytes(path, kMaxSceneBytes), path), path, overrides);
}

}  // namespace hoilcd
