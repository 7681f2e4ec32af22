// Shared by the point-set methods (SLCD, DLCD and their -lo variants): every query against its own
// database through a RetrievalIndex (MNN -> vertical filter -> RANSAC inliers), timed per query.
#pragma once

#include <string>

#include "hoilcd/bench/loop_closure_method.h"
#include "hoilcd/core/homography_ransac.h"
#include "hoilcd/core/retrieval_index.h"

namespace hoilcd {

MethodScores ScorePointSets(const MethodContext& context, const std::string& title, const RetrievalIndex& index,
                            const RansacOptions& ransac, const std::vector<double>& extract_ms_per_frame);

// The bench's RANSAC with the -lo variants' least-squares refits.
RansacOptions LocallyOptimised(const BenchOptions& options);

}  // namespace hoilcd
