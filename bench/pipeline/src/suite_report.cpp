#include "hoilcd/bench/pipeline/suite_report.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>

#include "hoilcd/bench/evaluation/json_number.h"
#include "hoilcd/bench/evaluation/report_json.h"
#include "hoilcd/bench/pipeline/shard.h"
#include "hoilcd/bench/pipeline/suite_file.h"
#include "hoilcd/bench/report/html_report.h"
#include "hoilcd/bench/report/output_folder.h"
#include "hoilcd/core/dataset/dataset_folder.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/folder_lock.h"
#include "hoilcd/core/util/json_reader.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

// A suite.json lists its runs and their errors: far below this; more is not a suite's.
constexpr uint64_t kMaxMarkerBytes = 64u << 20;

const OutputMarker kSuiteFolder{"suite.json", {"suite", "runs"}, "suite"};
const OutputMarker kSuiteReport{"suite_report.json", {"suite", "runs", "methods", "failed"}, "suite report"};

// `value` as compact JSON of at most 80 characters.
std::string Shown(const nlohmann::json& value) {
  const std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return text.size() <= 80 ? text : text.substr(0, 77) + "...";
}

// How two suite identities differ, e.g. `/split is "dev" there and "all" here`: the first of the
// top-level keys that differs, in the order a user sets them (so a changed split is named, not the
// run list it changes), down to the first difference inside it, short of a trailing array index
// (or the "-" of an append).
std::string IdentityDifference(const nlohmann::json& there, const nlohmann::json& here) {
  for (const char* key : {"split", "bench", "name", "description", "sequences", "runs"}) {
    const nlohmann::json a = there.value(key, nlohmann::json()), b = here.value(key, nlohmann::json());
    if (a == b) continue;
    nlohmann::json::json_pointer at("/" + std::string(key) + JsonFirstDifference(a, b));
    while (!at.parent_pointer().empty() &&
           (at.back() == "-" || at.back().find_first_not_of("0123456789") == std::string::npos)) {
      at = at.parent_pointer();
    }
    const auto value = [&](const nlohmann::json& j) { return j.contains(at) ? Shown(j.at(at)) : "absent"; };
    return at.to_string() + " is " + value(there) + " there and " + value(here) + " here";
  }
  return JsonFirstDifference(there, here);
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

// What a suite's identity (SuiteIdentity) says the report needs.
struct IdentityView {
  std::string name, description, split;
  nlohmann::json bench;
  std::vector<std::string> methods, runs;
  std::map<std::string, std::string> sequence_of_run;  // run name -> its sequence's name
};

IdentityView ViewIdentity(const nlohmann::json& identity, const std::string& source) {
  try {
    IdentityView v;
    v.name = identity.at("name").get<std::string>();
    v.description = identity.at("description").get<std::string>();
    v.split = identity.at("split").get<std::string>();
    v.bench = identity.at("bench");
    v.methods = v.bench.at("methods").get<std::vector<std::string>>();
    v.runs = identity.at("runs").get<std::vector<std::string>>();
    for (const nlohmann::json& seq : identity.at("sequences")) {
      const std::string name = seq.at("name").get<std::string>();
      for (const nlohmann::json& seed : seq.at("seeds"))
        v.sequence_of_run[SuiteRunName(name, seed.get<int64_t>())] = name;
    }
    return v;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(source, std::string("malformed suite identity (") + e.what() + ")");
  }
}

// One output folder of a suite, as its suite.json describes it.
struct ShardFolder {
  std::string dir, marker_path;
  nlohmann::json identity;
  Shard shard;
  std::vector<std::string> runs;              // the shard's runs, in run order
  std::map<std::string, std::string> failed;  // run -> its error
  bool finished = false;
};

ShardFolder ReadShardFolder(const std::string& dir) {
  ShardFolder f;
  f.dir = dir;
  f.marker_path = dir + "/suite.json";
  std::string text;
  try {
    text = ReadFileBytes(f.marker_path, kMaxMarkerBytes);
  } catch (const InputError& e) {
    throw InputError(
        dir, std::string("holds no suite: expected the suite.json that `hoilcd suite -o` writes (") + e.what() + ")");
  }
  const nlohmann::json marker = JsonReader(f.marker_path).Parse(text);
  for (const char* key : {"identity", "shard", "runs", "failed", "finished"}) {
    if (!marker.is_object() || !marker.contains(key)) {
      throw InputError(f.marker_path, std::string("has no \"") + key +
                                          "\": expected the suite.json of a suite or shard (an older hoilcd's "
                                          "cannot be merged: run that suite or shard again, which keeps its runs)");
    }
  }
  if (!marker.at("identity").is_object()) throw InputError(f.marker_path, "/identity: expected an object");
  try {
    f.identity = marker.at("identity");
    f.shard = {marker.at("shard").at("index").get<int>(), marker.at("shard").at("count").get<int>()};
    f.runs = marker.at("runs").get<std::vector<std::string>>();
    for (const nlohmann::json& r : marker.at("failed"))
      f.failed[r.at("run").get<std::string>()] = r.at("error").get<std::string>();
    f.finished = marker.at("finished").get<bool>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(f.marker_path, std::string("malformed suite.json (") + e.what() + ")");
  }
  if (const std::string problem = f.shard.Check(); !problem.empty())
    throw InputError(f.marker_path, "/shard: " + problem);
  return f;
}

// Why the run in run_dir is not a finished run of this suite ("" when it is): its report and the
// record that says what made it, for this run and these bench settings.
std::string WhyUnfinished(const std::string& run_dir, const std::string& run, const nlohmann::json& bench) {
  std::error_code ec;
  if (!fs::is_regular_file(run_dir + "/report.json", ec)) return "no report.json in " + run_dir;
  nlohmann::json record;
  try {
    record = ParseJsonOrDiscarded(ReadFileBytes(run_dir + "/suite_run.json", kMaxMarkerBytes));
  } catch (const InputError&) {
    record = nullptr;
  }
  if (!record.is_object()) return "no readable suite_run.json beside " + run_dir + "/report.json";
  const nlohmann::json sequence = record.value("sequence", nlohmann::json()),
                       seed = record.value("seed", nlohmann::json());
  if (!sequence.is_string() || !seed.is_number_integer() ||
      SuiteRunName(sequence.get<std::string>(), seed.get<int64_t>()) != run) {
    return run_dir + "/suite_run.json records another run";
  }
  if (record.value("bench", nlohmann::json()) != bench) {
    return run_dir + "/suite_run.json records other bench settings (at " +
           JsonFirstDifference(bench, record.value("bench", nlohmann::json())) + ")";
  }
  return "";
}

}  // namespace

