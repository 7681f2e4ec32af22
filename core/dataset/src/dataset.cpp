#include "hoilcd/core/dataset/dataset.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string_view>
#include <utility>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "hoilcd/core/dataset/frame_encoding.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/json_reader.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/png.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr const char* kVideoFile = "thermal.mp4";
constexpr const char* kPosesHeader =
    "frame,t,x,y,theta,cam_x,cam_y,cam_z,cam_yaw,cam_pitch,cam_roll,odo_x,odo_y,odo_theta";
constexpr int kPosesColumns = 14;
constexpr const char* kManifestChecksumKey = "manifest_checksum";

std::string JoinPath(const std::string& dir, const std::string& relative) {
  return (fs::path(dir) / relative).string();
}

bool IsSafeRelativePath(const std::string& relative) {
  const fs::path p(relative);
  if (relative.empty() || p.is_absolute()) return false;
  for (const fs::path& part : p) {
    if (part == "..") return false;
  }
  return true;
}

}  // namespace

int DatasetManifest::ClassId(const std::string& name) const {
  const auto it = classes.find(name);
  return it == classes.end() ? kNoClass : it->second;
}

std::string FrameFileName(int frame, const char* extension) {
  HOILCD_CHECK(frame >= 0 && extension != nullptr);
  char digits[16];
  std::snprintf(digits, sizeof(digits), "%06d", frame);
  std::string name = digits;
  if (extension[0] != '.') name += '.';
  return name + extension;
}

const std::vector<std::string>& DatasetOutputs::AllNames() {
  static const std::vector<std::string> kNames = {"thermal", "radiometric", "exr", "video", "persons"};
  return kNames;
}

bool DatasetOutputs::Has(const std::string& name) const {
  if (name == "thermal") return thermal;
  if (name == "radiometric") return radiometric;
  if (name == "exr") return exr;
  if (name == "video") return video;
  if (name == "persons") return persons;
  return false;
}

std::vector<std::string> DatasetOutputs::Names() const {
  std::vector<std::string> names;
  for (const std::string& name : AllNames()) {
    if (Has(name)) names.push_back(name);
  }
  return names;
}

std::string DatasetOutputs::ToText() const {
  std::string text;
  for (const std::string& name : Names()) text += (text.empty() ? "" : ",") + name;
  return text;
}

std::string DatasetOutputs::Parse(const std::string& text, DatasetOutputs* outputs) {
  DatasetOutputs parsed{false, false, false, false, false};
  bool* flags[] = {&parsed.thermal, &parsed.radiometric, &parsed.exr, &parsed.video, &parsed.persons};
  std::stringstream in(text);
  std::string name;
  bool any = false;
  while (std::getline(in, name, ',')) {
    const auto at = std::find(AllNames().begin(), AllNames().end(), name);
    if (at == AllNames().end()) {
      return "unknown output '" + name +
             "' (expected a comma-separated list of thermal, radiometric, exr, video, persons)";
    }
    bool* flag = flags[at - AllNames().begin()];
    if (*flag) return "output '" + name + "' is listed twice";
    *flag = true;
    any = true;
  }
  if (!any) return "expected at least one of thermal, radiometric, exr, video, persons";
  *outputs = parsed;
  return "";
}

std::string DatasetManifest::ToJson() const {
  json j;
  j["hoilcd_version"] = hoilcd_version;
  j["scene_hash"] = scene_hash;
  j["seed"] = seed;
  j["intrinsics"] = {{"width", intrinsics.width}, {"height", intrinsics.height}, {"fx", intrinsics.fx},
                     {"fy", intrinsics.fy},       {"cx", intrinsics.cx},         {"cy", intrinsics.cy}};
  j["frame_rate_hz"] = frame_rate_hz;
  j["frame_count"] = frame_count;
  j["window_min_c"] = window_min_c;
  j["window_max_c"] = window_max_c;
  j["classes"] = classes;
  j["files"] = files;
  j["outputs"] = outputs.Names();
  j["complete"] = complete;
  if (shard) {
    j["shard"] = {{"index", shard->shard.index},
                  {"count", shard->shard.count},
                  {"first_frame", shard->first_frame},
                  {"end_frame", shard->end_frame}};
  }
  j[kManifestChecksumKey] = ChecksumOf(j.dump(2));  // of the manifest without this key
  return j.dump(2) + "\n";
}

