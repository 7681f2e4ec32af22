// The SLAM consequence of a method's loops: its accepted top-1 matches become appearance-only loop
// edges in an SE(2) pose graph (pose_graph.h) over the dataset's wheel odometry, and the optimised
// trajectory is scored against the true base poses (trajectory_metrics.h). Reads only the dataset
// folder: the odometry noise model comes from DIR/scene.json.
#pragma once

#include <string>
#include <vector>

#include "hoilcd/bench/evaluation/protocol.h"
#include "hoilcd/bench/slam/pose_graph.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// Odometry edge noise, from the scene's documented odometry error model. Systematic errors (scale,
// steering bias) grow linearly with distance, but a chain of independent per-frame edges only lets
// errors grow with √distance: each is modelled as a random walk that reaches the systematic error
// after correlation_length_m (else the graph would be √n-overconfident in its odometry). Per step
// of length d (m), with D = max(d, correlation_length_m):
// σ_along = σ_lateral = distance_sd_frac·√(d·D), σ_θ² = heading_var_rad2_per_m·d + heading_sd_rad_per_m²·d·D,
// each at least its floor (keeps the information finite when the odometry is exact).
struct OdometryNoise {
  double distance_sd_frac = 0.01;        // fraction of the distance travelled, 1σ (systematic + random)
  double heading_sd_rad_per_m = 1e-3;    // rad per metre, systematic heading drift treated as 1σ
  double heading_var_rad2_per_m = 1e-5;  // rad²/m, heading random walk
  double correlation_length_m = 5.0;     // m, distance over which systematic errors are matched
  double floor_sd_m = 1e-4;              // m
  double floor_sd_rad = 1e-4;            // rad
  Eigen::Matrix3d Information(const Pose2d& step) const;
  // From scene.json's "robot" and "odometry" sections (either odometry schema: the per-step
  // encoder/steering noise one, or the systematic + slip + heading random-walk one).
  // InputError("<path>: /odometry", ...) when the section is missing or not numbers.
  static OdometryNoise FromSceneJson(const std::string& scene_json, const std::string& path, double frame_rate_hz);
};

// Defaults and ranges: Table() in slam.cpp.
struct SlamOptions {
  PoseGraphOptions graph;  // back end options (graph.backend is the headline back end)
  double loop_threshold;   // score a top-1 match must reach to be accepted; NaN = operating point
  double loop_sd_m;        // m, per-axis σ of an appearance loop: uniform over the 0.2 m radius disk (r/2)
  double loop_yaw_sd_deg;  // deg, σ of the relative yaw of a loop (weak: revisits run the same way)
  double rpe_delta_m;      // m, RPE pair spacing along the true path
  int keyframe_every;      // frames per graph node (paper_room: ~8 cm, well under the 0.2 m radius)

  SlamOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<SlamOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// One accepted loop: query frame sees reference frame.
struct LoopClosure {
  int query = 0, reference = 0;
  double score = 0;
  bool is_true = false;  // true base positions within the match radius (whatever labelled the queries)
};

// Each scored query's top-1 database frame (first in database order among equal scores) when its
// score is ≥ threshold; is_true from the true base poses and radius_m.
std::vector<LoopClosure> AcceptLoops(const std::vector<Query>& queries, const std::vector<std::vector<double>>& scores,
                                     double threshold, const std::vector<PoseRecord>& poses, double radius_m);

// The oracle: one loop per query whose database holds a frame within radius_m in true position
// (the same density as a method accepting every top-1), to the nearest such frame.
std::vector<LoopClosure> OracleLoops(const std::vector<Query>& queries, const std::vector<PoseRecord>& poses,
                                     double radius_m);

// Lowest threshold whose accepted loops are all true (100 % precision) and accept at least one;
// NaN when the best-scoring top-1 match is already false.
double ThresholdAtFullPrecision(const std::vector<Query>& queries, const std::vector<std::vector<double>>& scores,
                                const std::vector<PoseRecord>& poses, double radius_m);

// Distinct top-1 scores of scored queries, ascending, thinned to at most `count` (the ATE curve's x).
std::vector<double> ThresholdCandidates(const std::vector<Query>& queries,
                                        const std::vector<std::vector<double>>& scores, int count);

std::vector<Pose2d> TruePoses(const std::vector<PoseRecord>& poses);
std::vector<Pose2d> OdometryPoses(const std::vector<PoseRecord>& poses);

// Frames that are graph nodes: in each recording run (PoseRecord::run; poses indexed by frame),
// its first frame, every keyframe_every-th frame after it and its last frame. One run: every
// keyframe_every-th frame and the last one.
std::vector<int> Keyframes(const std::vector<PoseRecord>& poses, int keyframe_every);

// Nodes = odometry poses of the keyframes, odometry edges between consecutive keyframes of a run,
// one loop edge per loop from the reference's nearest keyframe to the query's (each in its own
// run): the appearance loop says "query pose = reference pose" (σ loop_sd_m per axis,
// loop_yaw_sd_deg in yaw), carried to the keyframes through the odometry between them. Each run's
// first node is fixed at its odometry pose: node 0 fixes the gauge, and a later run starts at the
// same known dock, where its odometry restarts (the robot was carried there, so no odometry edge
// joins two runs; loops between runs tie them together).
PoseGraph BuildPoseGraph(const std::vector<PoseRecord>& poses, const std::vector<LoopClosure>& loops,
                         const OdometryNoise& noise, const SlamOptions& options);

// Every frame's pose from optimised keyframe poses: the pose of the keyframe at or before it in its
// own run · odometry since that keyframe.
std::vector<Pose2d> FramePosesFromKeyframes(const std::vector<PoseRecord>& poses,
                                            const std::vector<Pose2d>& keyframe_poses, int keyframe_every);

struct SlamScore {
  std::string backend;
  double ate_rmse_m = 0;
  double rpe_rmse_m = 0;
  int loops_accepted = 0;
  int false_loops = 0;
  std::vector<Pose2d> poses;  // optimised
};

// Builds the graph, optimises with `backend`, scores against the true poses. With no loop the
// odometry itself is scored. InputError on an unusable graph or too few poses.
SlamScore SolveSlam(const std::vector<PoseRecord>& poses, const std::vector<LoopClosure>& loops,
                    const OdometryNoise& noise, const SlamOptions& options, const std::string& backend);

// The odometry alone, scored the same way.
SlamScore ScoreOdometry(const std::vector<PoseRecord>& poses, const SlamOptions& options);

}  // namespace hoilcd