SuiteRunResult ReadSuiteRunResult(const std::string& name, const std::string& report_path,
                                  const std::vector<std::string>& methods) {
  const nlohmann::json report = ReadReportJson(report_path);
  SuiteRunResult result;
  result.name = name;
  for (const std::string& m : methods) {
    if (!report.at("methods").contains(m)) throw InputError(report_path, "has no results of method " + m);
    const nlohmann::json& method = report.at("methods").at(m);
    result.mrr[m] = JsonNumberOrNan(method, "mrr");
    result.recall_at_1[m] = JsonNumberOrNan(method, "recall_at_1");
  }
  return result;
}

SuiteSummary MergeSuite(const std::vector<std::string>& dirs, const nlohmann::json* expected_identity) {
  if (dirs.empty()) throw InputError("--merge", "no suite output folders given");
  nlohmann::json identity = expected_identity ? *expected_identity : nlohmann::json();
  std::string identity_source = "the suite file and flags given to the merge";
  std::vector<ShardFolder> shards;
  for (const std::string& dir : dirs) {
    ShardFolder f = ReadShardFolder(dir);
    if (identity.is_null()) {
      identity = f.identity;
      identity_source = f.marker_path;
    } else if (f.identity != identity) {
      throw InputError(dir, "ran another suite than " + identity_source + ": " +
                                IdentityDifference(identity, f.identity) +
                                " (the shards of one suite are run with the same suite file, --split and bench flags)");
    }
    shards.push_back(std::move(f));
  }
  const IdentityView view = ViewIdentity(identity, identity_source);

  // Every shard of one split exactly once, each holding its part of the runs.
  std::vector<Problem> problems;
  const ShardFolder& first = shards.front();
  std::map<int, const ShardFolder*> by_index;
  for (const ShardFolder& f : shards) {
    if (f.shard.count != first.shard.count) {
      problems.push_back({f.dir, "is shard " + f.shard.Name() + " but " + first.dir + " is shard " +
                                     first.shard.Name() + ": the shards of one merge split the runs the same way"});
      continue;
    }
    const auto [it, inserted] = by_index.emplace(f.shard.index, &f);
    if (!inserted) {
      problems.push_back(
          {f.dir, "is shard " + f.shard.Name() + ", as " + it->second->dir + " is: give each shard once"});
      continue;
    }
    if (f.runs != ShardOf(view.runs, f.shard)) {
      problems.push_back({f.marker_path, "its runs (" + JoinNames(f.runs) + ") are not shard " + f.shard.Name() +
                                             " of the suite's (" + JoinNames(ShardOf(view.runs, f.shard)) + ")"});
    }
  }
  if (problems.empty()) {
    for (int index = 0; index < first.shard.count; ++index) {
      const Shard shard{index, first.shard.count};
      if (!by_index.count(index)) {
        problems.push_back({"--merge", "shard " + shard.Name() + " is missing (its runs: " +
                                           JoinNames(ShardOf(view.runs, shard)) + "): give its folder too"});
      }
    }
  }
  // Every run of a shard finished or recorded as failed.
  std::map<std::string, const ShardFolder*> owner;
  for (const auto& [index, f] : by_index) {
    for (const std::string& run : f->runs) {
      owner[run] = f;
      if (f->failed.count(run)) continue;
      const std::string why = WhyUnfinished(f->dir + "/runs/" + run, run, view.bench);
      if (!why.empty()) {
        problems.push_back(
            {f->dir, "shard " + f->shard.Name() + " has no finished run " + run + " (" + why + "); " +
                         (f->finished ? "its suite.json says it finished: run the shard again"
                                      : "the shard did not finish: run it again, it keeps its finished runs")});
      }
    }
  }
  if (!problems.empty()) throw InputError(problems);

  std::vector<SuiteRunResult> results;
  std::map<std::string, std::string> run_dirs;
  for (const std::string& run : view.runs) {
    const ShardFolder& f = *owner.at(run);
    const auto failed = f.failed.find(run);
    if (failed != f.failed.end()) {
      results.push_back({run, failed->second, {}, {}, ""});
    } else {
      results.push_back(ReadSuiteRunResult(run, f.dir + "/runs/" + run + "/report.json", view.methods));
      run_dirs[run] = f.dir + "/runs/" + run;
    }
    const auto sequence = view.sequence_of_run.find(run);
    if (sequence != view.sequence_of_run.end()) results.back().sequence = sequence->second;
  }
  SuiteSummary summary = SummariseSuite(view.name, view.description, view.methods, results);
  summary.settings = {{"split", view.split}, {"bench", view.bench}};
  summary.run_dirs = std::move(run_dirs);
  return summary;
}

