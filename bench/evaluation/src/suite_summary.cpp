#include "hoilcd/bench/evaluation/suite_summary.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/random.h"
#include "hoilcd/core/util/stats.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

std::vector<double> Finite(const std::vector<double>& values) {
  std::vector<double> out;
  for (double v : values) {
    if (std::isfinite(v)) out.push_back(v);
  }
  return out;
}

nlohmann::json Number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json IntervalJson(const Interval& i) { return nlohmann::json::array({Number(i.low), Number(i.high)}); }

std::string Cell(double v) { return Fixed(v, 3); }

std::string IntervalCell(double mean, const Interval& i) {
  return Cell(mean) + " [" + Cell(i.low) + ", " + Cell(i.high) + "]";
}

}  // namespace

std::string SuiteWins::ToString() const {
  const int total = a_wins + b_wins + ties;
  const bool a_leads = a_wins >= b_wins;
  std::string s = a_wins == b_wins
                      ? a + " and " + b + " each win " + std::to_string(a_wins) + " of " + std::to_string(total)
                      : (a_leads ? a : b) + " beats " + (a_leads ? b : a) + " on " +
                            std::to_string(a_leads ? a_wins : b_wins) + " of " + std::to_string(total);
  if (ties > 0) s += " (" + std::to_string(ties) + (ties == 1 ? " tie)" : " ties)");
  return s;
}

Interval BootstrapMeanInterval(const std::vector<double>& values, const SuiteBootstrapOptions& options,
                               const std::string& purpose) {
  HOILCD_CHECK_MSG(options.resamples >= 1 && options.confidence > 0 && options.confidence < 1,
                   "bootstrap options out of range");
  const std::vector<double> x = Finite(values);
  if (x.empty()) return {};
  const uint32_t n = static_cast<uint32_t>(x.size());
  std::vector<double> means(static_cast<size_t>(options.resamples));
  for (int r = 0; r < options.resamples; ++r) {
    Rng rng = KeyedRng(options.seed, "suite.bootstrap", HashString(purpose), r);
    double sum = 0;
    for (uint32_t k = 0; k < n; ++k) sum += x[rng.UniformInt(n)];
    means[static_cast<size_t>(r)] = sum / n;
  }
  const double alpha = (1 - options.confidence) / 2;
  return {Quantile(means, alpha), Quantile(means, 1 - alpha)};
}

std::vector<double> RanksDescending(const std::vector<double>& values) {
  std::vector<size_t> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  // Larger first; NaN after every number.
  const auto key = [&](size_t i) { return std::isnan(values[i]) ? -INFINITY : values[i]; };
  const auto same = [&](size_t i, size_t j) {
    return (std::isnan(values[i]) && std::isnan(values[j])) || values[i] == values[j];
  };
  std::stable_sort(order.begin(), order.end(), [&](size_t i, size_t j) {
    if (same(i, j)) return false;
    if (std::isnan(values[i])) return false;
    if (std::isnan(values[j])) return true;
    return key(i) > key(j);
  });
  std::vector<double> ranks(values.size());
  for (size_t start = 0; start < order.size();) {
    size_t end = start + 1;
    while (end < order.size() && same(order[start], order[end])) ++end;
    const double mean_rank = (static_cast<double>(start + 1) + static_cast<double>(end)) / 2;
    for (size_t k = start; k < end; ++k) ranks[order[k]] = mean_rank;
    start = end;
  }
  return ranks;
}