// 95 lines: one read and check per manifest key, in the file's order; a list, not steps.
DatasetManifest DatasetManifest::FromJson(const std::string& text, const std::string& path_for_errors) {
  JsonReader reader(path_for_errors);
  const json j = reader.Parse(text);
  DatasetManifest m;
  if (!reader.ExpectObject(j, "")) reader.problems().ThrowIfAny();
  reader.CheckKeys(
      j, "",
      {"hoilcd_version", "scene_hash", "seed", "intrinsics", "frame_rate_hz", "frame_count", "window_min_c",
       "window_max_c", "classes", "files", "outputs", "complete", "shard", kManifestChecksumKey});
  std::string checksum;
  reader.Read(j, "", kManifestChecksumKey, &checksum);
  if (!checksum.empty()) {
    json unsigned_part = j;
    unsigned_part.erase(kManifestChecksumKey);
    if (ChecksumOf(unsigned_part.dump(2)) != checksum) {
      reader.Add(std::string("/") + kManifestChecksumKey,
                 "does not match the manifest's content: manifest.json was edited or corrupted; "
                 "re-render the dataset");
    }
  }
  reader.Read(j, "", "hoilcd_version", &m.hoilcd_version);
  reader.Read(j, "", "scene_hash", &m.scene_hash);
  reader.Read(j, "", "seed", &m.seed);
  if (j.contains("intrinsics") && reader.ExpectObject(j["intrinsics"], "/intrinsics")) {
    const json& k = j["intrinsics"];
    reader.CheckKeys(k, "/intrinsics", {"width", "height", "fx", "fy", "cx", "cy"});
    reader.Read(k, "/intrinsics", "width", &m.intrinsics.width);
    reader.Read(k, "/intrinsics", "height", &m.intrinsics.height);
    reader.Read(k, "/intrinsics", "fx", &m.intrinsics.fx);
    reader.Read(k, "/intrinsics", "fy", &m.intrinsics.fy);
    reader.Read(k, "/intrinsics", "cx", &m.intrinsics.cx);
    reader.Read(k, "/intrinsics", "cy", &m.intrinsics.cy);
    const std::string problem = m.intrinsics.Check();
    if (!problem.empty()) reader.Add("/intrinsics", problem);
  } else if (!j.contains("intrinsics")) {
    reader.Add("/intrinsics", "missing");
  }
  reader.Read(j, "", "frame_rate_hz", &m.frame_rate_hz);
  if (!(m.frame_rate_hz > 0)) reader.Add("/frame_rate_hz", "must be positive");
  reader.Read(j, "", "frame_count", &m.frame_count);
  if (m.frame_count < 0) reader.Add("/frame_count", "must not be negative");
  reader.Read(j, "", "window_min_c", &m.window_min_c);
  reader.Read(j, "", "window_max_c", &m.window_max_c);
  if (!(m.window_max_c > m.window_min_c)) {
    reader.Add("/window_max_c", "must be greater than window_min_c");
  }
  if (j.contains("classes") && reader.ExpectObject(j["classes"], "/classes")) {
    for (const auto& item : j["classes"].items()) {
      int id = 0;
      reader.ReadValue(item.value(), "/classes/" + item.key(), &id);
      m.classes[item.key()] = id;
    }
  } else if (!j.contains("classes")) {
    reader.Add("/classes", "missing");
  }
  if (j.contains("files") && reader.ExpectObject(j["files"], "/files")) {
    for (const auto& item : j["files"].items()) {
      std::string checksum;
      reader.ReadValue(item.value(), "/files/" + item.key(), &checksum);
      if (!IsSafeRelativePath(item.key())) {
        reader.Add("/files/" + item.key(), "expected a relative path inside the dataset folder");
      }
      m.files[item.key()] = checksum;
    }
  } else if (!j.contains("files")) {
    reader.Add("/files", "missing");
  }
  // Datasets written before --outputs existed have no "outputs": every output.
  if (j.contains("outputs") && reader.ExpectArray(j["outputs"], "/outputs")) {
    std::string text;
    for (size_t i = 0; i < j["outputs"].size(); ++i) {
      std::string name;
      reader.ReadValue(j["outputs"][i], "/outputs/" + std::to_string(i), &name);
      text += (i == 0 ? "" : ",") + name;
    }
    const std::string problem = DatasetOutputs::Parse(text, &m.outputs);
    if (!problem.empty()) reader.Add("/outputs", problem);
  }
  reader.Read(j, "", "complete", &m.complete);
  if (j.contains("shard") && reader.ExpectObject(j["shard"], "/shard")) {
    DatasetShard s;
    reader.CheckKeys(j["shard"], "/shard", {"index", "count", "first_frame", "end_frame"});
    reader.Read(j["shard"], "/shard", "index", &s.shard.index);
    reader.Read(j["shard"], "/shard", "count", &s.shard.count);
    reader.Read(j["shard"], "/shard", "first_frame", &s.first_frame);
    reader.Read(j["shard"], "/shard", "end_frame", &s.end_frame);
    if (const std::string problem = s.shard.Check(); !problem.empty()) reader.Add("/shard", problem);
    if (!(0 <= s.first_frame && s.first_frame <= s.end_frame && s.end_frame <= m.frame_count)) {
      reader.Add("/shard", "expected 0 <= first_frame <= end_frame <= frame_count");
    }
    m.shard = s;
  }
  reader.problems().ThrowIfAny();
  return m;
}

int DatasetManifest::FramesWritten() const {
  const char* folder = outputs.thermal       ? "thermal/"
                       : outputs.radiometric ? "radiometric/"
                       : outputs.exr         ? "exr/"
                                             : nullptr;
  if (folder == nullptr) return frame_count;
  int count = 0;
  for (auto it = files.lower_bound(folder); it != files.end(); ++it) {
    if (it->first.rfind(folder, 0) != 0) break;
    ++count;
  }
  return count;
}

