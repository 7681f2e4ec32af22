// The SLAM part of the report folder: report.json's `slam` and `methods.<name>.slam` objects, a
// report.md section, a trajectory plot per method (true, odometry, optimised), each method's pose
// graph in g2o text format and its optimised trajectory in TUM format (for g2o, GTSAM, evo).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/slam/slam_run.h"

namespace hoilcd {

// report.json's "slam": odometry, oracle (per back end), back end, noise model, notes.
nlohmann::json SlamSummaryJson(const SlamResult& slam);
// methods.<name>.slam: threshold, loops, and ate_rmse_m / rpe_rmse_m / loops_accepted /
// false_loops per back end, plus the ATE-vs-threshold curve.
nlohmann::json MethodSlamJson(const MethodSlam& method);

// A report.md section: the per-method ATE table under every back end, and the loop edges' model
// (`options`, the options the graphs were built with).
std::string SlamMarkdown(const SlamResult& slam, const SlamOptions& options);

// Writes DIR/slam/<method>.g2o (the method's keyframe graph, nodes at their odometry poses),
// DIR/slam/<method>_tum.txt, odometry_tum.txt, groundtruth_tum.txt, oracle_tum.txt, and
// DIR/slam_trajectories.png, DIR/slam_ate_vs_threshold.png. Returns the figures' file names.
std::vector<std::string> WriteSlamFiles(const SlamResult& slam, const std::vector<PoseRecord>& poses,
                                        const SlamOptions& options, const std::string& dir);

// TUM "t x y z qx qy qz qw" lines of planar poses (z = 0, yaw about +z).
std::string PlanarTum(const std::vector<PoseRecord>& poses, const std::vector<Pose2d>& trajectory);

}  // namespace hoilcd
