#include "scene_runs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "hoilcd/core/util/json_reader.h"
#include "hoilcd/core/util/random.h"
#include "hoilcd/core/util/sizes.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

using nlohmann::json;

// What one run cannot change: what the dataset states once (camera, frame rate, name), what makes
// the runs one sequence (seed, frames, runs) and the place itself (floor, room size); the time of
// day is the run's own key.
constexpr const char* kSharedByRuns[] = {"/name",   "/description",   "/generator",   "/seed",
                                         "/frames", "/frame_rate_hz", "/assets_dir",  "/runs",
                                         "/camera", "/floor",         "/room/size_m", "/room/sun/time_of_day_h"};

bool StartsWithPointer(const std::string& pointer, const std::string& prefix) {
  return pointer == prefix || (pointer.size() > prefix.size() && pointer.compare(0, prefix.size(), prefix) == 0 &&
                               pointer[prefix.size()] == '/');
}

// "day D HH:MM" of a time since the first run's day began; with `second_digits` >= 0, "day D
// HH:MM:SS" with that many decimals of the second.
std::string ClockText(double seconds_since_first_day, int second_digits = -1) {
  const double scale = second_digits < 0 ? 1.0 / 60.0 : std::pow(10.0, second_digits);
  const auto ticks = static_cast<int64_t>(std::floor(seconds_since_first_day * scale + 1e-9));
  const int64_t per_minute = second_digits < 0 ? 1 : 60 * static_cast<int64_t>(scale);
  const int64_t minutes = ticks / per_minute;
  const int64_t day = minutes / (24 * 60), hour = minutes / 60 % 24, minute = minutes % 60;
  char text[96];
  std::snprintf(text, sizeof text, "day %lld %02lld:%02lld", static_cast<long long>(day), static_cast<long long>(hour),
                static_cast<long long>(minute));
  if (second_digits < 0) return text;
  const double second = static_cast<double>(ticks % per_minute) / scale;
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, ":%0*.*f", second_digits > 0 ? second_digits + 3 : 2, second_digits, second);
  return text + std::string(seconds);
}

// Two times as ClockText writes them, to the minute unless that shows them equal, then to the
// second, then to the millisecond: an overlap is never reported as "starts at 09:00, before the
// other ends at 09:00".
std::pair<std::string, std::string> TwoClockTexts(double a_s, double b_s) {
  for (int digits : {-1, 0, 3}) {
    std::pair<std::string, std::string> texts{ClockText(a_s, digits), ClockText(b_s, digits)};
    if (texts.first != texts.second || digits == 3) return texts;
  }
  return {};
}

}  // namespace

std::string OverridePointer(const std::string& key) {
  if (!key.empty() && key.front() == '/') return key;
  std::string pointer = "/" + key;
  std::replace(pointer.begin(), pointer.end(), '.', '/');
  return pointer;
}

