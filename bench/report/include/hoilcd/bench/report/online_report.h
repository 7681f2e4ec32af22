// The report of an online bench (`hoilcd bench --online`, online.h): its result as JSON and as
// Markdown, and its report folder: report.json (the result with the hoilcd version and the
// dataset), report.md and report.html, written atomically into a folder CheckReportFolder allows.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/runner/online.h"
#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

// The result for report.json: {"mode": "online", "online": {shortlist, recall, timing, ...},
// "methods": {name: metrics, intervals, p50/p99 ms, ...}, "recording_runs" (2+ runs only)}; and as
// report.md.
nlohmann::json OnlineResultToJson(const OnlineResult& result);
std::string OnlineResultToMarkdown(const OnlineResult& result);

void WriteOnlineReport(const OnlineResult& result, const Dataset& dataset, const std::string& dir);

}  // namespace hoilcd
