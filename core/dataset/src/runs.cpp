#include "hoilcd/core/dataset/runs.h"

#include <nlohmann/json.hpp>

#include "hoilcd/core/util/json_reader.h"

namespace hoilcd {

using json = nlohmann::json;

std::string RunsToJson(const std::vector<RunRecord>& runs) {
  json out = json::array();
  for (const RunRecord& r : runs) {
    out.push_back({{"first_frame", r.first_frame},
                   {"frames", r.frames},
                   {"time_of_day_h", r.time_of_day_h},
                   {"day", r.day},
                   {"start_time_s", r.start_time_s},
                   {"seed", r.seed}});
  }
  return json{{"runs", out}}.dump(1) + "\n";
}

std::vector<RunRecord> RunsFromJson(const std::string& text, const std::string& path, int frame_count) {
  JsonReader reader(path);
  const json j = reader.Parse(text);
  std::vector<RunRecord> runs;
  if (!reader.ExpectObject(j, "")) reader.problems().ThrowIfAny();
  reader.CheckKeys(j, "", {"runs"});
  if (!j.contains("runs")) reader.Add("/runs", "missing");
  if (j.contains("runs") && reader.ExpectArray(j["runs"], "/runs")) {
    const json& jr = j["runs"];
    if (jr.empty()) reader.Add("/runs", "expected at least one run");
    for (size_t i = 0; i < jr.size(); ++i) {
      const std::string rp = "/runs/" + std::to_string(i);
      if (!reader.ExpectObject(jr[i], rp)) continue;
      reader.CheckKeys(jr[i], rp, {"first_frame", "frames", "time_of_day_h", "day", "start_time_s", "seed"});
      RunRecord r;
      reader.Read(jr[i], rp, "first_frame", &r.first_frame);
      reader.Read(jr[i], rp, "frames", &r.frames);
      reader.Read(jr[i], rp, "time_of_day_h", &r.time_of_day_h);
      reader.Read(jr[i], rp, "day", &r.day);
      reader.Read(jr[i], rp, "start_time_s", &r.start_time_s);
      reader.Read(jr[i], rp, "seed", &r.seed);
      const int expected_first = runs.empty() ? 0 : runs.back().end_frame();
      if (r.first_frame != expected_first) {
        reader.Add(rp + "/first_frame", "expected " + std::to_string(expected_first) +
                                            " (runs follow each other from frame 0), got " +
                                            std::to_string(r.first_frame));
      }
      if (r.frames < 1) reader.Add(rp + "/frames", "expected at least 1 frame");
      if (r.day < 0) reader.Add(rp + "/day", "expected a day >= 0");
      if (!(r.time_of_day_h == -1 || (r.time_of_day_h >= 0 && r.time_of_day_h < 24))) {
        reader.Add(rp + "/time_of_day_h", "expected an hour in [0, 24), or -1 (not stated)");
      }
      if (!runs.empty() && !(r.start_time_s > runs.back().start_time_s)) {
        reader.Add(rp + "/start_time_s", "expected a start after the previous run's");
      }
      runs.push_back(r);
    }
    if (!runs.empty() && runs.back().end_frame() != frame_count) {
      reader.Add("/runs", "the runs end at frame " + std::to_string(runs.back().end_frame()) + ", expected " +
                              std::to_string(frame_count) + " (the manifest's frame_count)");
    }
  }
  reader.problems().ThrowIfAny();
  return runs;
}

std::vector<RunRecord> SingleRun(int frame_count) {
  RunRecord r;
  r.frames = frame_count;
  return {r};
}

std::vector<int> RunOfFrames(const std::vector<RunRecord>& runs) {
  std::vector<int> out;
  for (size_t k = 0; k < runs.size(); ++k)
    out.insert(out.end(), static_cast<size_t>(runs[k].frames), static_cast<int>(k));
  return out;
}

}  // namespace hoilcd
