#include "hoilcd/bench/evaluation/metrics.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <functional>
#include <numeric>

#include "hoilcd/bench/evaluation/json_number.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/stats.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

// A query's record before ranking: its size, labels and the top-1 match (the first of a tied
// top group in database order, with the group's expected correctness).
QueryRecord Top1Record(const Query& q, const std::vector<double>& s,
                       const std::function<const PoseRecord&(int)>& pose_of) {
  QueryRecord r;
  r.frame = q.frame;
  r.lap = q.lap;
  r.database_size = static_cast<int>(s.size());
  r.true_matches = q.NumTrueMatches();
  r.scored = r.true_matches > 0;
  if (s.empty()) return r;
  const double top = *std::max_element(s.begin(), s.end());
  int top_true = 0;
  for (size_t k = 0; k < s.size(); ++k) {
    if (s[k] != top) continue;
    if (r.top1_tie_size == 0) {
      r.top1_frame = q.database[k];
      r.top1_is_true_match = q.is_true_match[k] != 0;
    }
    ++r.top1_tie_size;
    top_true += q.is_true_match[k] ? 1 : 0;
  }
  r.top1_score = top;
  r.top1_expected_correct = static_cast<double>(top_true) / r.top1_tie_size;
  r.top1_distance_m = BaseDistanceM(pose_of(q.frame), pose_of(r.top1_frame));
  return r;
}

// The top-1 precision-recall curve of the scored queries, its area and the recall at 100 %
// precision (recall over m->queries_scored).
void AddPrCurve(MethodMetrics* m) {
  std::vector<const QueryRecord*> claims;
  for (const QueryRecord& r : m->queries) {
    if (r.scored) claims.push_back(&r);
  }
  std::sort(claims.begin(), claims.end(),
            [](const QueryRecord* a, const QueryRecord* b) { return a->top1_score > b->top1_score; });
  const double n = m->queries_scored;
  double correct = 0, previous_recall = 0;
  m->pr_auc = 0;
  m->recall_at_100p = 0;
  for (size_t i = 0; i < claims.size();) {
    const double threshold = claims[i]->top1_score;
    for (; i < claims.size() && claims[i]->top1_score == threshold; ++i) {
      correct += claims[i]->top1_expected_correct;
    }
    PrPoint p;
    p.threshold = threshold;
    p.precision = correct / i;
    p.recall = correct / n;
    m->pr_auc += (p.recall - previous_recall) * p.precision;
    previous_recall = p.recall;
    // Expected correctness is a sum of fractions; allow for its rounding.
    if (p.precision >= 1.0 - 1e-12) m->recall_at_100p = std::max(m->recall_at_100p, p.recall);
    m->pr_curve.push_back(p);
  }
}

}  // namespace

double FirstTrueRank::ExpectedRank() const {
  // The first of t marked items among g shuffled ones sits at (g + 1) / (t + 1) on average.
  return above + (tie_size + 1.0) / (tie_true + 1.0);
}

double FirstTrueRank::ExpectedReciprocalRank() const {
  HOILCD_CHECK(tie_true >= 1 && tie_size >= tie_true);
  const int g = tie_size;
  const int t = tie_true;
  // P(first true at position k) = C(g-k, t-1) / C(g, t); P(1) = t/g, then a ratio per step.
  double probability = static_cast<double>(t) / g;
  double expected = 0;
  for (int k = 1; k <= g - t + 1; ++k) {
    expected += probability / (above + k);
    if (k < g) probability *= static_cast<double>(g - k - t + 1) / (g - k);
  }
  return expected;
}

double FirstTrueRank::RecallAtK(int k) const {
  HOILCD_CHECK(tie_true >= 1 && tie_size >= tie_true);
  const int slots = k - above;  // positions of the tied group that fall within the top k
  if (slots <= 0) return 0.0;
  if (slots > tie_size - tie_true) return 1.0;
  // P(no true match in the first `slots` positions) = C(g - slots, t) / C(g, t).
  double none = 1.0;
  for (int i = 0; i < tie_true; ++i) {
    none *= static_cast<double>(tie_size - slots - i) / (tie_size - i);
  }
  return 1.0 - none;
}