SuiteSummary SummariseSuite(const std::string& name, const std::string& description,
                            const std::vector<std::string>& methods, const std::vector<SuiteRunResult>& runs,
                            const SuiteBootstrapOptions& options) {
  SuiteSummary s;
  s.name = name;
  s.description = description;
  s.bootstrap = options;
  for (const std::string& m : methods) {
    SuiteMethodSummary summary;
    summary.method = m;
    s.methods.push_back(summary);
  }
  std::vector<size_t> run_sequence;  // per finished run: its index in s.sequences
  for (const SuiteRunResult& run : runs) {
    if (!run.ok()) {
      s.failed.emplace_back(run.name, run.error);
      continue;
    }
    s.runs.push_back(run.name);
    const std::string& sequence = run.sequence.empty() ? run.name : run.sequence;
    const auto known = std::find(s.sequences.begin(), s.sequences.end(), sequence);
    run_sequence.push_back(static_cast<size_t>(known - s.sequences.begin()));
    if (known == s.sequences.end()) s.sequences.push_back(sequence);
    std::vector<double> mrr;
    for (SuiteMethodSummary& m : s.methods) {
      const auto at = [&](const std::map<std::string, double>& values) {
        const auto it = values.find(m.method);
        HOILCD_CHECK_MSG(it != values.end(), "run " + run.name + " has no value for " + m.method);
        return it->second;
      };
      m.mrr.push_back(at(run.mrr));
      m.recall_at_1.push_back(at(run.recall_at_1));
      mrr.push_back(m.mrr.back());
    }
    const std::vector<double> ranks = RanksDescending(mrr);
    for (size_t k = 0; k < s.methods.size(); ++k) s.methods[k].rank.push_back(ranks[k]);
  }
  // Each sequence's mean over its runs, ranked per sequence.
  for (size_t q = 0; q < s.sequences.size(); ++q) {
    std::vector<double> mrr;
    for (SuiteMethodSummary& m : s.methods) {
      std::vector<double> of_mrr, of_recall;
      for (size_t r = 0; r < s.runs.size(); ++r) {
        if (run_sequence[r] != q) continue;
        of_mrr.push_back(m.mrr[r]);
        of_recall.push_back(m.recall_at_1[r]);
      }
      const std::vector<double> finite_mrr = Finite(of_mrr), finite_recall = Finite(of_recall);
      m.sequence_mrr.push_back(finite_mrr.empty() ? NAN : Mean(finite_mrr));
      m.sequence_recall_at_1.push_back(finite_recall.empty() ? NAN : Mean(finite_recall));
      mrr.push_back(m.sequence_mrr.back());
    }
    const std::vector<double> ranks = RanksDescending(mrr);
    for (size_t k = 0; k < s.methods.size(); ++k) s.methods[k].sequence_rank.push_back(ranks[k]);
  }
  for (SuiteMethodSummary& m : s.methods) {
    m.mean_mrr = Mean(Finite(m.sequence_mrr));
    m.mean_recall_at_1 = Mean(Finite(m.sequence_recall_at_1));
    m.mean_rank = Mean(m.sequence_rank);
    m.mrr_interval = BootstrapMeanInterval(m.sequence_mrr, options, m.method + "/mrr");
    m.recall_at_1_interval = BootstrapMeanInterval(m.sequence_recall_at_1, options, m.method + "/recall_at_1");
  }
  for (size_t i = 0; i < s.methods.size(); ++i) {
    for (size_t j = i + 1; j < s.methods.size(); ++j) {
      SuiteWins w{s.methods[i].method, s.methods[j].method};
      for (size_t q = 0; q < s.sequences.size(); ++q) {
        const double a = s.methods[i].sequence_rank[q], b = s.methods[j].sequence_rank[q];
        if (a < b) {
          ++w.a_wins;
        } else if (b < a) {
          ++w.b_wins;
        } else {
          ++w.ties;
        }
      }
      s.wins.push_back(w);
    }
  }
  return s;
}

