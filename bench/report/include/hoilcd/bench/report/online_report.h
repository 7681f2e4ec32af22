// The report folder of an online bench (`hoilcd bench --online`, online.h): report.json (the
// result with the hoilcd version and the dataset) and report.md, written atomically into a folder
// CheckReportFolder allows.
#pragma once

#include <string>

#include "hoilcd/bench/runner/online.h"
#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

void WriteOnlineReport(const OnlineResult& result, const Dataset& dataset, const std::string& dir);

}  // namespace hoilcd
