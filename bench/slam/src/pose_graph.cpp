#include "hoilcd/bench/slam/pose_graph.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include <Eigen/Cholesky>
#include <ceres/ceres.h>

#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

template <typename T>
T WrapAngle(const T& a) {
  const T two_pi(2.0 * M_PI);
  return a - two_pi * ceres::floor((a + T(M_PI)) / two_pi);
}

// Residual of one edge: sqrt(information)·[R_fromᵀ(t_to − t_from) − t_meas; wrap(θ_to − θ_from − θ_meas)].
class EdgeResidual {
 public:
  EdgeResidual(const Pose2d& measurement, const Eigen::Matrix3d& sqrt_information)
      : measurement_(measurement), sqrt_information_(sqrt_information) {}

  template <typename T>
  bool operator()(const T* from, const T* to, T* residual) const {
    const T c = ceres::cos(from[2]), s = ceres::sin(from[2]);
    const T dx = to[0] - from[0], dy = to[1] - from[1];
    Eigen::Matrix<T, 3, 1> e;
    e(0) = c * dx + s * dy - T(measurement_.x_m);
    e(1) = -s * dx + c * dy - T(measurement_.y_m);
    e(2) = WrapAngle(to[2] - from[2] - T(measurement_.theta_rad));
    Eigen::Map<Eigen::Matrix<T, 3, 1>> out(residual);
    out = sqrt_information_.cast<T>() * e;
    return true;
  }

  static ceres::CostFunction* Create(const PoseEdge& edge) {
    // Upper-triangular square root U with UᵀU = information.
    const Eigen::Matrix3d u = edge.information.llt().matrixU();
    return new ceres::AutoDiffCostFunction<EdgeResidual, 3, 3, 3>(new EdgeResidual(edge.measurement, u));
  }

 private:
  Pose2d measurement_;
  Eigen::Matrix3d sqrt_information_;
};

// Dynamic Covariance Scaling as a robust kernel on s = χ² (the M-estimator form of Agarwal et al.
// 2013): ρ(s) = s for s ≤ Φ, else 4Φs/(Φ+s) − Φ, so ρ'(s) = (2Φ/(Φ+s))², DCS's squared scale.
class DcsLoss : public ceres::LossFunction {
 public:
  explicit DcsLoss(double phi) : phi_(phi) {}
  void Evaluate(double s, double rho[3]) const override {
    if (s <= phi_) {
      rho[0] = s, rho[1] = 1, rho[2] = 0;
      return;
    }
    const double d = phi_ + s;
    rho[0] = 4 * phi_ * s / d - phi_;
    rho[1] = 4 * phi_ * phi_ / (d * d);
    rho[2] = -8 * phi_ * phi_ / (d * d * d);
  }

 private:
  double phi_;
};

// A back end is the loss it puts on loop edges (null: squared).
std::unique_ptr<ceres::LossFunction> LoopLoss(const PoseGraphOptions& options) {
  if (options.backend == "cauchy") return std::make_unique<ceres::CauchyLoss>(options.cauchy_scale);
  if (options.backend == "dcs") return std::make_unique<DcsLoss>(options.dcs_phi);
  return nullptr;
}

bool Finite(const Pose2d& p) { return std::isfinite(p.x_m) && std::isfinite(p.y_m) && std::isfinite(p.theta_rad); }

std::string EdgeProblem(const PoseEdge& e, int n, const char* kind, size_t index) {
  const std::string where = std::string(kind) + " edge " + std::to_string(index) + " (" + std::to_string(e.from) +
                            " -> " + std::to_string(e.to) + "): ";
  if (e.from < 0 || e.to < 0 || e.from >= n || e.to >= n) return where + "names a node that does not exist";
  if (e.from == e.to) return where + "joins a node to itself";
  if (!Finite(e.measurement)) return where + "measurement is not finite";
  if (!e.information.allFinite() || !e.information.isApprox(e.information.transpose()) ||
      e.information.llt().info() != Eigen::Success || e.information.determinant() <= 0) {
    return where + "information matrix is not symmetric positive definite";
  }
  return "";
}

}  // namespace

Pose2d Between(const Pose2d& a, const Pose2d& b) {
  const double c = std::cos(a.theta_rad), s = std::sin(a.theta_rad);
  const double dx = b.x_m - a.x_m, dy = b.y_m - a.y_m;
  return {c * dx + s * dy, -s * dx + c * dy, WrapAngle(b.theta_rad - a.theta_rad)};
}

Pose2d Compose(const Pose2d& a, const Pose2d& d) {
  const double c = std::cos(a.theta_rad), s = std::sin(a.theta_rad);
  return {a.x_m + c * d.x_m - s * d.y_m, a.y_m + s * d.x_m + c * d.y_m, WrapAngle(a.theta_rad + d.theta_rad)};
}

std::string PoseGraph::Check() const {
  const int n = static_cast<int>(nodes.size());
  if (n == 0) return "the graph has no node";
  for (int i = 0; i < n; ++i)
    if (!Finite(nodes[i])) return "node " + std::to_string(i) + " is not finite";
  if (fixed.empty()) return "no node is fixed: the graph's gauge is free";
  std::string fixed_text;  // "node 0", "a fixed node (0, 40)"
  for (int f : fixed) {
    if (f < 0 || f >= n) return "fixed node " + std::to_string(f) + " does not exist";
    fixed_text += (fixed_text.empty() ? "" : ", ") + std::to_string(f);
  }
  fixed_text = fixed.size() == 1 ? "node " + fixed_text : "a fixed node (" + fixed_text + ")";
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const auto* edges : {&odometry, &loops}) {
    const char* kind = edges == &odometry ? "odometry" : "loop";
    for (size_t k = 0; k < edges->size(); ++k) {
      const PoseEdge& e = (*edges)[k];
      if (std::string p = EdgeProblem(e, n, kind, k); !p.empty()) return p;
      parent[root(e.from)] = root(e.to);
    }
  }
  std::vector<bool> anchored(n, false);  // by root: holds a fixed node
  for (int f : fixed) anchored[root(f)] = true;
  for (int i = 0; i < n; ++i) {
    if (!anchored[root(i)]) {
      return "singular graph: node " + std::to_string(i) + " is not connected to " + fixed_text + " by any edge";
    }
  }
  return "";
}