void WriteDatasetFile(const std::string& dir, const std::string& relative_path, std::string_view bytes,
                      DatasetManifest* manifest) {
  HOILCD_CHECK(manifest != nullptr);
  HOILCD_CHECK_MSG(IsSafeRelativePath(relative_path), relative_path);
  WriteFileAtomic(JoinPath(dir, relative_path), bytes);
  manifest->files[relative_path] = ChecksumOf(bytes);
}

namespace {

json FramePersonsToJson(const FramePersons& f) {
  json persons = json::array();
  for (const PersonRecord& p : f.persons) {
    json contacts = json::array();
    for (const ContactRecord& c : p.contacts) {
      contacts.push_back({{"name", c.name}, {"u_px", c.u_px}, {"v_px", c.v_px}, {"visible", c.visible}});
    }
    json person = {{"id", p.id},
                   {"box_px", {p.box_px.x, p.box_px.y, p.box_px.width, p.box_px.height}},
                   {"visible_fraction", p.visible_fraction},
                   {"occlusion_fraction", p.occlusion_fraction},
                   {"seated", p.seated},
                   {"posture", p.posture},
                   {"contacts", contacts}};
    if (!p.keypoints.empty()) {
      json keypoints = json::array();
      for (const KeypointRecord& k : p.keypoints) {
        keypoints.push_back({{"name", k.name},
                             {"world_m", {k.world_m[0], k.world_m[1], k.world_m[2]}},
                             {"u_px", k.u_px},
                             {"v_px", k.v_px},
                             {"visible", k.visible}});
      }
      person["keypoints"] = keypoints;
    }
    persons.push_back(person);
  }
  return {{"frame", f.frame}, {"persons", persons}};
}

}  // namespace

std::string PersonsToJson(const std::vector<FramePersons>& frames, int threads) {
  // The text of {"frames": [...]} dumped with indent 1, written frame by frame (in parallel):
  // each frame is dumped on its own and indented by its depth, 2 (JSON strings hold no raw
  // newline). The whole file was one JSON document in memory, the peak of a render.
  if (frames.empty()) return "{\n \"frames\": []\n}\n";
  std::vector<std::string> parts(frames.size());
  ParallelFor(static_cast<int64_t>(frames.size()), threads, [&](int64_t i) {
    const std::string text = FramePersonsToJson(frames[static_cast<size_t>(i)]).dump(1);
    std::string& out = parts[static_cast<size_t>(i)];
    out.reserve(text.size() + text.size() / 4);
    out += "  ";
    for (const char c : text) {
      out += c;
      if (c == '\n') out += "  ";
    }
  });
  size_t size = 0;
  for (const std::string& part : parts) size += part.size() + 2;
  std::string out;
  out.reserve(size + 32);
  out += "{\n \"frames\": [\n";
  for (size_t i = 0; i < parts.size(); ++i) {
    out += parts[i];
    out += i + 1 < parts.size() ? ",\n" : "\n";
    std::string().swap(parts[i]);
  }
  out += " ]\n}\n";
  return out;
}

