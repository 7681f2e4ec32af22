// An SE(2) pose graph optimised with Ceres Solver: one node per frame, odometry edges between
// consecutive frames and loop edges from accepted loop closures; fixed nodes anchor the gauge. Back
// ends differ only in how loop edges are weighted: plain least squares, a Cauchy robust loss, or
// Dynamic Covariance Scaling (Agarwal et al. 2013), which scales a loop's information by
// min(1, 2Φ/(Φ+χ²))².
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

struct Pose2d {
  double x_m = 0, y_m = 0, theta_rad = 0;
};

// b expressed in a's frame (a⁻¹·b), angle wrapped to (-π, π].
Pose2d Between(const Pose2d& a, const Pose2d& b);
// a·delta.
Pose2d Compose(const Pose2d& a, const Pose2d& delta);

// A relative-pose constraint: pose `to` seen from pose `from` is `measurement`.
struct PoseEdge {
  int from = 0, to = 0;
  Pose2d measurement;
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();  // (x m, y m, θ rad)⁻², symmetric PD
};

struct PoseGraph {
  std::vector<Pose2d> nodes;  // initial estimates
  // Nodes held at their initial estimate: node 0 fixes the gauge; with recording runs, each run's
  // first node too (the run starts at the known dock, where its odometry restarts).
  std::vector<int> fixed = {0};
  std::vector<PoseEdge> odometry;  // sequential, always trusted (squared loss)
  std::vector<PoseEdge> loops;     // weighted by the back end
  // Empty when usable, else what is wrong (no node, no fixed node or one that does not exist, an
  // edge naming a missing node or itself, a non-finite measurement, an information matrix that is
  // not symmetric positive definite, a node no edge connects to a fixed node). A graph is data,
  // not options: no table, checked by hand.
  std::string Check() const;
};

// Defaults and ranges: Table() in pose_graph.cpp.
struct PoseGraphOptions {
  std::string backend;  // "plain" | "cauchy" | "dcs"
  double cauchy_scale;  // χ (Mahalanobis, dimensionless) where the Cauchy loss bends
  double dcs_phi;       // Φ of Dynamic Covariance Scaling, χ² (dimensionless)
  int max_iterations;   // Levenberg–Marquardt iterations

  PoseGraphOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<PoseGraphOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// The back ends, in report order.
const std::vector<std::string>& PoseGraphBackends();

struct PoseGraphSolution {
  std::vector<Pose2d> poses;
  int iterations = 0;
  double final_cost = 0;
  std::vector<double> loop_weights;  // per loop edge: effective weight ρ'(χ²) in [0, 1]
};

// Optimises the graph. InputError("pose graph", ...) when Check() fails or the solver does not
// return finite poses; never returns NaN.
PoseGraphSolution OptimisePoseGraph(const PoseGraph& graph, const PoseGraphOptions& options);

// The graph in g2o's text format (VERTEX_SE2, one FIX line naming the fixed nodes, EDGE_SE2 with the
// upper triangle of the information matrix), nodes at `poses` (pass graph.nodes for the initial
// estimate).
std::string PoseGraphToG2o(const PoseGraph& graph, const std::vector<Pose2d>& poses);

}  // namespace hoilcd
