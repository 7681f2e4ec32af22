#include "hoilcd/bench/slam/slam.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/slam/trajectory_metrics.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/json_reader.h"
#include "hoilcd/core/util/sizes.h"

namespace hoilcd {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

// A number at /section/key of the resolved scene; InputError naming the pointer otherwise.
double Number(const nlohmann::json& doc, const std::string& section, const std::string& key, const std::string& path) {
  const std::string pointer = "/" + section + "/" + key;
  const nlohmann::json::json_pointer p(pointer);
  if (!doc.contains(p) || !doc.at(p).is_number()) {
    throw InputError(path + ": " + pointer,
                     "expected a number (the odometry noise model the pose graph weights odometry with)");
  }
  return doc.at(p).get<double>();
}

// The graph's nodes by recording run: each run's frames [first, last] hold nodes [first_node,
// first_node + nodes), at its first frame, every keyframe_every-th frame after and its last frame.
// No node stands for frames of two runs: the robot was carried to its dock between them.
class KeyframeLayout {
 public:
  KeyframeLayout(const std::vector<PoseRecord>& poses, int keyframe_every) : every_(keyframe_every) {
    HOILCD_CHECK(keyframe_every >= 1);
    for (size_t f = 0; f < poses.size(); ++f) {
      HOILCD_CHECK_MSG(poses[f].frame == static_cast<int>(f), "poses are indexed by frame");
      if (f == 0 || poses[f].run != poses[f - 1].run) runs_.push_back({static_cast<int>(f), 0, 0, 0});
      runs_.back().last = static_cast<int>(f);
      run_of_frame_.push_back(static_cast<int>(runs_.size()) - 1);
    }
    for (Run& r : runs_) {
      r.first_node = static_cast<int>(keyframes_.size());
      for (int f = r.first; f <= r.last; f += every_) keyframes_.push_back(f);
      if (keyframes_.back() != r.last) keyframes_.push_back(r.last);
      r.nodes = static_cast<int>(keyframes_.size()) - r.first_node;
    }
  }
  const std::vector<int>& keyframes() const { return keyframes_; }
  // Each run's first node: where the run starts, at the dock.
  std::vector<int> FirstNodes() const {
    std::vector<int> out;
    for (const Run& r : runs_) out.push_back(r.first_node);
    return out;
  }
  // Whether nodes i - 1 and i are consecutive nodes of one run.
  bool SameRun(int i) const { return run_of_frame_[keyframes_[i - 1]] == run_of_frame_[keyframes_[i]]; }
  // The node of the keyframe at or before frame f (the run's last node for its last frame).
  int NodeAtOrBefore(int f) const {
    const Run& r = runs_[run_of_frame_[f]];
    return f == r.last ? r.first_node + r.nodes - 1 : r.first_node + (f - r.first) / every_;
  }
  // The node of the keyframe nearest to frame f in its run, counted in keyframe spacings.
  int NearestNode(int f) const {
    const Run& r = runs_[run_of_frame_[f]];
    const int k = static_cast<int>(std::lround(static_cast<double>(f - r.first) / every_));
    return r.first_node + std::min(k, r.nodes - 1);
  }

 private:
  struct Run {
    int first, last, first_node, nodes;
  };
  int every_;
  std::vector<Run> runs_;
  std::vector<int> run_of_frame_;
  std::vector<int> keyframes_;
};

}  // namespace

Eigen::Matrix3d OdometryNoise::Information(const Pose2d& step) const {
  const double d = std::hypot(step.x_m, step.y_m);
  const double span = std::max(d, correlation_length_m);
  const double sd_xy = std::max(floor_sd_m, distance_sd_frac * std::sqrt(d * span));
  const double var_theta = heading_var_rad2_per_m * d + heading_sd_rad_per_m * heading_sd_rad_per_m * d * span;
  const double sd_theta = std::max(floor_sd_rad, std::sqrt(var_theta));
  return Eigen::Vector3d(1 / (sd_xy * sd_xy), 1 / (sd_xy * sd_xy), 1 / (sd_theta * sd_theta)).asDiagonal();
}