namespace {

// One element of persons.json's "frames" array, at JSON pointer fp; problems go to reader.
FramePersons FramePersonsFromJson(const json& frame, const std::string& fp, JsonReader& reader) {
  reader.CheckKeys(frame, fp, {"frame", "persons"});
  FramePersons f;
  reader.Read(frame, fp, "frame", &f.frame);
  if (!frame.contains("persons")) reader.Add(fp + "/persons", "missing");
  if (frame.contains("persons") && reader.ExpectArray(frame["persons"], fp + "/persons")) {
    const json& jp = frame["persons"];
    for (size_t k = 0; k < jp.size(); ++k) {
      const std::string pp = fp + "/persons/" + std::to_string(k);
      if (!reader.ExpectObject(jp[k], pp)) continue;
      reader.CheckKeys(
          jp[k], pp,
          {"id", "box_px", "visible_fraction", "occlusion_fraction", "seated", "posture", "contacts", "keypoints"});
      PersonRecord p;
      reader.Read(jp[k], pp, "id", &p.id);
      const auto box = jp[k].find("box_px");
      if (box == jp[k].end()) {
        reader.Add(pp + "/box_px", "missing");
      } else if (!box->is_array() || box->size() != 4) {
        reader.Add(pp + "/box_px", "expected [x, y, width, height]");
      } else {
        reader.ReadValue((*box)[0], pp + "/box_px/0", &p.box_px.x);
        reader.ReadValue((*box)[1], pp + "/box_px/1", &p.box_px.y);
        reader.ReadValue((*box)[2], pp + "/box_px/2", &p.box_px.width);
        reader.ReadValue((*box)[3], pp + "/box_px/3", &p.box_px.height);
      }
      reader.Read(jp[k], pp, "visible_fraction", &p.visible_fraction);
      reader.Read(jp[k], pp, "occlusion_fraction", &p.occlusion_fraction);
      reader.Read(jp[k], pp, "seated", &p.seated);
      reader.Read(jp[k], pp, "posture", &p.posture);
      const auto contacts = jp[k].find("contacts");
      if (contacts == jp[k].end()) {
        reader.Add(pp + "/contacts", "missing");
      } else if (reader.ExpectArray(*contacts, pp + "/contacts")) {
        for (size_t c = 0; c < contacts->size(); ++c) {
          const std::string cp = pp + "/contacts/" + std::to_string(c);
          const json& jc = (*contacts)[c];
          if (!reader.ExpectObject(jc, cp)) continue;
          reader.CheckKeys(jc, cp, {"name", "u_px", "v_px", "visible"});
          ContactRecord contact;
          reader.Read(jc, cp, "name", &contact.name);
          reader.Read(jc, cp, "u_px", &contact.u_px);
          reader.Read(jc, cp, "v_px", &contact.v_px);
          reader.Read(jc, cp, "visible", &contact.visible);
          p.contacts.push_back(contact);
        }
      }
      const auto keypoints = jp[k].find("keypoints");
      if (keypoints != jp[k].end() && reader.ExpectArray(*keypoints, pp + "/keypoints")) {
        for (size_t c = 0; c < keypoints->size(); ++c) {
          const std::string kp = pp + "/keypoints/" + std::to_string(c);
          const json& jk = (*keypoints)[c];
          if (!reader.ExpectObject(jk, kp)) continue;
          reader.CheckKeys(jk, kp, {"name", "world_m", "u_px", "v_px", "visible"});
          KeypointRecord keypoint;
          reader.Read(jk, kp, "name", &keypoint.name);
          const auto world = jk.find("world_m");
          if (world == jk.end() || !world->is_array() || world->size() != 3) {
            reader.Add(kp + "/world_m", "expected [x, y, z] in metres");
          } else {
            for (int i = 0; i < 3; ++i) {
              reader.ReadValue((*world)[i], kp + "/world_m/" + std::to_string(i), &keypoint.world_m[i]);
            }
          }
          reader.Read(jk, kp, "u_px", &keypoint.u_px);
          reader.Read(jk, kp, "v_px", &keypoint.v_px);
          reader.Read(jk, kp, "visible", &keypoint.visible);
          p.keypoints.push_back(keypoint);
        }
      }
      f.persons.push_back(std::move(p));
    }
  }
  return f;
}

// Byte ranges of the elements of the "frames" array of a persons.json shaped as PersonsToJson
// writes it ({"frames": [...]} and nothing else), or nothing for any other text. Hand-written:
// it lets the elements be parsed in parallel, and JSON libraries give no element boundaries
// without building the whole document first.
std::optional<std::vector<std::pair<size_t, size_t>>> FrameElementRanges(const std::string& text) {
  size_t i = 0;
  auto skip_space = [&] {
    while (i < text.size() && (text[i] == ' ' || text[i] == '\n' || text[i] == '\r' || text[i] == '\t')) ++i;
  };
  auto expect = [&](std::string_view token) {
    skip_space();
    if (text.compare(i, token.size(), token) != 0) return false;
    i += token.size();
    return true;
  };
  if (!expect("{") || !expect("\"frames\"") || !expect(":") || !expect("[")) return std::nullopt;
  std::vector<std::pair<size_t, size_t>> ranges;
  skip_space();
  if (i < text.size() && text[i] == ']') {
    ++i;
  } else {
    for (;;) {
      skip_space();
      const size_t begin = i;
      int depth = 0;
      bool in_string = false;
      for (; i < text.size(); ++i) {
        const char c = text[i];
        if (in_string) {
          if (c == '\\')
            ++i;  // the escaped character
          else if (c == '"')
            in_string = false;
        } else if (c == '"') {
          in_string = true;
        } else if (c == '{' || c == '[') {
          ++depth;
        } else if (c == '}' || c == ']') {
          if (depth == 0) break;
          --depth;
        } else if (c == ',' && depth == 0) {
          break;
        }
      }
      if (i >= text.size() || in_string || depth != 0 || i == begin) return std::nullopt;
      ranges.emplace_back(begin, i);
      if (text[i++] == ']') break;
    }
  }
  if (!expect("}")) return std::nullopt;
  skip_space();
  if (i != text.size()) return std::nullopt;
  return ranges;
}

}  // namespace

