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
          "the other queries it scores " << Fixed(dd.mrr_without_hoi) << " against SLCD's "
       << Fixed(sd.mrr_without_hoi) << ". Where people are detected SLCD still leads ("
       << Fixed(sd.mrr_with_hoi) << " vs " << Fixed(dd.mrr_with_hoi)
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
    md << "**Why fusion falls below " << fd.better << ".** Reciprocal rank fusion with k = "
       << "0 averages the two rankings, and a first rank in either list (1/1) outweighs anything "
          "else: fusion ranks the true match lower than " << fd.better << " on " << fd.queries_ranked_lower
       << " queries (on " << fd.queries_ranked_lower_weaker_top1_false << " of them " << fd.weaker
       << " put a false match first) and higher on " << fd.queries_ranked_higher << ". With one method clearly "
          "weaker, its confident mistakes cost more than its agreement adds.\n\n";
  }
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
    out << "; fusion MRR " << Fixed(fm) << (fm >= better - 0.01 ? " >= " : " < ") << "better - 0.01 = "
        << Fixed(better - 0.01) << (fm >= better - 0.01 ? " (holds)" : " (does NOT hold)");
  }
  if (result.mean_hoi_points_per_frame == 0) {
    out << ". DLCD found no HOI points at all (no person detected in any frame"
        << (result.ground_truth_person_views == 0 ? ", and the scene has no people" : "")
        << "), so it has nothing to match: every query scores 0 and its ranks are pure ties.";
  } else if (result.ground_truth_person_views == 0) {
    out << ". The scene has no people, so every one of DLCD's HOI points (" << Fixed(result.mean_hoi_points_per_frame, 1)
        << " a frame) comes from a warm object mistaken for a person: its score measures the detector's false "
           "positives, not human-object interaction.";
  }
  return out.str();
}

nlohmann::json Diagnosis::ToJson() const {
  nlohmann::json j;
  j["queries_with_hoi_points"] = queries_with_hoi;
  j["queries_without_hoi_points"] = queries_without_hoi;
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
  const MethodRun* d = result.Find("dlcd");
  if (!d) return diagnosis;
  diagnosis.evaluated = true;
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
  if (result.mean_hoi_points_per_frame == 0) {
    md << "No person detected in any frame: DLCD has no HOI points, every query scores 0 and its "
          "MRR is that of a random order of the database. "
       << (result.ground_truth_person_views == 0
               ? "Correct here: the ground truth has no people either."
               : "The ground truth has people (" +
                     std::to_string(result.ground_truth_person_views) +
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
  md << "\n" << FindingExplanation(result, diagnosis);
  return md.str();
}

}  // namespace hoilcd