OdometryNoise OdometryNoise::FromSceneJson(const std::string& scene_json, const std::string& path,
                                           double frame_rate_hz) {
  const nlohmann::json doc = ParseJsonOrDiscarded(scene_json);
  if (doc.is_discarded() || !doc.is_object()) throw InputError(path, "expected the resolved scene as a JSON object");
  if (!doc.contains("odometry") || !doc["odometry"].is_object()) {
    throw InputError(path + ": /odometry", "expected the odometry error model (an object); the pose graph needs it");
  }
  const nlohmann::json& odo = doc["odometry"];
  OdometryNoise noise;
  if (odo.contains("enabled") && odo["enabled"].is_boolean() && !odo["enabled"].get<bool>()) {
    noise.distance_sd_frac = noise.heading_sd_rad_per_m = noise.heading_var_rad2_per_m = 0;
    return noise;  // exact odometry: only the floors remain
  }
  if (!odo.contains("encoder_noise_frac") && !odo.contains("heading_noise_deg_sqrt_m")) {
    throw InputError(path + ": /odometry",
                     "expected an odometry error model with encoder_noise_frac or heading_noise_deg_sqrt_m");
  }
  const double wheelbase_m = Number(doc, "robot", "wheelbase_m", path);
  if (odo.contains("encoder_noise_frac")) {
    // Per-integration-step noise: k independent steps per frame shrink the random part by √k;
    // the constant slip and steering bias are counted as 1σ errors.
    const double rate_hz = Number(doc, "robot", "integration_rate_hz", path);
    const double k = std::max(1.0, rate_hz / frame_rate_hz);
    const double encoder = Number(doc, "odometry", "encoder_noise_frac", path);
    const double slip = Number(doc, "odometry", "slip_frac", path);
    const double steer_sd = Number(doc, "odometry", "steer_noise_deg", path) * kDegToRad;
    const double steer_bias = Number(doc, "odometry", "steer_bias_deg", path) * kDegToRad;
    noise.distance_sd_frac = std::sqrt(encoder * encoder / k + slip * slip);
    noise.heading_sd_rad_per_m = std::sqrt(steer_bias * steer_bias + steer_sd * steer_sd / k) / wheelbase_m;
    noise.heading_var_rad2_per_m = 0;
  } else {
    // Systematic + slip + heading random walk model (docs/models/robot.md): systematic terms as 1σ, slips
    // at 1 m/s² (longitudinal) and 1 m/s² lateral, the wheelbase error at 1 rad turned per metre.
    const double scale = Number(doc, "odometry", "error_scale", path);
    const double radius = Number(doc, "odometry", "wheel_radius_error_frac", path);
    const double slip = Number(doc, "odometry", "slip_per_accel_s2_m", path);
    const double offset = Number(doc, "odometry", "steer_offset_deg", path) * kDegToRad;
    const double wheelbase_err = Number(doc, "odometry", "wheelbase_error_frac", path);
    const double turn_slip = Number(doc, "odometry", "turn_slip_per_lat_accel_s2_m", path);
    const double walk = Number(doc, "odometry", "heading_noise_deg_sqrt_m", path) * kDegToRad;
    noise.distance_sd_frac = scale * std::hypot(radius, slip);
    noise.heading_sd_rad_per_m =
        scale * std::hypot(std::tan(offset) / wheelbase_m, std::hypot(wheelbase_err, turn_slip));
    noise.heading_var_rad2_per_m = std::pow(scale * walk, 2);
  }
  return noise;
}

SlamOptions::SlamOptions() { Table().FillDefaults(this); }

const OptionTable<SlamOptions>& SlamOptions::Table() {
  using O = SlamOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Nest("graph", &O::graph, PoseGraphOptions::Table())
          .Add("loop_threshold", &O::loop_threshold, NAN, "", R::Any().OrNaN(),
               "score a top-1 match must reach to be accepted (NaN: the operating point)")
          .Add("loop_sd_m", &O::loop_sd_m, 0.1, "m", R::Any().Above(0),
               "per-axis sigma of an appearance loop: uniform over the 0.2 m radius disk (r/2)")
          .Add("loop_yaw_sd_deg", &O::loop_yaw_sd_deg, 20, "deg", R::Any().Above(0),
               "sigma of the relative yaw of a loop (weak: revisits run the same way)")
          .Add("rpe_delta_m", &O::rpe_delta_m, 1.0, "m", R::Any().Above(0), "RPE pair spacing along the true path")
          .Add("keyframe_every", &O::keyframe_every, 5, "frames", R::Closed(1, kMaxFrames), "frames per graph node");
  return table;
}

std::string SlamOptions::Check() const { return Table().FirstProblem(*this); }