std::vector<FramePersons> PersonsFromJson(const std::string& text, const std::string& path, int threads) {
  // Fast path, for well-formed files: the frames parsed and read in parallel. Anything amiss
  // falls through to reading the whole document, which names every problem.
  if (const auto ranges = FrameElementRanges(text)) {
    std::vector<FramePersons> frames(ranges->size());
    std::atomic<bool> failed{false};
    ParallelFor(static_cast<int64_t>(ranges->size()), threads, [&](int64_t k) {
      if (failed) return;
      const auto [begin, end] = (*ranges)[static_cast<size_t>(k)];
      const json frame = ParseJsonOrDiscarded(std::string_view(text).substr(begin, end - begin));
      JsonReader reader(path);
      if (frame.is_discarded() || !frame.is_object()) {
        failed = true;
        return;
      }
      frames[static_cast<size_t>(k)] = FramePersonsFromJson(frame, "/frames/" + std::to_string(k), reader);
      if (!reader.problems().empty()) failed = true;
    });
    if (!failed) return frames;
  }
  JsonReader reader(path);
  const json j = reader.Parse(text);
  std::vector<FramePersons> frames;
  if (!reader.ExpectObject(j, "")) reader.problems().ThrowIfAny();
  reader.CheckKeys(j, "", {"frames"});
  if (!j.contains("frames")) reader.Add("/frames", "missing");
  if (j.contains("frames") && reader.ExpectArray(j["frames"], "/frames")) {
    const json& jf = j["frames"];
    for (size_t i = 0; i < jf.size(); ++i) {
      const std::string fp = "/frames/" + std::to_string(i);
      if (!reader.ExpectObject(jf[i], fp)) continue;
      frames.push_back(FramePersonsFromJson(jf[i], fp, reader));
    }
  }
  reader.problems().ThrowIfAny();
  return frames;
}

std::string EventsToJson(const std::vector<DatasetEvent>& events) {
  json out = json::array();
  for (const DatasetEvent& e : events) {
    out.push_back({{"frame", e.frame}, {"type", e.type}, {"person", e.person}, {"seat", e.seat}, {"detail", e.detail}});
  }
  return json{{"events", out}}.dump(1) + "\n";
}

std::vector<DatasetEvent> EventsFromJson(const std::string& text, const std::string& path) {
  JsonReader reader(path);
  const json j = reader.Parse(text);
  std::vector<DatasetEvent> events;
  if (!reader.ExpectObject(j, "")) reader.problems().ThrowIfAny();
  reader.CheckKeys(j, "", {"events"});
  if (!j.contains("events")) reader.Add("/events", "missing");
  if (j.contains("events") && reader.ExpectArray(j["events"], "/events")) {
    const json& je = j["events"];
    for (size_t i = 0; i < je.size(); ++i) {
      const std::string ep = "/events/" + std::to_string(i);
      if (!reader.ExpectObject(je[i], ep)) continue;
      reader.CheckKeys(je[i], ep, {"frame", "type", "person", "seat", "detail"});
      DatasetEvent e;
      reader.Read(je[i], ep, "frame", &e.frame);
      reader.Read(je[i], ep, "type", &e.type);
      if (je[i].contains("type") && e.type != "arrive" && e.type != "leave" && e.type != "swap" && e.type != "ffc" &&
          e.type != "freeze") {
        reader.Add(ep + "/type", "expected one of arrive, leave, swap, ffc, freeze; got '" + e.type + "'");
      }
      reader.Read(je[i], ep, "person", &e.person);
      reader.Read(je[i], ep, "seat", &e.seat);
      reader.Read(je[i], ep, "detail", &e.detail);
      events.push_back(std::move(e));
    }
  }
  reader.problems().ThrowIfAny();
  return events;
}

std::string FootprintsToJson(const std::vector<FootprintRecord>& footprints) {
  json out = json::array();
  for (const FootprintRecord& f : footprints) {
    out.push_back({{"name", f.name},
                   {"kind", f.kind},
                   {"centre_m", f.centre_m},
                   {"half_size_m", f.half_size_m},
                   {"yaw_deg", f.yaw_deg},
                   {"radius_m", f.radius_m}});
  }
  return json{{"footprints", out}}.dump(1) + "\n";
}

namespace {
// A two-number array such as [x, y] (JsonReader reads scalars only).
void ReadPair(JsonReader& reader, const json& object, const std::string& pointer, const char* key,
              std::array<double, 2>* out) {
  const std::string where = pointer + "/" + key;
  if (!object.contains(key)) {
    reader.Add(where, "missing");
    return;
  }
  const json& v = object.at(key);
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) {
    reader.Add(where, "expected an array of 2 numbers");
    return;
  }
  *out = {v[0].get<double>(), v[1].get<double>()};
}
}  // namespace

std::vector<FootprintRecord> FootprintsFromJson(const std::string& text, const std::string& path) {
  JsonReader reader(path);
  const json j = reader.Parse(text);
  std::vector<FootprintRecord> footprints;
  if (!reader.ExpectObject(j, "")) reader.problems().ThrowIfAny();
  reader.CheckKeys(j, "", {"footprints"});
  if (!j.contains("footprints")) reader.Add("/footprints", "missing");
  if (j.contains("footprints") && reader.ExpectArray(j["footprints"], "/footprints")) {
    const json& jf = j["footprints"];
    for (size_t i = 0; i < jf.size(); ++i) {
      const std::string fp = "/footprints/" + std::to_string(i);
      if (!reader.ExpectObject(jf[i], fp)) continue;
      reader.CheckKeys(jf[i], fp, {"name", "kind", "centre_m", "half_size_m", "yaw_deg", "radius_m"});
      FootprintRecord f;
      reader.Read(jf[i], fp, "name", &f.name);
      reader.Read(jf[i], fp, "kind", &f.kind);
      if (jf[i].contains("kind") && f.kind != "rectangle" && f.kind != "circle") {
        reader.Add(fp + "/kind", "expected rectangle or circle; got '" + f.kind + "'");
      }
      ReadPair(reader, jf[i], fp, "centre_m", &f.centre_m);
      ReadPair(reader, jf[i], fp, "half_size_m", &f.half_size_m);
      reader.Read(jf[i], fp, "yaw_deg", &f.yaw_deg);
      reader.Read(jf[i], fp, "radius_m", &f.radius_m);
      if (f.half_size_m[0] < 0 || f.half_size_m[1] < 0) {
        reader.Add(fp + "/half_size_m", "expected sizes >= 0 m");
      }
      if (f.radius_m < 0) reader.Add(fp + "/radius_m", "expected a radius >= 0 m");
      footprints.push_back(std::move(f));
    }
  }
  reader.problems().ThrowIfAny();
  return footprints;
}