void ReadRuns(json* doc, const json& written, const std::vector<std::string>& overrides, Scene* s,
              ProblemCollector* problems) {
  if (!doc->contains("runs")) return;
  const std::string file = s->file;
  const json& runs = (*doc)["runs"];
  const double first_time_h = runs[0]["time_of_day_h"].get<double>();
  // The sun's time is the first run's (a dataset's scene.json says so); a scene may state it only
  // as that.
  const json::json_pointer sun_time("/room/sun/time_of_day_h");
  bool sun_time_given = written.contains(sun_time);
  for (const std::string& o : overrides) {
    sun_time_given =
        sun_time_given || StartsWithPointer(OverridePointer(o.substr(0, o.find('='))), sun_time.to_string());
  }
  if (sun_time_given && (*doc)[sun_time].get<double>() != first_time_h) {
    problems->Add(file + ": /room/sun/time_of_day_h", "is " + Fixed((*doc)[sun_time].get<double>(), 2) +
                                                          ", but a scene with runs takes each run's time of day "
                                                          "from /runs/N/time_of_day_h (the first run's is " +
                                                          Fixed(first_time_h, 2) + "); remove it");
  }
  (*doc)[sun_time] = first_time_h;
  s->room.sun.time_of_day_h = first_time_h;
  int64_t total_frames = 0;
  for (size_t k = 0; k < runs.size(); ++k) {
    const json& r = runs[k];
    const std::string at = file + ": /runs/" + std::to_string(k);
    RunSpec run;
    run.time_of_day_h = r["time_of_day_h"].get<double>();
    run.day = r["day"].get<int>();
    run.frames = r.contains("frames") ? r["frames"].get<int>() : s->frames;
    // The first run is the scene as it would render without runs; the others draw their own.
    constexpr uint64_t kJsonSafeInteger = (uint64_t{1} << 53) - 1;
    run.seed = r.contains("seed") ? r["seed"].get<uint64_t>()
               : k == 0           ? s->seed
                                  : HashCombine(s->seed, HashString("scene.run"), k) & kJsonSafeInteger;
    run.start_time_s = (run.day * 24.0 + run.time_of_day_h - first_time_h) * 3600.0;
    if (k == 0 && run.day != 0)
      problems->Add(at + "/day", "the first run's day is day 0 (days count from it); expected 0");
    if (k > 0) {
      const RunSpec& previous = s->runs.back();
      const double previous_end_s = previous.start_time_s + previous.frames / s->frame_rate_hz;
      if (run.start_time_s < previous_end_s) {
        const auto [start, end] =
            TwoClockTexts(run.start_time_s + first_time_h * 3600, previous_end_s + first_time_h * 3600);
        problems->Add(at + "/time_of_day_h",
                      "run " + std::to_string(k) + " starts at " + start + ", before run " + std::to_string(k - 1) +
                          " ends at " + end + "; expected a later time or day (/runs/" + std::to_string(k) + "/day)");
      }
    }
    if (r.contains("set")) {
      for (const auto& [key, value] : r["set"].items()) {
        // An override is applied as KEY=VALUE, split at the first '=': a key holding one would be
        // checked as one path and applied as another.
        if (key.find('=') != std::string::npos) {
          problems->Add(at + "/set/" + JsonPointerToken(key), "a scene path, which never holds '='");
          continue;
        }
        const std::string pointer = OverridePointer(key);
        std::string shared;
        for (const char* p : kSharedByRuns) {
          if (StartsWithPointer(pointer, p) || StartsWithPointer(p, pointer)) shared = p;
        }
        if (!shared.empty()) {
          problems->Add(at + "/set/" + key,
                        "sets " + shared + ", which is one for all runs" +
                            (shared == "/room/sun/time_of_day_h" ? " (use /runs/N/time_of_day_h)" : ""));
          continue;
        }
        run.overrides.push_back(key + "=" + value.dump());
      }
    }
    total_frames += run.frames;
    s->runs.push_back(std::move(run));
  }
  if (total_frames > kMaxFrames) {
    problems->Add(file + ": /runs", "the runs hold " + std::to_string(total_frames) +
                                        " frames in all; expected at most " + std::to_string(kMaxFrames));
  }
  s->frames = static_cast<int>(std::min<int64_t>(total_frames, kMaxFrames));
}

void CheckRunScenes(const Scene& s, ProblemCollector* problems) {
  for (size_t k = 0; k < s.runs.size(); ++k) {
    try {
      SceneOfRun(s, static_cast<int>(k));
    } catch (const InputError& e) {
      const InputError located = LocatedInRun(s, static_cast<int>(k), e);
      for (const Problem& p : located.problems()) problems->Add(p.where, p.message);
    }
  }
}

InputError LocatedInRun(const Scene& scene, int k, const InputError& error) {
  if (scene.runs.empty()) return error;
  std::vector<Problem> problems;
  for (const Problem& p : error.problems()) {
    problems.push_back({scene.file + ": /runs/" + std::to_string(k),
                        "its scene (the scene with /runs/" + std::to_string(k) + "/set applied): " + p.ToString()});
  }
  return InputError(std::move(problems));
}

Scene SceneOfRun(const Scene& scene, int k) {
  if (scene.runs.empty()) {
    HOILCD_CHECK_MSG(k == 0, "a scene without runs has run 0 only");
    return scene;
  }
  HOILCD_CHECK(k >= 0 && k < static_cast<int>(scene.runs.size()));
  const RunSpec& run = scene.runs[static_cast<size_t>(k)];
  json doc = scene.resolved;
  doc.erase("runs");
  doc["frames"] = run.frames;
  json& sun = doc["room"]["sun"];
  sun["time_of_day_h"] = run.time_of_day_h;
  sun["day_of_year"] = (sun["day_of_year"].get<int>() - 1 + run.day) % 365 + 1;
  Scene s = SceneFromJson(std::move(doc), scene.file, run.overrides);
  s.run_seed = run.seed;
  s.clock_offset_s = run.start_time_s;
  return s;
}

}  // namespace hoilcd