PoseGraphOptions::PoseGraphOptions() { Table().FillDefaults(this); }

const OptionTable<PoseGraphOptions>& PoseGraphOptions::Table() {
  using O = PoseGraphOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("backend", &O::backend, "dcs", PoseGraphBackends(),
               "how loop edges are weighted: plain least squares, a Cauchy loss, or Dynamic Covariance Scaling")
          .Add("cauchy_scale", &O::cauchy_scale, 1.0, "", R::Any().Above(0),
               "chi (Mahalanobis, dimensionless) where the Cauchy loss bends")
          .Add("dcs_phi", &O::dcs_phi, 1.0, "", R::Any().Above(0),
               "Phi of Dynamic Covariance Scaling, a chi^2 (dimensionless)")
          .Add("max_iterations", &O::max_iterations, 100, "", R::Closed(1, 10000), "Levenberg-Marquardt iterations");
  return table;
}

std::string PoseGraphOptions::Check() const { return Table().FirstProblem(*this); }

const std::vector<std::string>& PoseGraphBackends() {
  static const std::vector<std::string> kBackends = {"plain", "cauchy", "dcs"};
  return kBackends;
}

PoseGraphSolution OptimisePoseGraph(const PoseGraph& graph, const PoseGraphOptions& options) {
  if (const std::string p = options.Check(); !p.empty()) throw InputError("pose graph", p);
  if (const std::string p = graph.Check(); !p.empty()) throw InputError("pose graph", p);
  const int n = static_cast<int>(graph.nodes.size());
  std::vector<double> state(3 * n);
  for (int i = 0; i < n; ++i) {
    state[3 * i] = graph.nodes[i].x_m, state[3 * i + 1] = graph.nodes[i].y_m,
              state[3 * i + 2] = graph.nodes[i].theta_rad;
  }
  ceres::Problem problem;
  for (const PoseEdge& e : graph.odometry) {
    problem.AddResidualBlock(EdgeResidual::Create(e), nullptr, &state[3 * e.from], &state[3 * e.to]);
  }
  for (const PoseEdge& e : graph.loops) {
    problem.AddResidualBlock(EdgeResidual::Create(e), LoopLoss(options).release(), &state[3 * e.from],
                             &state[3 * e.to]);
  }
  for (int f : graph.fixed) {  // a fixed node no edge reaches is not in the problem, and stays put anyway
    if (problem.HasParameterBlock(&state[3 * f])) problem.SetParameterBlockConstant(&state[3 * f]);
  }

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  // Eigen's sparse Cholesky, not CHOLMOD's: CHOLMOD factorises on OpenMP threads of its own,
  // whatever num_threads says (350 k futex calls in one paper_room bench's SLAM step, twice its
  // time). The poses agree to ~1e-12 relative: no printed figure moves.
  solver.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
  solver.max_num_iterations = options.max_iterations;
  solver.num_threads = 1;  // one thread: byte-identical results on any machine load
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);

  PoseGraphSolution out;
  out.iterations = static_cast<int>(summary.iterations.size());
  out.final_cost = summary.final_cost;
  for (int i = 0; i < n; ++i) {
    out.poses.push_back({state[3 * i], state[3 * i + 1], WrapAngle(state[3 * i + 2])});
    if (!Finite(out.poses.back())) {
      throw InputError("pose graph", "the optimiser returned a non-finite pose (" + summary.message + ")");
    }
  }
  if (!summary.IsSolutionUsable()) {
    throw InputError("pose graph", "the optimiser failed: " + summary.message);
  }
  const auto loss = LoopLoss(options);
  for (const PoseEdge& e : graph.loops) {
    const Pose2d err_pose = Between(Between(out.poses[e.from], out.poses[e.to]), e.measurement);
    const Eigen::Vector3d err(err_pose.x_m, err_pose.y_m, err_pose.theta_rad);
    const double chi2 = err.dot(e.information * err);
    double rho[3] = {chi2, 1, 0};
    if (loss) loss->Evaluate(chi2, rho);
    out.loop_weights.push_back(rho[1]);
  }
  return out;
}

std::string PoseGraphToG2o(const PoseGraph& graph, const std::vector<Pose2d>& poses) {
  std::string out;
  char line[512];
  for (size_t i = 0; i < poses.size(); ++i) {
    std::snprintf(line, sizeof(line), "VERTEX_SE2 %zu %.17g %.17g %.17g\n", i, poses[i].x_m, poses[i].y_m,
                  poses[i].theta_rad);
    out += line;
  }
  if (!poses.empty() && !graph.fixed.empty()) {
    out += "FIX";
    for (int f : graph.fixed) out += " " + std::to_string(f);
    out += "\n";
  }
  for (const auto* edges : {&graph.odometry, &graph.loops}) {
    for (const PoseEdge& e : *edges) {
      const Eigen::Matrix3d& m = e.information;
      std::snprintf(line, sizeof(line), "EDGE_SE2 %d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n",
                    e.from, e.to, e.measurement.x_m, e.measurement.y_m, e.measurement.theta_rad, m(0, 0), m(0, 1),
                    m(0, 2), m(1, 1), m(1, 2), m(2, 2));
      out += line;
    }
  }
  return out;
}

}  // namespace hoilcd
