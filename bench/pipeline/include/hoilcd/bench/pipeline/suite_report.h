// The report of a suite (suite.h): its output folder, or the folders of its shards, read back,
// checked to be one suite's and to hold every run once, summarised (suite_summary.h) and written
// as suite_report.json and .md. An unsharded suite's report is the merge of its one folder, so
// shards merged give the same bytes.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/evaluation/suite_summary.h"

namespace hoilcd {

// A finished run's MRR and R@1 for each method, from its report.json (ReadReportJson);
// InputError naming the file when it is unreadable or lacks a method.
SuiteRunResult ReadSuiteRunResult(const std::string& name, const std::string& report_path,
                                  const std::vector<std::string>& methods);

// Reads suite output folders (each one's suite.json, and its finished runs' suite_run.json and
// report.json) and summarises their runs in the suite's run order; a run a shard recorded as failed
// is a failed run of the report. InputError naming the folder when one holds no suite, or another
// suite than `expected_identity` (SuiteIdentity) or than the first folder (naming where they first
// differ); and, every problem listed, when a shard is given twice or is missing, or a run is
// neither finished nor recorded as failed (naming its shard, and whether that shard finished).
SuiteSummary MergeSuite(const std::vector<std::string>& dirs, const nlohmann::json* expected_identity = nullptr);

// The report's folder may hold other things (the shards' folders, logs); InputError when it holds
// suite_report.json or suite_report.md but neither a suite (suite.json) nor an earlier report.
// WriteSuiteReport checks it; call it before long work too.
void CheckSuiteReportFolder(const std::string& out_dir);

// OUT/suite_report.json and OUT/suite_report.md, each written atomically.
void WriteSuiteReport(const SuiteSummary& summary, const std::string& out_dir);

}  // namespace hoilcd
