#include "hoilcd/bench/report/diagnosis.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "hoilcd/bench/evaluation/json_number.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

// Why DLCD wins or loses: each method's MRR on the queries whose frame has HOI points (people
// were detected) and on those without.
// Mean reciprocal rank of `run` over the scored queries with (with_hoi) or without HOI points.
double MrrWhere(const BenchResult& result, const MethodRun& run, bool with_hoi) {
  double sum = 0;
  int count = 0;
  for (const QueryRecord& q : run.metrics.queries) {
    if (!q.scored || result.features[q.frame].hoi.empty() == with_hoi) continue;
    sum += q.reciprocal_rank;
    ++count;
  }
  return count ? sum / count : NAN;
}

const MethodDiagnosis* FindDiagnosis(const Diagnosis& diagnosis, const std::string& method) {
  for (const MethodDiagnosis& m : diagnosis.methods)
    if (m.method == method) return &m;
  return nullptr;
}

// Why the paper's finding fails on this dataset, from its own numbers (empty when it holds).
std::string FindingExplanation(const BenchResult& result, const Diagnosis& diagnosis) {
  const MethodRun* s = result.Find("slcd");
  const MethodRun* d = result.Find("dlcd");
  if (!s || !d || result.mean_hoi_points_per_frame == 0) return "";
  std::ostringstream md;
  const double sm = s->metrics.mrr, dm = d->metrics.mrr;
  if (dm <= sm) {
    const MethodDiagnosis& sd = *FindDiagnosis(diagnosis, "slcd");
    const MethodDiagnosis& dd = *FindDiagnosis(diagnosis, "dlcd");
    md << "**Why DLCD does not beat SLCD here.** DLCD can only work where people are detected: on "
          "the other queries it scores "
       << Fixed(dd.mrr_without_hoi) << " against SLCD's " << Fixed(sd.mrr_without_hoi)
       << ". Where people are detected SLCD still leads (" << Fixed(sd.mrr_with_hoi) << " vs " << Fixed(dd.mrr_with_hoi)
       << "): the static corners of this synthetic room (chairs, table edges, the people's "
          "outlines) repeat lap after lap, which real thermal rooms at equilibrium do not, while the "
          "detector behind DLCD merges people who overlap in the image";
    if (result.tracking_evaluated) {
      md << " (person tracking precision " << Fixed(result.tracking.precision) << ", recall "
         << Fixed(result.tracking.recall) << ", below)";
    }
    md << ", so HOI contours of groups change whenever anyone in them moves. The study "
          "docs/results/2026-12-01-why-dlcd-scores-0.141.md in the hoilcd repository has the full discussion.\n\n";
  }
  const MethodRun* f = result.Find("fusion");
  if (f && f->metrics.mrr < std::max(sm, dm) - 0.01) {
    const FusionDiagnosis& fd = *diagnosis.fusion;
    // The k it ran with (its options), not the default: with k > 0 a first rank no longer dominates.
    const double k = f->options.is_object() ? f->options.value("k", 0.0) : 0.0;
    md << "**Why fusion falls below " << fd.better << ".** Reciprocal rank fusion with k = " << k
       << " sums 1/(k + rank) over the two rankings"
       << (k == 0 ? ", and a first rank in either list (1/1) outweighs anything else" : "")
       << ": fusion ranks the true match lower than " << fd.better << " on " << fd.queries_ranked_lower
       << " queries (on " << fd.queries_ranked_lower_weaker_top1_false << " of them " << fd.weaker
       << " put a false match first) and higher on " << fd.queries_ranked_higher
       << ". With one method clearly "
          "weaker, its confident mistakes cost more than its agreement adds.\n\n";
  }
  return md.str();
}

// The oracles and the method each stands beside, with the words of its finding.
struct OracleSpec {
  const char* oracle;
  const char* method;
  const char* source;     // what the oracle reads in place of the method's input
  const char* costs;      // the finding when the oracle is better beyond the noise
  const char* not_limit;  // ... when it is not
  const char* limit;      // what limits the method then
};
constexpr OracleSpec kOracles[] = {
    {"dlcd-oracle", "dlcd", "ground-truth people", "detection and tracking are part of DLCD's deficit",
     "detection is not DLCD's deficit", "the HOI landmarks themselves limit it"},
    {"slcd-ideal", "slcd", "noise-free image",
     "the sensor (noise, fixed pattern, blur, drift, FFC) is part of SLCD's deficit", "the sensor is not SLCD's limit",
     "the corners and their matching limit it"},
};

// Below this difference of MRR an oracle counts as no better, when no interval was computed.
constexpr double kMrrNoise = 0.01;

// The paired bootstrap of `a` against `b` from the result, oriented as a - b (NaN when absent).
std::pair<double, Interval> PairedDelta(const BenchResult& result, const std::string& a, const std::string& b) {
  for (const PairedComparison& c : result.comparisons) {
    if (c.a == a && c.b == b) return {c.delta, c.interval};
    if (c.a == b && c.b == a) return {-c.delta, Interval{-c.interval.high, -c.interval.low}};
  }
  return {NAN, Interval{}};
}

