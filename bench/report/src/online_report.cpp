#include "hoilcd/bench/report/online_report.h"

#include <sstream>

#include "hoilcd/bench/evaluation/json_number.h"
#include "hoilcd/bench/report/html_report.h"
#include "hoilcd/bench/report/output_folder.h"
#include "hoilcd/bench/report/report.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/folder_lock.h"
#include "hoilcd/core/util/memory.h"
#include "hoilcd/core/util/safe_text.h"
#include "hoilcd/core/util/stats.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

nlohmann::json TimingRowsJson(const std::vector<OnlineTimingRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const OnlineTimingRow& r : rows) {
    out.push_back({{"database_from", r.database_from},
                   {"database_to", r.database_to},
                   {"queries", r.queries},
                   {"p50_ms", JsonNumber(r.p50_ms)},
                   {"p99_ms", JsonNumber(r.p99_ms)}});
  }
  return out;
}

}  // namespace

nlohmann::json OnlineResultToJson(const OnlineResult& result) {
  nlohmann::json j;
  j["shortlist"] = ShortlistOptions::Table().ToJson(result.shortlist);
  j["shortlist"]["descriptor"] = "thumbnail (the thumbnails front end)";
  j["protocol"] = result.protocol;
  j["database"] = "every frame older than the exclusion window";
  j["unranked"] = "frames outside the shortlist tie below every shortlisted frame";
  j["ground_truth"] = result.ground_truth;
  j["frames"] = result.frames;
  j["queries_processed"] = result.queries_processed;
  j["queries_scored"] = result.queries_scored;
  j["shortlist_hits"] = result.shortlist_hits;
  j["shortlist_recall"] = JsonNumber(result.shortlist_recall);
  j["search_p50_ms"] = JsonNumber(Quantile(result.search_ms, 0.5));
  j["search_p99_ms"] = JsonNumber(Quantile(result.search_ms, 0.99));
  j["search_by_database_size"] = TimingRowsJson(result.search_by_database_size);
  j["insert_p50_ms"] = JsonNumber(result.insert_p50_ms);
  j["insert_p99_ms"] = JsonNumber(result.insert_p99_ms);
  j["index_bytes"] = JsonNumber(result.index_bytes);
  j["peak_rss_bytes"] = JsonNumber(result.peak_rss_bytes);
  j["seconds"] = JsonNumber(result.seconds);
  j["bootstrap"] = result.bootstrap.ToJson();
  j["skipped"] = result.skipped;
  nlohmann::json methods = nlohmann::json::object();
  for (const OnlineMethodRun& run : result.runs) {
    nlohmann::json m = run.metrics.ToJson();
    for (const char* timing : {"ms_per_query", "ms_per_query_median", "extract_ms_mean", "extract_ms_median",
                               "match_ms_mean", "match_ms_median"}) {
      m.erase(timing);  // online timing is per query below, search included
    }
    m["intervals"] = run.intervals.ToJson();
    m["p50_ms"] = JsonNumber(run.p50_ms);
    m["p99_ms"] = JsonNumber(run.p99_ms);
    m["by_database_size"] = TimingRowsJson(run.by_database_size);
    m["options"] = run.options;
    methods[run.name] = m;
  }
  nlohmann::json out = {{"mode", "online"}, {"online", j}, {"methods", methods}};
  if (!result.per_run.empty()) out["recording_runs"] = MetricsPerRunJson(result.per_run);
  return out;
}

std::string OnlineResultToMarkdown(const OnlineResult& result) {
  std::ostringstream md;
  md << "# Online loop closure\n\n";
  md << "Frames in time order; the database is every frame older than the exclusion window; each query "
        "takes a shortlist of "
     << (result.shortlist.k > 0 ? std::to_string(result.shortlist.k) : std::string("every"))
     << " frames by thumbnail similarity (FAISS " << result.shortlist.index
     << "), then each method scores only those; frames outside the shortlist are unranked (they tie below every "
        "shortlisted frame). Queries: the "
     << result.protocol << " protocol's; ground truth: " << result.ground_truth << ".\n\n";
  md << "Queries processed " << result.queries_processed << ", scored (a true match in the database) "
     << result.queries_scored << "; **shortlist recall " << Fixed(result.shortlist_recall, 3) << "** ("
     << result.shortlist_hits << " scored queries with a true match in their shortlist).\n\n";
  md << "| method | MRR | 95 % interval | R@1 | p50 ms/query | p99 ms/query |\n|---|---|---|---|---|---|\n";
  for (const OnlineMethodRun& run : result.runs) {
    md << "| " << run.name << " | " << Fixed(run.metrics.mrr, 3) << " | [" << Fixed(run.intervals.mrr.low, 3) << ", "
       << Fixed(run.intervals.mrr.high, 3) << "] | " << Fixed(run.metrics.recall_at_1, 3) << " | "
       << Fixed(run.p50_ms, 2) << " | " << Fixed(run.p99_ms, 2) << " |\n";
  }
  md << MetricsPerRunMarkdown(result.per_run, result.bootstrap.confidence);
  md << "\nms per query (shortlist search plus the method's scoring; extraction not included) as the database "
        "grows:\n\n| database frames | queries | search p50 / p99 |";
  for (const OnlineMethodRun& run : result.runs) md << " " << run.name << " p50 / p99 |";
  md << "\n|---|---|---|";
  for (size_t i = 0; i < result.runs.size(); ++i) md << "---|";
  md << "\n";
  for (size_t row = 0; row < result.search_by_database_size.size(); ++row) {
    const OnlineTimingRow& s = result.search_by_database_size[row];
    md << "| " << s.database_from << "–" << s.database_to << " | " << s.queries << " | " << Fixed(s.p50_ms, 2) << " / "
       << Fixed(s.p99_ms, 2) << " |";
    for (const OnlineMethodRun& run : result.runs) {
      const OnlineTimingRow& r = run.by_database_size[row];
      md << " " << Fixed(r.p50_ms, 2) << " / " << Fixed(r.p99_ms, 2) << " |";
    }
    md << "\n";
  }
  md << "\nAdding a frame to the index: p50 " << Fixed(result.insert_p50_ms, 3) << " ms, p99 "
     << Fixed(result.insert_p99_ms, 3) << " ms. Index " << FormatBytes(result.index_bytes) << "; peak memory "
     << FormatBytes(result.peak_rss_bytes) << "; " << Fixed(result.seconds, 1) << " s in all.\n";
  if (!result.skipped.empty()) {
    md << "\nLeft out:\n\n";
    for (const std::string& s : result.skipped) md << "- " << s << "\n";
  }
  return md.str();
}

void WriteOnlineReport(const OnlineResult& result, const Dataset& dataset, const std::string& dir) {
  CheckReportFolder(dir);
  nlohmann::json report = OnlineResultToJson(result);
  report["hoilcd_version"] = HOILCD_VERSION;
  report["dataset"] = {{"dir", SafeText(dataset.dir())},
                       {"scene_hash", dataset.manifest().scene_hash},
                       {"seed", dataset.manifest().seed},
                       {"frames", dataset.num_frames()}};
  const FolderLock lock(dir, FolderLock::IfBusy::kWait);  // one writer at a time: never a mix of two reports
  WriteFileAtomic(dir + "/report.json", report.dump(2) + "\n");
  WriteFileAtomic(dir + "/report.md", OnlineResultToMarkdown(result));
  WriteFileAtomic(dir + "/report.html", OnlineReportHtml(result, dataset));
}

}  // namespace hoilcd
