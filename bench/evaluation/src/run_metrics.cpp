#include "hoilcd/bench/evaluation/run_metrics.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "hoilcd/bench/evaluation/json_number.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/safe_text.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {

std::string WhenRecorded(const RunRecord& r) {
  std::string out = "day " + std::to_string(r.day);
  if (r.time_of_day_h < 0) return out;
  const int minutes = static_cast<int>(std::lround(r.time_of_day_h * 60)) % (24 * 60);
  char text[16];
  std::snprintf(text, sizeof(text), ", %02d:%02d", minutes / 60, minutes % 60);
  return out + text;
}

std::vector<RunMetrics> MetricsPerRun(const std::vector<RunRecord>& runs, const std::vector<std::string>& names,
                                      const std::vector<const std::vector<QueryRecord>*>& records,
                                      const BootstrapPlan& plan, uint64_t seed, int threads) {
  HOILCD_CHECK(names.size() == records.size());
  std::vector<RunMetrics> rows;
  if (runs.size() < 2 || records.empty()) return rows;
  const std::vector<int> run_of_frame = RunOfFrames(runs);
  std::vector<std::vector<size_t>> members(runs.size());  // query indices by run
  for (size_t i = 0; i < records.front()->size(); ++i) {
    members[static_cast<size_t>(run_of_frame.at(static_cast<size_t>((*records.front())[i].frame)))].push_back(i);
  }
  for (size_t k = 0; k < runs.size(); ++k) {
    RunMetrics row;
    row.run = static_cast<int>(k);
    row.record = runs[k];
    row.queries = static_cast<int>(members[k].size());
    row.methods = names;
    for (const std::vector<QueryRecord>* method : records) {
      HOILCD_CHECK(method->size() == records.front()->size());
      std::vector<QueryRecord> subset;
      for (size_t i : members[k]) subset.push_back((*method)[i]);
      const HeadlineIntervals intervals = BootstrapHeadline(subset, plan, seed, threads);
      const MethodMetrics metrics = SummariseQueries(std::move(subset));
      row.queries_scored = metrics.queries_scored;
      row.mrr.push_back(metrics.mrr);
      row.recall_at_1.push_back(metrics.recall_at_1);
      row.mrr_interval.push_back(intervals.mrr);
      row.recall_at_1_interval.push_back(intervals.recall_at_1);
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

nlohmann::json MetricsPerRunJson(const std::vector<RunMetrics>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const RunMetrics& r : rows) {
    nlohmann::json methods = nlohmann::json::object();
    for (size_t m = 0; m < r.methods.size(); ++m) {
      methods[r.methods[m]] = {
          {"mrr", JsonNumber(r.mrr[m])},
          {"recall_at_1", JsonNumber(r.recall_at_1[m])},
          {"intervals", {{"mrr", r.mrr_interval[m].ToJson()}, {"recall_at_1", r.recall_at_1_interval[m].ToJson()}}}};
    }
    out.push_back({{"run", r.run},
                   {"time_of_day_h", r.record.time_of_day_h},
                   {"day", r.record.day},
                   {"start_time_s", r.record.start_time_s},
                   {"first_frame", r.record.first_frame},
                   {"frames", r.record.frames},
                   {"queries", r.queries},
                   {"queries_scored", r.queries_scored},
                   {"methods", methods}});
  }
  return out;
}

std::string MetricsPerRunMarkdown(const std::vector<RunMetrics>& rows, double confidence) {
  if (rows.empty()) return "";
  std::ostringstream md;
  md << "\n### Results by recording run\n\nMRR [" << Fixed(100 * confidence, 0)
     << " % interval] / R@1 of each method on the queries of each recording run (the same place recorded "
        "at another time, with other occupants); a run without queries is only a database.\n\n"
     << "| run | recorded | frames | queries scored |";
  for (const std::string& m : rows.front().methods) md << " " << SafeText(m) << " |";
  md << "\n|---|---|---|---|";
  for (size_t m = 0; m < rows.front().methods.size(); ++m) md << "---|";
  md << "\n";
  for (const RunMetrics& r : rows) {
    md << "| " << r.run << " | " << WhenRecorded(r.record) << " | " << r.record.first_frame << "-"
       << r.record.end_frame() - 1 << " | " << r.queries_scored << " of " << r.queries << " |";
    for (size_t m = 0; m < r.methods.size(); ++m) {
      if (r.queries_scored == 0) {
        md << " - |";
        continue;
      }
      md << " " << Fixed(r.mrr[m]) << " [" << Fixed(r.mrr_interval[m].low) << ", " << Fixed(r.mrr_interval[m].high)
         << "] / " << Fixed(r.recall_at_1[m]) << " |";
    }
    md << "\n";
  }
  return md.str();
}

}  // namespace hoilcd