// The oracle's numbers and its finding in words.
OracleDiagnosis DiagnoseOracle(const BenchResult& result, const OracleSpec& spec, const MethodRun& oracle) {
  OracleDiagnosis o;
  o.oracle = spec.oracle;
  o.method = spec.method;
  o.oracle_mrr = oracle.metrics.mrr;
  std::ostringstream text;
  text << spec.oracle << " (" << spec.source << ") " << Fixed(o.oracle_mrr);
  const MethodRun* method = result.Find(spec.method);
  if (method == nullptr) {
    text << "; run " << spec.method << " beside it to see what it isolates";
    o.finding = text.str();
    return o;
  }
  o.method_mrr = method->metrics.mrr;
  const auto [paired, interval] = PairedDelta(result, spec.oracle, spec.method);
  o.delta = std::isnan(paired) ? o.oracle_mrr - o.method_mrr : paired;
  o.interval = interval;
  const bool has_interval = !std::isnan(interval.low) && !std::isnan(interval.high);
  const bool separated = has_interval ? (interval.low > 0 || interval.high < 0) : std::abs(o.delta) >= kMrrNoise;
  o.helps = separated && o.delta > 0;
  text << " vs " << spec.method << " " << Fixed(o.method_mrr) << " (\xce\x94 " << (o.delta >= 0 ? "+" : "")
       << Fixed(o.delta);
  if (has_interval) text << " [" << Fixed(interval.low) << ", " << Fixed(interval.high) << "]";
  text << "): ";
  if (o.helps) {
    text << "higher beyond the noise: " << spec.costs;
  } else {
    text << (separated ? "lower" : "within the noise") << ": " << spec.not_limit << "; " << spec.limit;
  }
  o.finding = text.str();
  return o;
}

// "**Oracles.**" and the lines of what each showed and which were left out (empty: none).
std::string OracleMarkdown(const Diagnosis& diagnosis) {
  if (diagnosis.oracles.empty() && diagnosis.not_run.empty()) return "";
  std::ostringstream md;
  md << "**Oracles.** Each replaces one part of a method with the dataset's ground truth: dlcd-oracle "
        "takes the people from it (no detector, no tracker), slcd-ideal reads the true temperature "
        "before the sensor model, in the same 8-bit window.\n\n";
  for (const OracleDiagnosis& o : diagnosis.oracles) md << "- " << o.finding << ".\n";
  for (const std::string& n : diagnosis.not_run) md << "- " << n << ".\n";
  md << "\n";
  return md.str();
}

}  // namespace

std::string PaperFindingSummary(const BenchResult& result) {
  const MethodRun* s = result.Find("slcd");
  const MethodRun* d = result.Find("dlcd");
  const MethodRun* f = result.Find("fusion");
  if (!s || !d) return "The paper's finding needs slcd and dlcd.";
  std::ostringstream out;
  const double sm = s->metrics.mrr, dm = d->metrics.mrr;
  out << "DLCD MRR " << Fixed(dm) << (dm > sm ? " > " : " <= ") << "SLCD MRR " << Fixed(sm)
      << (dm > sm ? " (holds, as in the paper)" : " (does NOT hold)");
  if (f) {
    const double fm = f->metrics.mrr, better = std::max(sm, dm);
    out << "; fusion MRR " << Fixed(fm) << (fm >= better - 0.01 ? " >= " : " < ")
        << "better - 0.01 = " << Fixed(better - 0.01) << (fm >= better - 0.01 ? " (holds)" : " (does NOT hold)");
  }
  // Whether the scene has people is known only from persons.json (tracking_evaluated: the dataset
  // has it and DLCD's front end ran).
  const bool no_people = result.tracking_evaluated && result.ground_truth_person_views == 0;
  if (result.mean_hoi_points_per_frame == 0) {
    out << ". DLCD found no HOI points at all (no person detected in any frame"
        << (no_people ? ", and the scene has no people" : "")
        << "), so it has nothing to match: every query scores 0 and its ranks are pure ties.";
  } else if (no_people) {
    out << ". The scene has no people, so every one of DLCD's HOI points ("
        << Fixed(result.mean_hoi_points_per_frame, 1)
        << " a frame) comes from a warm object mistaken for a person: its score measures the detector's false "
           "positives, not human-object interaction.";
  }
  return out.str();
}

