#include "hoilcd/bench/report/html.h"
#include "hoilcd/bench/report/html_report.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

// One row per finished run, its name linking to its report.html, then the failed runs.
std::string RunsTable(const SuiteSummary& summary, const std::map<std::string, std::string>& run_reports) {
  std::vector<std::string> headers = {"run"};
  for (const SuiteMethodSummary& m : summary.methods) headers.push_back(m.method + " MRR (rank)");
  headers.push_back("report");
  std::vector<std::vector<HtmlCell>> rows;
  for (size_t r = 0; r < summary.runs.size(); ++r) {
    std::vector<HtmlCell> cells = {TextCell(summary.runs[r])};
    for (const SuiteMethodSummary& m : summary.methods) {
      cells.push_back({Fixed(m.mrr[r]) + " (" + Fixed(m.rank[r], 1) + ")", m.mrr[r]});
    }
    const auto report = run_reports.find(summary.runs[r]);
    cells.push_back(
        report == run_reports.end()
            ? TextCell(kMissingFigure)
            : HtmlCell{"<a href=\"" + EscapeHtml(report->second + "/report.html") + "\">report.html</a>", NAN});
    rows.push_back(std::move(cells));
  }
  std::string html =
      "<h2>Runs</h2>\n<p class=\"note\">One row per run (room and seed); each links to its own "
      "report.html.</p>\n" +
      SortableTable(headers, rows);
  if (!summary.failed.empty()) {
    html += "<h3>Failed runs</h3>\n<ul>";
    for (const auto& [run, error] : summary.failed)
      html += "<li>" + EscapeHtml(run) + ": " + EscapeHtml(error) + "</li>";
    html += "</ul>\n";
  }
  return html;
}

std::string SequencesTable(const SuiteSummary& summary) {
  if (summary.sequences.empty()) return "";
  std::vector<std::string> headers = {"sequence"};
  for (const SuiteMethodSummary& m : summary.methods) headers.push_back(m.method + " MRR (rank)");
  std::vector<std::vector<HtmlCell>> rows;
  for (size_t q = 0; q < summary.sequences.size(); ++q) {
    std::vector<HtmlCell> cells = {TextCell(summary.sequences[q])};
    for (const SuiteMethodSummary& m : summary.methods) {
      cells.push_back({Fixed(m.sequence_mrr[q]) + " (" + Fixed(m.sequence_rank[q], 1) + ")", m.sequence_mrr[q]});
    }
    rows.push_back(std::move(cells));
  }
  return "<h2>MRR per sequence (rank)</h2>\n" + SortableTable(headers, rows);
}

}  // namespace

std::string SuiteReportHtml(const SuiteSummary& summary, const std::map<std::string, std::string>& run_reports) {
  std::vector<std::vector<HtmlCell>> rows;
  for (const SuiteMethodSummary& m : summary.methods) {
    rows.push_back({TextCell(m.method), IntervalCell(m.mean_mrr, m.mrr_interval),
                    IntervalCell(m.mean_recall_at_1, m.recall_at_1_interval), NumberCell(m.mean_rank, 2)});
  }
  std::string body = "<h1>Suite " + EscapeHtml(summary.name) + "</h1>\n";
  if (!summary.description.empty()) body += "<p>" + EscapeHtml(summary.description) + "</p>\n";
  body += "<p>" + std::to_string(summary.runs.size()) + " runs of " + std::to_string(summary.sequences.size()) +
          " sequences finished, " + std::to_string(summary.failed.size()) +
          " failed. Means over sequences (each the mean of its seeds) with " +
          Fixed(100 * summary.bootstrap.confidence, 0) +
          " % percentile bootstrap intervals over the sequences. "
          "The same numbers as text: <a href=\"suite_report.md\">suite_report.md</a>.</p>\n" +
          SortableTable({"method", "MRR", "R@1", "mean rank"}, rows);
  if (!summary.wins.empty()) {
    body += "<h2>Paired wins on MRR</h2>\n<ul>";
    for (const SuiteWins& w : summary.wins) body += "<li>" + EscapeHtml(w.ToString()) + "</li>";
    body += "</ul>\n";
  }
  body += SequencesTable(summary) + RunsTable(summary, run_reports);
  return HtmlPage("hoilcd suite " + summary.name, body);
}

}  // namespace hoilcd