nlohmann::json SuiteSummary::ToJson() const {
  nlohmann::json j;
  j["suite"] = {{"name", name}, {"description", description}};
  if (!settings.is_null()) j["settings"] = settings;
  j["interval"] = {{"kind", "percentile bootstrap over sequences (each the mean of its runs), resampled i.i.d."},
                   {"resamples", bootstrap.resamples},
                   {"confidence", bootstrap.confidence},
                   {"seed", bootstrap.seed}};
  j["runs"] = runs;
  j["sequences"] = sequences;
  nlohmann::json ms = nlohmann::json::array();
  for (const SuiteMethodSummary& m : methods) {
    nlohmann::json per_run = nlohmann::json::object();
    for (size_t r = 0; r < runs.size(); ++r) {
      per_run[runs[r]] = {{"mrr", Number(m.mrr[r])}, {"recall_at_1", Number(m.recall_at_1[r])}, {"rank", m.rank[r]}};
    }
    nlohmann::json per_sequence = nlohmann::json::object();
    for (size_t q = 0; q < sequences.size(); ++q) {
      per_sequence[sequences[q]] = {{"mrr", Number(m.sequence_mrr[q])},
                                    {"recall_at_1", Number(m.sequence_recall_at_1[q])},
                                    {"rank", m.sequence_rank[q]}};
    }
    ms.push_back(
        {{"method", m.method},
         {"mrr", {{"mean", Number(m.mean_mrr)}, {"interval", IntervalJson(m.mrr_interval)}}},
         {"recall_at_1", {{"mean", Number(m.mean_recall_at_1)}, {"interval", IntervalJson(m.recall_at_1_interval)}}},
         {"mean_rank", Number(m.mean_rank)},
         {"sequences", per_sequence},
         {"runs", per_run}});
  }
  j["methods"] = ms;
  nlohmann::json ws = nlohmann::json::array();
  for (const SuiteWins& w : wins) {
    ws.push_back(
        {{"a", w.a}, {"b", w.b}, {"a_wins", w.a_wins}, {"b_wins", w.b_wins}, {"ties", w.ties}, {"text", w.ToString()}});
  }
  j["wins"] = ws;
  nlohmann::json f = nlohmann::json::array();
  for (const auto& [run, error] : failed) f.push_back({{"run", run}, {"error", error}});
  j["failed"] = f;
  return j;
}

std::string SuiteSummary::ToMarkdown() const {
  std::ostringstream out;
  out << "# Suite " << name << "\n\n";
  if (!description.empty()) out << description << "\n\n";
  out << runs.size() << " runs of " << sequences.size() << " sequences finished, " << failed.size()
      << " failed. Means over sequences (each the mean of its seeds) with " << Fixed(100 * bootstrap.confidence, 0)
      << " % percentile bootstrap intervals (" << bootstrap.resamples
      << " resamples of the sequences, i.i.d.: the seeds of one room are not independent of each other); ranks "
         "and wins per sequence.\n\n";
  out << "| method | MRR | R@1 | mean rank |\n|---|---|---|---|\n";
  for (const SuiteMethodSummary& m : methods) {
    out << "| " << m.method << " | " << IntervalCell(m.mean_mrr, m.mrr_interval) << " | "
        << IntervalCell(m.mean_recall_at_1, m.recall_at_1_interval) << " | " << Cell(m.mean_rank) << " |\n";
  }
  if (!wins.empty()) {
    out << "\n## Paired wins on MRR\n\n";
    for (const SuiteWins& w : wins) out << "- " << w.ToString() << "\n";
  }
  if (!sequences.empty()) {
    out << "\n## MRR per sequence (rank)\n\n| sequence |";
    for (const SuiteMethodSummary& m : methods) out << " " << m.method << " |";
    out << "\n|---|";
    for (size_t k = 0; k < methods.size(); ++k) out << "---|";
    out << "\n";
    for (size_t q = 0; q < sequences.size(); ++q) {
      out << "| " << sequences[q] << " |";
      for (const SuiteMethodSummary& m : methods) {
        out << " " << Cell(m.sequence_mrr[q]) << " (" << Fixed(m.sequence_rank[q], 1) << ") |";
      }
      out << "\n";
    }
  }
  if (!runs.empty()) {
    out << "\n## MRR per run (rank)\n\n| run |";
    for (const SuiteMethodSummary& m : methods) out << " " << m.method << " |";
    out << "\n|---|";
    for (size_t k = 0; k < methods.size(); ++k) out << "---|";
    out << "\n";
    for (size_t r = 0; r < runs.size(); ++r) {
      out << "| " << runs[r] << " |";
      for (const SuiteMethodSummary& m : methods) out << " " << Cell(m.mrr[r]) << " (" << Fixed(m.rank[r], 1) << ") |";
      out << "\n";
    }
  }
  if (!failed.empty()) {
    out << "\n## Failed runs\n\n";
    for (const auto& [run, error] : failed) {
      std::string line = error;
      std::replace(line.begin(), line.end(), '\n', ' ');
      out << "- " << run << ": " << line << "\n";
    }
  }
  return out.str();
}

}  // namespace hoilcd
