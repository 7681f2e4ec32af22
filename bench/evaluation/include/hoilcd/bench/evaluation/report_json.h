// A report.json read back (the bench's, run's or evaluate's): the CI gate's --baseline. The text
// is checked before it is used: JSON of bounded size and depth, with a "methods" object whose
// every method gives the headline metrics as numbers in [0, 1] or null.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace hoilcd {

// The metrics the CI gate compares, which every method of a report gives.
inline constexpr const char* kHeadlineMetrics[] = {"mrr", "recall_at_1"};

// The report in `text`; InputError naming `source` and the JSON pointer (or the parse error's
// place) and what was expected.
nlohmann::json ReportJsonFromText(std::string_view text, const std::string& source);

// ReportJsonFromText of the regular file `path` (RegularFile, core/util/file_io.h) of at most
// 64 MiB, its size checked before it is read.
nlohmann::json ReadReportJson(const std::string& path);

}  // namespace hoilcd