std::vector<LoopClosure> AcceptLoops(const std::vector<Query>& queries, const std::vector<std::vector<double>>& scores,
                                     double threshold, const std::vector<PoseRecord>& poses, double radius_m) {
  HOILCD_CHECK(queries.size() == scores.size());
  std::vector<LoopClosure> loops;
  for (size_t i = 0; i < queries.size(); ++i) {
    const Query& q = queries[i];
    if (q.NumTrueMatches() == 0 || q.database.empty()) continue;
    HOILCD_CHECK(scores[i].size() == q.database.size());
    const size_t best = std::max_element(scores[i].begin(), scores[i].end()) - scores[i].begin();
    if (!(scores[i][best] >= threshold)) continue;
    const int r = q.database[best];
    loops.push_back({q.frame, r, scores[i][best], BaseDistanceM(poses.at(q.frame), poses.at(r)) <= radius_m});
  }
  return loops;
}

std::vector<LoopClosure> OracleLoops(const std::vector<Query>& queries, const std::vector<PoseRecord>& poses,
                                     double radius_m) {
  std::vector<LoopClosure> loops;
  for (const Query& q : queries) {
    int best = -1;
    double best_d = radius_m;
    for (int r : q.database) {
      const double d = BaseDistanceM(poses.at(q.frame), poses.at(r));
      if (d <= best_d) best_d = d, best = r;
    }
    if (best >= 0) loops.push_back({q.frame, best, 1.0, true});
  }
  return loops;
}

double ThresholdAtFullPrecision(const std::vector<Query>& queries, const std::vector<std::vector<double>>& scores,
                                const std::vector<PoseRecord>& poses, double radius_m) {
  // Top-1 matches by descending score; the threshold stops just before the first false one.
  std::vector<LoopClosure> all =
      AcceptLoops(queries, scores, -std::numeric_limits<double>::infinity(), poses, radius_m);
  std::sort(all.begin(), all.end(), [](const LoopClosure& a, const LoopClosure& b) { return a.score > b.score; });
  double threshold = NAN;
  for (size_t i = 0; i < all.size();) {
    size_t j = i;
    bool any_false = false;
    while (j < all.size() && all[j].score == all[i].score) any_false |= !all[j++].is_true;
    if (any_false) break;  // a tie group holding a false loop cannot be split by a threshold
    threshold = all[i].score;
    i = j;
  }
  return threshold;
}

std::vector<double> ThresholdCandidates(const std::vector<Query>& queries,
                                        const std::vector<std::vector<double>>& scores, int count) {
  std::vector<double> values;
  for (size_t i = 0; i < queries.size(); ++i) {
    if (queries[i].NumTrueMatches() == 0 || scores[i].empty()) continue;
    values.push_back(*std::max_element(scores[i].begin(), scores[i].end()));
  }
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  if (count < 1 || static_cast<int>(values.size()) <= count) return values;
  std::vector<double> thinned;
  for (int k = 0; k < count; ++k) thinned.push_back(values[k * (values.size() - 1) / (count - 1)]);
  thinned.erase(std::unique(thinned.begin(), thinned.end()), thinned.end());
  return thinned;
}

std::vector<Pose2d> TruePoses(const std::vector<PoseRecord>& poses) {
  std::vector<Pose2d> out;
  for (const PoseRecord& p : poses) out.push_back({p.x_m, p.y_m, p.theta_rad});
  return out;
}

std::vector<Pose2d> OdometryPoses(const std::vector<PoseRecord>& poses) {
  std::vector<Pose2d> out;
  for (const PoseRecord& p : poses) out.push_back({p.odo_x_m, p.odo_y_m, p.odo_theta_rad});
  return out;
}

std::vector<int> Keyframes(const std::vector<PoseRecord>& poses, int keyframe_every) {
  return KeyframeLayout(poses, keyframe_every).keyframes();
}

std::vector<Pose2d> FramePosesFromKeyframes(const std::vector<PoseRecord>& poses,
                                            const std::vector<Pose2d>& keyframe_poses, int keyframe_every) {
  const std::vector<Pose2d> odometry = OdometryPoses(poses);
  const KeyframeLayout layout(poses, keyframe_every);
  const std::vector<int>& keyframes = layout.keyframes();
  HOILCD_CHECK(keyframes.size() == keyframe_poses.size());
  std::vector<Pose2d> out;
  for (size_t f = 0; f < poses.size(); ++f) {
    const size_t k = static_cast<size_t>(layout.NodeAtOrBefore(static_cast<int>(f)));
    out.push_back(Compose(keyframe_poses[k], Between(odometry[keyframes[k]], odometry[f])));
  }
  return out;
}