FirstTrueRank RankFirstTrueMatch(const std::vector<double>& scores, const std::vector<uint8_t>& is_true_match) {
  HOILCD_CHECK(scores.size() == is_true_match.size());
  double best_true = -INFINITY;
  for (size_t i = 0; i < scores.size(); ++i) {
    HOILCD_CHECK_MSG(std::isfinite(scores[i]), "score " << i << " is " << scores[i]);
    if (is_true_match[i]) best_true = std::max(best_true, scores[i]);
  }
  HOILCD_CHECK_MSG(best_true > -INFINITY, "query has no true match");
  FirstTrueRank rank;
  for (size_t i = 0; i < scores.size(); ++i) {
    if (scores[i] > best_true) ++rank.above;
    if (scores[i] == best_true) {
      ++rank.tie_size;
      if (is_true_match[i]) ++rank.tie_true;
    }
  }
  return rank;
}

void MethodMetrics::SetTiming(const std::vector<double>& extract_ms, const std::vector<double>& match_ms) {
  HOILCD_CHECK(extract_ms.size() == match_ms.size());
  std::vector<double> total_ms(extract_ms.size());
  for (size_t i = 0; i < total_ms.size(); ++i) total_ms[i] = extract_ms[i] + match_ms[i];
  ms_per_query = Mean(total_ms);
  ms_per_query_median = Median(total_ms);
  extract_ms_mean = Mean(extract_ms);
  extract_ms_median = Median(extract_ms);
  match_ms_mean = Mean(match_ms);
  match_ms_median = Median(match_ms);
}

nlohmann::json MethodMetrics::ToJson() const {
  nlohmann::json j;
  j["queries_total"] = queries_total;
  j["queries_scored"] = queries_scored;
  j["queries_skipped"] = queries_skipped;
  j["mrr"] = JsonNumber(mrr);
  j["recall_at_1"] = JsonNumber(recall_at_1);
  j["recall_at_5"] = JsonNumber(recall_at_5);
  j["recall_at_10"] = JsonNumber(recall_at_10);
  j["pr_auc"] = JsonNumber(pr_auc);
  j["pr_auc_integration"] = "step: sum over thresholds of precision x recall increment";
  j["recall_at_100p"] = JsonNumber(recall_at_100p);
  j["ties"] = "expected value over a uniformly random order of tied scores";
  j["ms_per_query"] = JsonNumber(ms_per_query);
  j["ms_per_query_median"] = JsonNumber(ms_per_query_median);
  j["extract_ms_mean"] = JsonNumber(extract_ms_mean);
  j["extract_ms_median"] = JsonNumber(extract_ms_median);
  j["match_ms_mean"] = JsonNumber(match_ms_mean);
  j["match_ms_median"] = JsonNumber(match_ms_median);
  nlohmann::json laps = nlohmann::json::object();
  for (const auto& [lap, m] : per_lap) {
    laps[std::to_string(lap)] = {{"mrr", JsonNumber(m.mrr)}, {"queries_scored", m.queries_scored}};
  }
  j["per_lap"] = laps;
  nlohmann::json curve = nlohmann::json::array();
  for (const PrPoint& p : pr_curve) {
    curve.push_back({{"threshold", JsonNumber(p.threshold)},
                     {"precision", JsonNumber(p.precision)},
                     {"recall", JsonNumber(p.recall)}});
  }
  j["pr_curve"] = curve;
  return j;
}

MethodMetrics ComputeMetrics(const std::vector<Query>& queries, const std::vector<std::vector<double>>& scores,
                             const std::vector<PoseRecord>& poses) {
  HOILCD_CHECK(scores.size() == queries.size());
  auto pose_of = [&](int frame) -> const PoseRecord& {
    HOILCD_CHECK_MSG(frame >= 0 && frame < static_cast<int>(poses.size()) && poses[frame].frame == frame,
                     "no pose for frame " << frame);
    return poses[frame];
  };
  std::vector<QueryRecord> records;
  records.reserve(queries.size());
  for (size_t i = 0; i < queries.size(); ++i) {
    const Query& q = queries[i];
    const std::vector<double>& s = scores[i];
    HOILCD_CHECK_MSG(s.size() == q.database.size() && q.is_true_match.size() == s.size(),
                     "query " << i << ": scores, database and is_true_match differ in size");
    QueryRecord r = Top1Record(q, s, pose_of);
    if (r.scored) {
      const FirstTrueRank rank = RankFirstTrueMatch(s, q.is_true_match);
      r.first_true_rank = rank.ExpectedRank();
      r.reciprocal_rank = rank.ExpectedReciprocalRank();
      r.recall_at_1 = rank.RecallAtK(1);
      r.recall_at_5 = rank.RecallAtK(5);
      r.recall_at_10 = rank.RecallAtK(10);
    }
    records.push_back(r);
  }
  return SummariseQueries(std::move(records));
}

