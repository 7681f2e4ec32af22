// Reciprocal Rank Fusion of retrieval rankings (paper 4.3, Cormack et al. 2009): each method ranks
// the database best-first; an item's fused score is Σ 1/(k + r) over the rankings it appears in.
#pragma once

#include <vector>

namespace hoilcd {

// rankings: lists of database indices best-first (rank 1 = first), each index at most once per
// list; returns the fused score per database index (size num_database), score = Σ 1/(k + r);
// items absent from a ranking contribute 0. k > -1 so every term is finite and positive.
std::vector<double> ReciprocalRankFusion(const std::vector<std::vector<int>>& rankings, int num_database,
                                         double k = 0.0);

// Database indices sorted by descending score, ties kept in index order (stable). Tie-aware
// metrics (expected rank over a tied group) are the bench's job, not this helper's.
std::vector<int> RankByScore(const std::vector<double>& scores);

// Ranks 1..n by descending score where tied items share the mean of the positions they occupy
// (fractional ranking), so a rank never depends on database order.
std::vector<double> FractionalRanks(const std::vector<double>& scores);

// Reciprocal rank fusion of score lists over the same database (each parallel to it): fused
// score = Σ 1/(k + r) with r the fractional rank in each list. With no ties it equals
// ReciprocalRankFusion of the RankByScore rankings.
std::vector<double> ReciprocalRankFusionOfScores(const std::vector<std::vector<double>>& scores, double k = 0.0);

}  // namespace hoilcd