PoseGraph BuildPoseGraph(const std::vector<PoseRecord>& poses, const std::vector<LoopClosure>& loops,
                         const OdometryNoise& noise, const SlamOptions& options) {
  PoseGraph graph;
  const std::vector<Pose2d> odometry = OdometryPoses(poses);
  const int n = static_cast<int>(poses.size());
  const KeyframeLayout layout(poses, options.keyframe_every);
  const std::vector<int>& keyframes = layout.keyframes();
  for (int f : keyframes) graph.nodes.push_back(odometry[f]);
  graph.fixed = layout.FirstNodes();  // node 0 (the gauge) and each later run's start at the dock
  for (size_t i = 1; i < graph.nodes.size(); ++i) {
    if (!layout.SameRun(static_cast<int>(i))) continue;  // carried to the dock: no odometry between runs
    const Pose2d step = Between(graph.nodes[i - 1], graph.nodes[i]);
    graph.odometry.push_back({static_cast<int>(i - 1), static_cast<int>(i), step, noise.Information(step)});
  }
  const double yaw_sd = options.loop_yaw_sd_deg * kDegToRad;
  const Eigen::Matrix3d loop_information =
      Eigen::Vector3d(1 / std::pow(options.loop_sd_m, 2), 1 / std::pow(options.loop_sd_m, 2), 1 / (yaw_sd * yaw_sd))
          .asDiagonal();
  for (const LoopClosure& l : loops) {
    HOILCD_CHECK(l.query >= 0 && l.query < n && l.reference >= 0 && l.reference < n);
    const int a = layout.NearestNode(l.reference), b = layout.NearestNode(l.query);
    if (a == b) continue;  // within one keyframe spacing: says nothing the odometry does not
    // keyframe_a⁻¹·keyframe_b = (keyframe_a⁻¹·reference)·(query⁻¹·keyframe_b), with query = reference.
    const Pose2d measurement = Compose(Between(odometry[keyframes[a]], odometry[l.reference]),
                                       Between(odometry[l.query], odometry[keyframes[b]]));
    graph.loops.push_back({a, b, measurement, loop_information});
  }
  return graph;
}

namespace {
SlamScore Score(const std::vector<PoseRecord>& poses, std::vector<Pose2d> estimate, const SlamOptions& options) {
  if (poses.size() < 2) throw InputError("slam", "the dataset has fewer than 2 poses; no trajectory to score");
  const std::vector<Pose2d> truth = TruePoses(poses);
  SlamScore s;
  s.ate_rmse_m = AteRmseM(estimate, truth);
  std::vector<int> runs;  // RPE pairs stay within a recording run
  for (const PoseRecord& p : poses) runs.push_back(p.run);
  s.rpe_rmse_m = RpeRmseM(estimate, truth, options.rpe_delta_m, nullptr, runs);
  s.poses = std::move(estimate);
  return s;
}
}  // namespace

SlamScore ScoreOdometry(const std::vector<PoseRecord>& poses, const SlamOptions& options) {
  SlamScore s = Score(poses, OdometryPoses(poses), options);
  s.backend = "odometry";
  return s;
}

SlamScore SolveSlam(const std::vector<PoseRecord>& poses, const std::vector<LoopClosure>& loops,
                    const OdometryNoise& noise, const SlamOptions& options, const std::string& backend) {
  if (const std::string p = options.Check(); !p.empty()) throw InputError("slam", p);
  PoseGraphOptions graph_options = options.graph;
  graph_options.backend = backend;
  SlamScore s;
  if (loops.empty()) {
    s = ScoreOdometry(poses, options);
  } else {
    const PoseGraph graph = BuildPoseGraph(poses, loops, noise, options);
    s = Score(poses,
              FramePosesFromKeyframes(poses, OptimisePoseGraph(graph, graph_options).poses, options.keyframe_every),
              options);
  }
  s.backend = backend;
  s.loops_accepted = static_cast<int>(loops.size());
  for (const LoopClosure& l : loops) s.false_loops += l.is_true ? 0 : 1;
  return s;
}

}  // namespace hoilcd