std::string PosesToCsv(const std::vector<PoseRecord>& poses) {
  std::string out = std::string(kPosesHeader) + "\n";
  for (const PoseRecord& p : poses) {
    out += std::to_string(p.frame);
    for (double v : {p.time_s, p.x_m, p.y_m, p.theta_rad, p.cam_x_m, p.cam_y_m, p.cam_z_m, p.cam_yaw_rad,
                     p.cam_pitch_rad, p.cam_roll_rad, p.odo_x_m, p.odo_y_m, p.odo_theta_rad}) {
      out += ',';
      out += ShortestDouble(v);
    }
    out += '\n';
  }
  return out;
}

std::vector<PoseRecord> PosesFromCsv(const std::string& text, const std::string& path) {
  static const std::array<const char*, kPosesColumns> kNames = {"frame",    "t",     "x",     "y",        "theta",
                                                                "cam_x",    "cam_y", "cam_z", "cam_yaw",  "cam_pitch",
                                                                "cam_roll", "odo_x", "odo_y", "odo_theta"};
  std::vector<PoseRecord> poses;
  ProblemCollector problems;
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string where = path + ":" + std::to_string(line_number);
    if (line_number == 1) {
      if (line != kPosesHeader) problems.Add(where, std::string("expected header ") + kPosesHeader);
      continue;
    }
    if (line.empty()) continue;
    std::vector<std::string> fields;
    std::stringstream row(line);
    std::string field;
    while (std::getline(row, field, ',')) fields.push_back(field);
    if (line.back() == ',') fields.emplace_back();
    if (static_cast<int>(fields.size()) != kPosesColumns) {
      problems.Add(where,
                   "expected " + std::to_string(kPosesColumns) + " columns, got " + std::to_string(fields.size()));
      continue;
    }
    PoseRecord p;
    double* const doubles[] = {&p.time_s,  &p.x_m,     &p.y_m,          &p.theta_rad,     &p.cam_x_m,
                               &p.cam_y_m, &p.cam_z_m, &p.cam_yaw_rad,  &p.cam_pitch_rad, &p.cam_roll_rad,
                               &p.odo_x_m, &p.odo_y_m, &p.odo_theta_rad};
    bool ok = true;
    for (int c = 0; c < kPosesColumns; ++c) {
      const std::string& s = fields[c];
      const char* end = s.data() + s.size();
      std::from_chars_result r{};
      double value = 0;
      if (c == 0)
        r = std::from_chars(s.data(), end, p.frame);
      else
        r = std::from_chars(s.data(), end, value);
      if (s.empty() || r.ec != std::errc() || r.ptr != end || (c > 0 && !std::isfinite(value))) {
        problems.Add(where, std::string("column ") + std::to_string(c + 1) + " '" + kNames[c] + "': expected " +
                                (c == 0 ? "an integer" : "a finite number") + ", got '" + s + "'");
        ok = false;
        continue;
      }
      if (c > 0) *doubles[c - 1] = value;
    }
    if (ok) poses.push_back(p);
  }
  if (line_number == 0) problems.Add(path + ":1", std::string("expected header ") + kPosesHeader);
  problems.ThrowIfAny();
  return poses;
}

CameraPose PoseRecord::Camera() const {
  CameraPose pose;
  pose.x_m = cam_x_m;
  pose.y_m = cam_y_m;
  pose.z_m = cam_z_m;
  pose.yaw_rad = cam_yaw_rad;
  pose.pitch_rad = cam_pitch_rad;
  pose.roll_rad = cam_roll_rad;
  return pose;
}

std::string PosesToTum(const std::vector<PoseRecord>& poses) {
  std::string out = "# timestamp tx ty tz qx qy qz qw (world_from_cam, OpenCV camera frame)\n";
  for (const PoseRecord& p : poses) {
    const Rigid3 world_from_cam = p.Camera().WorldFromCam();
    const Eigen::Quaterniond& q = world_from_cam.rotation;
    const Eigen::Vector3d& t = world_from_cam.translation;
    out += ShortestDouble(p.time_s);
    for (double v : {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()}) {
      out += ' ';
      out += ShortestDouble(v);
    }
    out += '\n';
  }
  return out;
}

