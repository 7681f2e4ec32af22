#include "hoilcd/bench/slam/pose_graph.h"

#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "hoilcd/core/util/error.h"
#include "option_properties.h"

namespace hoilcd {
namespace {

// Three counter-clockwise laps of a 1.2 m circle, 0.05 m apart.
std::vector<Pose2d> CircleLaps(int laps = 3) {
  const double radius = 1.2, step = 0.05;
  const int per_lap = static_cast<int>(std::round(2 * M_PI * radius / step));
  std::vector<Pose2d> poses;
  for (int i = 0; i < laps * per_lap; ++i) {
    const double a = 2 * M_PI * i / per_lap;
    poses.push_back({radius * std::cos(a), radius * std::sin(a), std::remainder(a + M_PI / 2, 2 * M_PI)});
  }
  return poses;
}

PoseGraph ExactGraph(const std::vector<Pose2d>& truth, int per_lap) {
  PoseGraph g;
  // Initial guess: the truth's steps integrated with a heading bias, so it drifts away.
  g.nodes.push_back(truth[0]);
  for (size_t i = 1; i < truth.size(); ++i) {
    Pose2d step = Between(truth[i - 1], truth[i]);
    step.theta_rad += 0.004;
    g.nodes.push_back(Compose(g.nodes.back(), step));
  }
  const Eigen::Matrix3d info = Eigen::Vector3d(1e4, 1e4, 1e5).asDiagonal();
  for (size_t i = 1; i < truth.size(); ++i)
    g.odometry.push_back({int(i - 1), int(i), Between(truth[i - 1], truth[i]), info});
  for (int q = per_lap; q < static_cast<int>(truth.size()); q += 10)
    g.loops.push_back({q - per_lap, q, Between(truth[q - per_lap], truth[q]), info});
  return g;
}

TEST(PoseGraphTest, RecoversKnownTrajectoryFromExactOdometryAndLoopsToOneMillimetreWithEveryBackend) {
  const std::vector<Pose2d> truth = CircleLaps();
  const int per_lap = static_cast<int>(truth.size()) / 3;
  const PoseGraph graph = ExactGraph(truth, per_lap);
  double initial_error = 0;
  for (size_t i = 0; i < truth.size(); ++i)
    initial_error =
        std::max(initial_error, std::hypot(graph.nodes[i].x_m - truth[i].x_m, graph.nodes[i].y_m - truth[i].y_m));
  ASSERT_GT(initial_error, 0.5);  // the start really is far off
  for (const std::string& backend : PoseGraphBackends()) {
    PoseGraphOptions options;
    options.backend = backend;
    const PoseGraphSolution s = OptimisePoseGraph(graph, options);
    ASSERT_EQ(s.poses.size(), truth.size());
    for (size_t i = 0; i < truth.size(); ++i) {
      EXPECT_LT(std::hypot(s.poses[i].x_m - truth[i].x_m, s.poses[i].y_m - truth[i].y_m), 1e-3) << backend << " " << i;
      EXPECT_LT(std::abs(std::remainder(s.poses[i].theta_rad - truth[i].theta_rad, 2 * M_PI)), 1e-3) << backend;
    }
  }
}

TEST(PoseGraphTest, DcsAndCauchyDownweightAFalseLoopThatPlainTrusts) {
  const std::vector<Pose2d> truth = CircleLaps();
  const int per_lap = static_cast<int>(truth.size()) / 3;
  PoseGraph graph = ExactGraph(truth, per_lap);
  graph.loops.push_back({10, per_lap + per_lap / 2, Pose2d{}, graph.loops[0].information});  // 2.4 m apart
  std::map<std::string, double> weight;
  for (const std::string& backend : PoseGraphBackends()) {
    PoseGraphOptions options;
    options.backend = backend;
    weight[backend] = OptimisePoseGraph(graph, options).loop_weights.back();
  }
  EXPECT_EQ(weight["plain"], 1.0);
  EXPECT_LT(weight["cauchy"], 1e-3);
  EXPECT_LT(weight["dcs"], 1e-3);
}

TEST(PoseGraphTest, BetweenAndComposeRoundTrip) {
  const Pose2d a{1.0, -2.0, 2.5}, b{-0.3, 0.7, -3.0};
  const Pose2d back = Compose(a, Between(a, b));
  EXPECT_NEAR(back.x_m, b.x_m, 1e-12);
  EXPECT_NEAR(back.y_m, b.y_m, 1e-12);
  EXPECT_NEAR(back.theta_rad, b.theta_rad, 1e-12);
}

std::string ProblemOf(const PoseGraph& g) {
  try {
    OptimisePoseGraph(g, PoseGraphOptions{});
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PoseGraphTest, UnusableGraphsAreClearErrorsNotNaN) {
  PoseGraph empty;
  EXPECT_NE(ProblemOf(empty).find("no node"), std::string::npos);

  PoseGraph g;
  g.nodes = {Pose2d{}, Pose2d{1, 0, 0}, Pose2d{2, 0, 0}};
  g.odometry.push_back({0, 1, Pose2d{1, 0, 0}, Eigen::Matrix3d::Identity()});
  EXPECT_NE(ProblemOf(g).find("singular graph: node 2 is not connected"), std::string::npos);

  PoseGraph missing = g;
  missing.odometry.push_back({1, 5, Pose2d{1, 0, 0}, Eigen::Matrix3d::Identity()});
  EXPECT_NE(ProblemOf(missing).find("names a node that does not exist"), std::string::npos);

  PoseGraph self = g;
  self.loops.push_back({1, 1, Pose2d{}, Eigen::Matrix3d::Identity()});
  EXPECT_NE(ProblemOf(self).find("joins a node to itself"), std::string::npos);

  PoseGraph degenerate = g;
  degenerate.odometry.push_back({1, 2, Pose2d{1, 0, 0}, Eigen::Vector3d(1, 1, 0).asDiagonal()});
  EXPECT_NE(ProblemOf(degenerate).find("not symmetric positive definite"), std::string::npos);

  PoseGraph nan_measurement = g;
  nan_measurement.odometry.push_back({1, 2, Pose2d{NAN, 0, 0}, Eigen::Matrix3d::Identity()});
  EXPECT_NE(ProblemOf(nan_measurement).find("measurement is not finite"), std::string::npos);

  PoseGraph nan_node = g;
  nan_node.nodes[1].x_m = NAN;
  EXPECT_NE(ProblemOf(nan_node).find("node 1 is not finite"), std::string::npos);
}

// Two chains joined by no edge (two recording runs): each needs a fixed node of its own, which
// stays where it is while the chain's loose end follows its measurement.
TEST(PoseGraphTest, EveryChainNeedsAFixedNodeAndFixedNodesStayPut) {
  PoseGraph g;
  g.nodes = {Pose2d{}, Pose2d{1, 0, 0}, Pose2d{5, 5, 0}, Pose2d{6.5, 5, 0}};
  g.odometry = {{0, 1, Pose2d{1, 0, 0}, Eigen::Matrix3d::Identity()},
                {2, 3, Pose2d{1, 0, 0}, Eigen::Matrix3d::Identity()}};
  EXPECT_EQ(g.Check(), "singular graph: node 2 is not connected to node 0 by any edge");
  g.fixed = {0, 2};
  EXPECT_EQ(g.Check(), "");
  const PoseGraphSolution solution = OptimisePoseGraph(g, PoseGraphOptions());
  EXPECT_EQ(solution.poses[2].x_m, 5);  // held, not averaged with its neighbour
  EXPECT_NEAR(solution.poses[3].x_m, 6, 1e-6);
  EXPECT_NE(PoseGraphToG2o(g, g.nodes).find("FIX 0 2\n"), std::string::npos);
  g.fixed = {2};
  EXPECT_EQ(g.Check(), "singular graph: node 0 is not connected to node 2 by any edge");
  g.fixed = {0, 3};
  g.odometry.pop_back();
  EXPECT_EQ(g.Check(), "singular graph: node 2 is not connected to a fixed node (0, 3) by any edge");
  g.fixed = {0, 4};
  EXPECT_EQ(g.Check(), "fixed node 4 does not exist");
  g.fixed.clear();
  EXPECT_EQ(g.Check(), "no node is fixed: the graph's gauge is free");
}

TEST(PoseGraphTest, UnknownBackendIsRejected) {
  PoseGraphOptions options;
  options.backend = "gauss";
  EXPECT_EQ(options.Check(), "backend: must be one of: plain, cauchy, dcs (got 'gauss')");
  options = PoseGraphOptions{};
  options.dcs_phi = 0;
  EXPECT_NE(options.Check().find("dcs_phi"), std::string::npos);
  options = PoseGraphOptions{};
  options.cauchy_scale = -1;
  EXPECT_NE(options.Check().find("cauchy_scale"), std::string::npos);
  options = PoseGraphOptions{};
  options.max_iterations = 0;
  EXPECT_NE(options.Check().find("max_iterations"), std::string::npos);
}

TEST(PoseGraphTest, OptionsHoldTheirTablesDefaultsAndEveryBoundIsChecked) {
  EXPECT_EQ(PoseGraphOptions().backend, "dcs");
  ExpectConstructedHoldsTheTableDefaults<PoseGraphOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<PoseGraphOptions>(), 4);
}

TEST(PoseGraphTest, G2oTextHasOneVertexPerNodeOneEdgePerConstraintAndFixesNodeZero) {
  const std::vector<Pose2d> truth = CircleLaps(2);
  const PoseGraph g = ExactGraph(truth, static_cast<int>(truth.size()) / 2);
  const std::string text = PoseGraphToG2o(g, g.nodes);
  size_t vertices = 0, edges = 0, pos = 0;
  while ((pos = text.find("VERTEX_SE2 ", pos)) != std::string::npos) ++vertices, ++pos;
  pos = 0;
  while ((pos = text.find("EDGE_SE2 ", pos)) != std::string::npos) ++edges, ++pos;
  EXPECT_EQ(vertices, g.nodes.size());
  EXPECT_EQ(edges, g.odometry.size() + g.loops.size());
  EXPECT_NE(text.find("FIX 0\n"), std::string::npos);
  EXPECT_EQ(text.rfind("VERTEX_SE2 0 ", 0), 0u);
}

}  // namespace
}  // namespace hoilcd
