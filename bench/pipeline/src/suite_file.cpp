#include "hoilcd/bench/pipeline/suite_file.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <set>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/json_reader.h"
#include "hoilcd/core/util/safe_text.h"
#include "hoilcd/core/util/sizes.h"
#include "hoilcd/sim/generate/generator.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

// The longest lists a suite file may hold: more is a mistake, and is refused before it is read.
constexpr size_t kMaxSequences = 10000;
constexpr size_t kMaxSeedsPerSequence = 10000;  // as sweep's --seeds
constexpr size_t kMaxSetsPerSequence = 256;     // as a scene's /runs/N/set

// False, with a problem at `pointer`, when `list` holds more than `max` items.
bool WithinCount(JsonReader* r, const nlohmann::json& list, const std::string& pointer, size_t max) {
  if (list.size() <= max) return true;
  r->Add(pointer, "holds " + std::to_string(list.size()) + " items; expected at most " + std::to_string(max));
  return false;
}

bool SafeName(const std::string& name) {
  if (name.empty() || name.size() > 100 || name[0] == '.') return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
  });
}

void ReadSequence(JsonReader* r, const nlohmann::json& j, const std::string& ptr, const fs::path& base,
                  SuiteSequence* s) {
  if (!r->ExpectObject(j, ptr)) return;
  r->CheckKeys(j, ptr, {"name", "scene", "generate", "seeds", "set", "split"});
  r->Read(j, ptr, "name", &s->name);
  if (j.contains("name") && j["name"].is_string() && !SafeName(s->name)) {
    r->Add(ptr + "/name",
           "expected 1-100 letters, digits, '.', '_' or '-' (not starting with '.'): it names the run folders");
  }
  const bool has_scene = j.contains("scene"), has_generate = j.contains("generate");
  if (has_scene == has_generate) {
    r->Add(ptr, "expected exactly one of \"scene\" (a scene file) and \"generate\" (a generator spec)");
  } else if (has_scene) {
    std::string scene;
    r->Read(j, ptr, "scene", &scene);
    if (j["scene"].is_string() && scene.empty()) r->Add(ptr + "/scene", "expected a scene file path, got \"\"");
    if (!scene.empty())
      s->scene_path = fs::path(scene).is_absolute() ? scene : (base / scene).lexically_normal().string();
  } else {
    const std::string gptr = ptr + "/generate";
    const nlohmann::json& g = j["generate"];
    s->generated = true;
    if (r->ExpectObject(g, gptr)) {
      r->CheckKeys(g, gptr, {"layout", "seed", "index"});
      r->Read(g, gptr, "layout", &s->layout);
      const std::vector<std::string>& families = LayoutFamilies();
      if (g.contains("layout") && g["layout"].is_string() && s->layout != "mixed" &&
          std::find(families.begin(), families.end(), s->layout) == families.end()) {
        std::string list;
        for (const std::string& f : families) list += f + ", ";
        r->Add(gptr + "/layout",
               "expected a layout family (" + list + "or mixed), got \"" + SafeText(s->layout) + "\"");
      }
      r->Read(g, gptr, "seed", &s->generator_seed);
      if (g.contains("seed") && g["seed"].is_number_unsigned() && s->generator_seed > kMaxSeed) {
        r->Add(gptr + "/seed", "expected a seed in [0, " + std::to_string(kMaxSeed) + "], got " + g["seed"].dump());
      }
      r->Read(g, gptr, "index", &s->generator_index);
      if (g.contains("index") && g["index"].is_number_integer() &&
          (s->generator_index < 0 || s->generator_index > kMaxGeneratedSceneIndex)) {
        r->Add(gptr + "/index", "expected a scene index in [0, " + std::to_string(kMaxGeneratedSceneIndex) + "], got " +
                                    g["index"].dump());
      }
    }
  }
  const std::string sptr = ptr + "/seeds";
  if (!j.contains("seeds")) {
    r->Add(sptr, "missing");
  } else if (r->ExpectArray(j["seeds"], sptr) && WithinCount(r, j["seeds"], sptr, kMaxSeedsPerSequence)) {
    if (j["seeds"].empty()) r->Add(sptr, "expected at least one seed");
    std::set<int> seen;
    for (size_t k = 0; k < j["seeds"].size(); ++k) {
      int seed = -1;
      r->ReadValue(j["seeds"][k], sptr + "/" + std::to_string(k), &seed);
      if (j["seeds"][k].is_number_integer() && seed < 0) {
        r->Add(sptr + "/" + std::to_string(k), "expected a non-negative seed");
      } else if (seed >= 0 && !seen.insert(seed).second) {
        r->Add(sptr + "/" + std::to_string(k), "seed " + std::to_string(seed) + " is listed twice");
      }
      if (seed >= 0) s->seeds.push_back(seed);
    }
  }
  if (j.contains("set") && r->ExpectArray(j["set"], ptr + "/set") &&
      WithinCount(r, j["set"], ptr + "/set", kMaxSetsPerSequence)) {
    for (size_t k = 0; k < j["set"].size(); ++k) {
      const std::string where = ptr + "/set/" + std::to_string(k);
      std::string set;
      r->ReadValue(j["set"][k], where, &set);
      if (!j["set"][k].is_string()) continue;
      const size_t eq = set.find('=');
      const std::string key = set.substr(0, eq);
      if (eq == std::string::npos || eq == 0) {
        r->Add(where, "expected \"key=value\", got \"" + SafeText(set) + "\"");
      } else if (key == "seed" || key == "/seed") {
        r->Add(where, "the seed is given by \"seeds\", not by \"set\"");
      } else {
        s->sets.push_back(set);
      }
    }
  }
  r->Read(j, ptr, "split", &s->split);
  if (j.contains("split") && j["split"].is_string() && s->split != "dev" && s->split != "test") {
    r->Add(ptr + "/split", "expected \"dev\" or \"test\", got \"" + SafeText(s->split) + "\"");
  }
}

}  // namespace