namespace {
std::string ChecksumMismatch(const std::string& listed, const std::string& actual) {
  return "checksum mismatch (manifest.json says " + listed + ", file has " + actual +
         "): the file was changed or corrupted; re-render the dataset";
}

// Throws unless the manifest lists every side file and every frame of the outputs it names.
void CheckListedFiles(const DatasetManifest& m, const std::string& manifest_path) {
  ProblemCollector problems;
  for (const char* side : {"scene.json", "poses.csv", "persons.json", "events.json"}) {
    if (std::string(side) == "persons.json" && !m.outputs.persons) continue;
    if (!m.files.count(side)) problems.Add(manifest_path + ": /files", std::string("no ") + side);
  }
  // Bound the per-frame loop below by what is listed, not by frame_count alone.
  if (m.frame_count > m.FramesWritten()) {
    problems.Add(manifest_path + ": /frame_count", "is " + std::to_string(m.frame_count) + " but /files lists " +
                                                       std::to_string(m.FramesWritten()) + " " +
                                                       m.outputs.Names().front() + " frames");
    problems.ThrowIfAny();
  }
  for (int frame = 0; frame < m.frame_count; ++frame) {
    for (const char* folder : {"thermal/", "radiometric/"}) {
      if (!m.outputs.Has(std::string(folder).substr(0, std::string(folder).size() - 1))) continue;
      const std::string name = folder + FrameFileName(frame, "png");
      if (!m.files.count(name)) problems.Add(manifest_path + ": /files", "no " + name);
    }
  }
  problems.ThrowIfAny();
}

// Checksums every listed file on `threads` threads; throws on a missing or changed file, except
// the video (a preview of the frames), which only adds a warning.
void VerifyEveryFile(const std::string& dir, const DatasetManifest& m, int threads,
                     std::vector<std::string>* warnings) {
  const std::vector<std::pair<std::string, std::string>> listed(m.files.begin(), m.files.end());
  std::vector<std::string> errors(listed.size());
  ParallelFor(static_cast<int64_t>(listed.size()), threads, [&](int64_t i) {
    const std::string path = JoinPath(dir, listed[i].first);
    std::string actual;
    try {
      actual = ChecksumOfFile(path);
    } catch (const InputError&) {
      errors[i] = "listed in manifest.json but missing or unreadable";
      return;
    }
    if (actual != listed[i].second) errors[i] = ChecksumMismatch(listed[i].second, actual);
  });
  ProblemCollector problems;
  for (size_t i = 0; i < listed.size(); ++i) {
    if (errors[i].empty()) continue;
    if (listed[i].first == kVideoFile) {
      warnings->push_back(JoinPath(dir, listed[i].first) + ": " + errors[i] + "; the frames are read without it");
    } else {
      problems.Add(JoinPath(dir, listed[i].first), errors[i]);
    }
  }
  problems.ThrowIfAny();
}
}  // namespace

Dataset Dataset::Open(const std::string& dir, Verify verify, int threads) {
  Dataset ds;
  ds.dir_ = dir;
  ds.verify_ = verify;
  const std::string manifest_path = JoinPath(dir, "manifest.json");
  if (!fs::is_regular_file(manifest_path)) {
    throw InputError(manifest_path,
                     "no manifest.json: not a hoilcd dataset folder (write one with "
                     "hoilcd render SCENE -o DIR)");
  }
  ds.manifest_ = DatasetManifest::FromJson(ReadFileBytes(manifest_path), manifest_path);
  const DatasetManifest& m = ds.manifest_;
  if (m.shard) {
    throw InputError(dir, "is shard " + m.shard->shard.Name() + " of a sequence (frames " +
                              std::to_string(m.shard->first_frame) + " to " + std::to_string(m.shard->end_frame - 1) +
                              " of " + std::to_string(m.frame_count) +
                              "), not a dataset; join the shards with hoilcd merge DIR... -o DIR");
  }
  if (!m.complete) {
    throw InputError(dir, "dataset is partial: " + std::to_string(m.FramesWritten()) + " of " +
                              std::to_string(m.frame_count) + " frames; re-run hoilcd render to finish it");
  }

  CheckListedFiles(m, manifest_path);
  if (m.outputs.video && !m.files.count(kVideoFile)) {
    ds.warnings_.push_back(JoinPath(dir, kVideoFile) + ": not listed in manifest.json; the frames are read without it");
  }
  if (verify == Verify::kEveryFile) VerifyEveryFile(dir, m, threads, &ds.warnings_);

  const std::string poses_path = JoinPath(dir, "poses.csv");
  ds.poses_ = PosesFromCsv(ds.ReadFile("poses.csv"), poses_path);
  bool frames_in_order = static_cast<int>(ds.poses_.size()) == m.frame_count;
  for (size_t i = 0; frames_in_order && i < ds.poses_.size(); ++i) {
    frames_in_order = ds.poses_[i].frame == static_cast<int>(i);
  }
  if (!frames_in_order) {
    throw InputError(poses_path,
                     "expected one row per frame, frames 0 to " + std::to_string(m.frame_count - 1) + " in order");
  }
  const std::string persons_path = JoinPath(dir, "persons.json");
  if (m.outputs.persons) ds.persons_ = PersonsFromJson(ds.ReadFile("persons.json"), persons_path, threads);
  for (const FramePersons& f : ds.persons_) {
    if (f.frame < 0 || f.frame >= m.frame_count) {
      throw InputError(persons_path,
                       "frame " + std::to_string(f.frame) + " outside 0.." + std::to_string(m.frame_count - 1));
    }
  }
  const std::string events_path = JoinPath(dir, "events.json");
  ds.events_ = EventsFromJson(ds.ReadFile("events.json"), events_path);
  for (const DatasetEvent& e : ds.events_) {
    if (e.frame < 0 || e.frame >= m.frame_count) {
      throw InputError(events_path,
                       "frame " + std::to_string(e.frame) + " outside 0.." + std::to_string(m.frame_count - 1));
    }
  }
  if (m.files.count("footprints.json")) {  // absent from datasets written before it existed
    const std::string footprints_path = JoinPath(dir, "footprints.json");
    ds.footprints_ = FootprintsFromJson(ds.ReadFile("footprints.json"), footprints_path);
  }
  ds.runs_ = m.files.count("runs.json")
                 ? RunsFromJson(ds.ReadFile("runs.json"), JoinPath(dir, "runs.json"), m.frame_count)
                 : SingleRun(m.frame_count);
  const std::vector<int> run_of_frame = RunOfFrames(ds.runs_);
  for (PoseRecord& p : ds.poses_) p.run = run_of_frame[static_cast<size_t>(p.frame)];
  return ds;
}