nlohmann::json Diagnosis::ToJson() const {
  nlohmann::json j;
  if (hoi_split) {
    j["queries_with_hoi_points"] = queries_with_hoi;
    j["queries_without_hoi_points"] = queries_without_hoi;
  }
  if (!oracles.empty() || !not_run.empty()) {
    j["oracles"] = nlohmann::json::object();
    for (const OracleDiagnosis& o : oracles) {
      j["oracles"][o.oracle] = {{"method", o.method},
                                {"mrr", JsonNumber(o.oracle_mrr)},
                                {"method_mrr", JsonNumber(o.method_mrr)},
                                {"delta_mrr", JsonNumber(o.delta)},
                                {"interval", {JsonNumber(o.interval.low), JsonNumber(o.interval.high)}},
                                {"replaced_part_costs_method", o.helps},
                                {"finding", o.finding}};
    }
    j["not_run"] = not_run;
  }
  j["methods"] = nlohmann::json::object();
  for (const MethodDiagnosis& m : methods) {
    j["methods"][m.method] = {{"mrr_with_hoi_points", JsonNumber(m.mrr_with_hoi)},
                              {"mrr_without_hoi_points", JsonNumber(m.mrr_without_hoi)}};
  }
  if (fusion) {
    j["fusion"] = {{"better", fusion->better},
                   {"weaker", fusion->weaker},
                   {"queries_ranked_lower", fusion->queries_ranked_lower},
                   {"queries_ranked_lower_weaker_top1_false", fusion->queries_ranked_lower_weaker_top1_false},
                   {"queries_ranked_higher", fusion->queries_ranked_higher}};
  }
  return j;
}

Diagnosis Diagnose(const BenchResult& result) {
  Diagnosis diagnosis;
  for (const MethodRun& run : result.runs) {
    for (const OracleSpec& spec : kOracles)
      if (run.name == spec.oracle) diagnosis.oracles.push_back(DiagnoseOracle(result, spec, run));
  }
  diagnosis.not_run = result.skipped;
  diagnosis.evaluated = !diagnosis.oracles.empty() || !diagnosis.not_run.empty();
  const MethodRun* d = result.Find("dlcd");
  if (!d) return diagnosis;
  diagnosis.evaluated = diagnosis.hoi_split = true;
  for (const QueryRecord& q : d->metrics.queries) {
    if (!q.scored) continue;
    (result.features[q.frame].hoi.empty() ? diagnosis.queries_without_hoi : diagnosis.queries_with_hoi) += 1;
  }
  for (const MethodRun& run : result.runs) {
    diagnosis.methods.push_back({run.name, MrrWhere(result, run, true), MrrWhere(result, run, false)});
  }
  const MethodRun* s = result.Find("slcd");
  const MethodRun* f = result.Find("fusion");
  if (s && f) {
    const bool slcd_better = s->metrics.mrr >= d->metrics.mrr;
    const MethodRun& better = slcd_better ? *s : *d;
    const MethodRun& weaker = slcd_better ? *d : *s;
    FusionDiagnosis fd;
    fd.better = better.name;
    fd.weaker = weaker.name;
    for (size_t i = 0; i < f->metrics.queries.size(); ++i) {
      const QueryRecord& fq = f->metrics.queries[i];
      if (!fq.scored) continue;
      const double b = better.metrics.queries[i].reciprocal_rank;
      fd.queries_ranked_lower += fq.reciprocal_rank < b - 1e-9 ? 1 : 0;
      fd.queries_ranked_higher += fq.reciprocal_rank > b + 1e-9 ? 1 : 0;
      fd.queries_ranked_lower_weaker_top1_false +=
          (fq.reciprocal_rank < b - 1e-9 && !weaker.metrics.queries[i].top1_is_true_match) ? 1 : 0;
    }
    diagnosis.fusion = fd;
  }
  return diagnosis;
}

std::string DiagnosisMarkdown(const BenchResult& result, const Diagnosis& diagnosis) {
  if (!diagnosis.evaluated) return "";
  std::ostringstream md;
  md << "## Diagnosis\n\n";
  if (!diagnosis.hoi_split) return md.str() + OracleMarkdown(diagnosis);
  if (result.mean_hoi_points_per_frame == 0) {
    md << "No person detected in any frame: DLCD has no HOI points, every query scores 0 and its "
          "MRR is that of a random order of the database. "
       << (result.ground_truth_person_views == 0
               ? "Correct here: the ground truth has no people either."
               : "The ground truth has people (" + std::to_string(result.ground_truth_person_views) +
                     " person views): the detector missed them all.")
       << "\n\n";
  } else {
    md << diagnosis.queries_with_hoi << " scored queries show detected people (DLCD has HOI points), "
       << diagnosis.queries_without_hoi << " show none (walls in the turns, or people not detected).\n\n";
  }
  md << "| method | MRR, queries with HOI points | MRR, queries without |\n|---|---|---|\n";
  for (const MethodDiagnosis& m : diagnosis.methods) {
    md << "| " << m.method << " | " << Fixed(m.mrr_with_hoi) << " | " << Fixed(m.mrr_without_hoi) << " |\n";
  }
  md << "\n" << FindingExplanation(result, diagnosis) << OracleMarkdown(diagnosis);
  return md.str();
}

}  // namespace hoilcd