void CheckSuiteReportFolder(const std::string& out_dir) {
  std::error_code ec;
  if (!fs::exists(out_dir, ec)) return;
  if (!fs::is_directory(out_dir, ec)) throw InputError(out_dir, "is a file: expected a folder for the suite's report");
  if (IsEarlierOutput(out_dir, kSuiteFolder) || IsEarlierOutput(out_dir, kSuiteReport)) return;
  std::vector<std::string> taken;
  for (const char* name : {"suite_report.json", "suite_report.md", "suite_report.html"}) {
    if (fs::exists(out_dir + "/" + name, ec)) taken.push_back(name);
  }
  if (!taken.empty()) {
    throw InputError(out_dir, "holds " + JoinFileList(taken) +
                                  ", which the suite's report would overwrite, and no earlier hoilcd suite "
                                  "(suite.json or suite_report.json); refusing: choose another folder");
  }
}

void WriteSuiteReport(const SuiteSummary& summary, const std::string& out_dir) {
  CheckSuiteReportFolder(out_dir);
  const FolderLock lock(out_dir, FolderLock::IfBusy::kRefuse);  // held already by `hoilcd suite`'s thread
  WriteFileAtomic(out_dir + "/suite_report.json",
                  summary.ToJson().dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  WriteFileAtomic(out_dir + "/suite_report.md", summary.ToMarkdown());
  // Each run's folder as a link relative to the report's, so the folders can move together.
  std::map<std::string, std::string> links;
  const fs::path base = fs::absolute(out_dir).lexically_normal();
  for (const auto& [run, dir] : summary.run_dirs) {
    links[run] = fs::absolute(dir).lexically_normal().lexically_relative(base).generic_string();
  }
  WriteFileAtomic(out_dir + "/suite_report.html", SuiteReportHtml(summary, links));
}

}  // namespace hoilcd