cv::Mat DecodeFramePng(const std::string& bytes, const std::string& path, int expected_type,
                       const CameraIntrinsics& k) {
  uint32_t width = 0;
  uint32_t height = 0;
  // Read before decoding, so that a small file that inflates to a huge image is refused first.
  if (!PngSize(bytes, &width, &height)) throw InputError(path, "cannot read PNG (not a PNG)");
  if (width != static_cast<uint32_t>(k.width) || height != static_cast<uint32_t>(k.height)) {
    throw InputError(path, "expected " + std::to_string(k.width) + "x" + std::to_string(k.height) +
                               " px as in manifest.json, the PNG is " + std::to_string(width) + "x" +
                               std::to_string(height));
  }
  cv::Mat image;  // the dataset's own frames take the fast path; any other PNG goes to OpenCV
  if (DecodeGreyPng(bytes, k.width, k.height, expected_type, &image)) return image;
  image = cv::imdecode(std::vector<uchar>(bytes.begin(), bytes.end()), cv::IMREAD_UNCHANGED);
  if (image.empty()) throw InputError(path, "cannot read PNG (damaged)");
  if (image.type() != expected_type) {
    throw InputError(path, expected_type == CV_8UC1 ? "expected an 8-bit single-channel PNG"
                                                    : "expected a 16-bit single-channel PNG");
  }
  if (image.cols != k.width || image.rows != k.height) {
    throw InputError(
        path, "expected " + std::to_string(k.width) + "x" + std::to_string(k.height) + " px as in manifest.json");
  }
  return image;
}

std::string Dataset::ReadFile(const std::string& name) const {
  const std::string path = JoinPath(dir_, name);
  if (verify_ != Verify::kOnRead) return ReadFileBytes(path);
  const auto listed = manifest_.files.find(name);
  if (listed == manifest_.files.end()) {
    throw InputError(path, "not listed in manifest.json, so its checksum cannot be checked");
  }
  std::string bytes = ReadFileBytes(path);
  const std::string actual = ChecksumOf(bytes);
  if (actual != listed->second) throw InputError(path, ChecksumMismatch(listed->second, actual));
  return bytes;
}

void Dataset::RequireOutput(const std::string& output, const std::string& needed_for) const {
  if (manifest_.outputs.Has(output)) return;
  throw InputError(dir_, "has no " + output + " output, which " + needed_for +
                             " needs: it was rendered with --outputs " + manifest_.outputs.ToText() +
                             "; render it again with " + output + " among --outputs");
}

const std::vector<FramePersons>& Dataset::persons() const {
  RequireOutput("persons", "the people ground truth (persons.json)");
  return persons_;
}

cv::Mat Dataset::FramePng(const std::string& output, int frame, int type, const std::string& needed_for) const {
  RequireOutput(output, needed_for);
  HOILCD_CHECK_MSG(frame >= 0 && frame < num_frames(), "frame " << frame);
  const std::string name = output + "/" + FrameFileName(frame, "png");
  return DecodeFramePng(ReadFile(name), JoinPath(dir_, name), type, manifest_.intrinsics);
}

cv::Mat Dataset::Thermal(int frame) const {
  return FramePng("thermal", frame, CV_8UC1, "reading the 8-bit thermal frames");
}

cv::Mat Dataset::RadiometricCentikelvin(int frame) const {
  return FramePng("radiometric", frame, CV_16UC1, "reading the radiometric frames");
}

cv::Mat Dataset::RadiometricC(int frame) const { return CelsiusFromCentikelvin16(RadiometricCentikelvin(frame)); }

std::string Dataset::scene_json() const { return ReadFile("scene.json"); }

}  // namespace hoilcd