QueryRecord ShortlistRecord(const Query& shortlisted, const std::vector<double>& scores, int database_size,
                            int true_matches, const std::vector<PoseRecord>& poses) {
  const int listed = static_cast<int>(shortlisted.database.size());
  const int listed_true = shortlisted.NumTrueMatches();
  HOILCD_CHECK_MSG(scores.size() == shortlisted.database.size() && shortlisted.is_true_match.size() == scores.size() &&
                       database_size >= listed && true_matches >= listed_true,
                   "shortlist of frame " << shortlisted.frame << ": " << listed << " frames (" << listed_true
                                         << " true) of " << database_size << " (" << true_matches << " true)");
  QueryRecord r = Top1Record(shortlisted, scores, [&](int frame) -> const PoseRecord& {
    HOILCD_CHECK_MSG(frame >= 0 && frame < static_cast<int>(poses.size()), "no pose for frame " << frame);
    return poses[frame];
  });
  r.database_size = database_size;
  r.true_matches = true_matches;
  r.scored = true_matches > 0;
  if (!r.scored) return r;
  FirstTrueRank rank;
  if (listed_true > 0) {
    rank = RankFirstTrueMatch(scores, shortlisted.is_true_match);
  } else {
    rank.above = listed;
    rank.tie_size = database_size - listed;
    rank.tie_true = true_matches;
  }
  r.first_true_rank = rank.ExpectedRank();
  r.reciprocal_rank = rank.ExpectedReciprocalRank();
  r.recall_at_1 = rank.RecallAtK(1);
  r.recall_at_5 = rank.RecallAtK(5);
  r.recall_at_10 = rank.RecallAtK(10);
  return r;
}

MethodMetrics SummariseQueries(std::vector<QueryRecord> records) {
  MethodMetrics m;
  m.queries_total = static_cast<int>(records.size());
  double sum_rr = 0, sum_r1 = 0, sum_r5 = 0, sum_r10 = 0;
  std::map<int, double> lap_sum_rr;
  for (const QueryRecord& r : records) {
    if (r.scored) {
      ++m.queries_scored;
      sum_rr += r.reciprocal_rank;
      sum_r1 += r.recall_at_1;
      sum_r5 += r.recall_at_5;
      sum_r10 += r.recall_at_10;
      lap_sum_rr[r.lap] += r.reciprocal_rank;
      ++m.per_lap[r.lap].queries_scored;
    } else {
      ++m.queries_skipped;
    }
  }
  m.queries = std::move(records);
  if (m.queries_scored == 0) return m;
  const double n = m.queries_scored;
  m.mrr = sum_rr / n;
  m.recall_at_1 = sum_r1 / n;
  m.recall_at_5 = sum_r5 / n;
  m.recall_at_10 = sum_r10 / n;
  for (auto& [lap, lap_metrics] : m.per_lap) {
    lap_metrics.mrr = lap_sum_rr[lap] / lap_metrics.queries_scored;
  }
  AddPrCurve(&m);
  return m;
}

std::string QueryRecordsToCsv(const std::vector<QueryRecord>& records) {
  std::string out =
      "frame,lap,database_size,true_matches,scored,first_true_rank,reciprocal_rank,top1_frame,"
      "top1_score,top1_distance_m,top1_is_true_match,top1_tie_size,top1_expected_correct,recall_at_1,"
      "recall_at_5,recall_at_10\n";
  for (const QueryRecord& r : records) {
    out += std::to_string(r.frame) + ',' + std::to_string(r.lap) + ',' + std::to_string(r.database_size) + ',' +
           std::to_string(r.true_matches) + ',' + (r.scored ? "1" : "0") + ',' + CsvNumber(r.first_true_rank) + ',' +
           CsvNumber(r.reciprocal_rank) + ',' + (r.top1_frame >= 0 ? std::to_string(r.top1_frame) : "") + ',' +
           CsvNumber(r.top1_score) + ',' + CsvNumber(r.top1_distance_m) + ',' +
           (r.top1_frame >= 0 ? (r.top1_is_true_match ? "1" : "0") : "") + ',' + std::to_string(r.top1_tie_size) + ',' +
           CsvNumber(r.top1_expected_correct) + ',' + CsvNumber(r.recall_at_1) + ',' + CsvNumber(r.recall_at_5) + ',' +
           CsvNumber(r.recall_at_10) + '\n';
  }
  return out;
}

}  // namespace hoilcd