Suite ParseSuite(const std::string& text, const std::string& path) {
  JsonReader r(path);
  const nlohmann::json j = r.Parse(text);
  Suite suite;
  suite.path = path;
  if (r.ExpectObject(j, "")) {
    r.CheckKeys(j, "", {"name", "description", "sequences"});
    r.Read(j, "", "name", &suite.name);
    if (j.contains("description")) r.ReadValue(j["description"], "/description", &suite.description);
    if (!j.contains("sequences")) {
      r.Add("/sequences", "missing");
    } else if (r.ExpectArray(j["sequences"], "/sequences") &&
               WithinCount(&r, j["sequences"], "/sequences", kMaxSequences)) {
      if (j["sequences"].empty()) r.Add("/sequences", "expected at least one sequence");
      const fs::path base = fs::path(path).parent_path();
      std::set<std::string> names;
      for (size_t k = 0; k < j["sequences"].size(); ++k) {
        const std::string ptr = "/sequences/" + std::to_string(k);
        SuiteSequence s;
        ReadSequence(&r, j["sequences"][k], ptr, base, &s);
        if (!s.name.empty() && !names.insert(s.name).second)
          r.Add(ptr + "/name", "sequence name \"" + s.name + "\" is used twice");
        suite.sequences.push_back(s);
      }
    }
  }
  r.problems().ThrowIfAny();
  return suite;
}

Suite ReadSuite(const std::string& path) {
  std::string text;
  try {
    text = ReadFileBytes(path, 16u << 20);  // a suite lists sequences: megabytes are a mistake
  } catch (const InputError& e) {
    throw InputError(path, std::string("cannot read the suite file: ") + e.what());
  }
  return ParseSuite(text, path);
}

std::string SuiteRunName(const std::string& sequence, int64_t seed) {
  return sequence + "-seed" + std::to_string(seed);
}

std::vector<SuiteRunSpec> SuiteRuns(const Suite& suite, const std::string& split) {
  std::vector<SuiteRunSpec> runs;
  for (size_t k = 0; k < suite.sequences.size(); ++k) {
    const SuiteSequence& s = suite.sequences[k];
    if (split != "all" && s.split != split) continue;
    for (int seed : s.seeds) runs.push_back({k, seed, SuiteRunName(s.name, seed)});
  }
  std::sort(runs.begin(), runs.end(), [](const SuiteRunSpec& a, const SuiteRunSpec& b) { return a.name < b.name; });
  return runs;
}

}  // namespace hoilcd
