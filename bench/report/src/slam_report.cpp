#include "hoilcd/bench/report/slam_report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "hoilcd/bench/evaluation/json_number.h"
#include "hoilcd/bench/evaluation/protocol.h"
#include "hoilcd/bench/report/chart.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

nlohmann::json ScoreJson(const SlamScore& s) {
  return {{"ate_rmse_m", JsonNumber(s.ate_rmse_m)},
          {"rpe_rmse_m", JsonNumber(s.rpe_rmse_m)},
          {"loops_accepted", s.loops_accepted},
          {"false_loops", s.false_loops}};
}

// A trajectory (one pose per frame of `frames`), with a gap between recording runs: the robot was
// carried to its dock, not driven there.
Series Path(const std::string& label, const std::vector<Pose2d>& poses, const std::vector<PoseRecord>& frames,
            cv::Scalar colour) {
  Series s;
  s.label = label;
  for (size_t i = 0; i < poses.size(); ++i) {
    if (i > 0 && i < frames.size() && frames[i].run != frames[i - 1].run) s.x.push_back(NAN), s.y.push_back(NAN);
    s.x.push_back(poses[i].x_m), s.y.push_back(poses[i].y_m);
  }
  s.colour = colour;
  return s;
}

}  // namespace

nlohmann::json SlamSummaryJson(const SlamResult& slam) {
  nlohmann::json j;
  j["backend"] = slam.backend;
  j["backends"] = PoseGraphBackends();
  j["odometry"] = ScoreJson(slam.odometry);
  j["oracle"] = ScoreJson(slam.oracle.empty() ? slam.odometry : slam.oracle.front());
  for (const SlamScore& s : slam.oracle)
    if (s.backend == slam.backend) j["oracle"] = ScoreJson(s);
  for (const SlamScore& s : slam.oracle) j["oracle"]["backends"][s.backend] = ScoreJson(s);
  j["odometry_noise"] = {{"distance_sd_frac", slam.noise.distance_sd_frac},
                         {"heading_sd_rad_per_m", slam.noise.heading_sd_rad_per_m},
                         {"heading_var_rad2_per_m", slam.noise.heading_var_rad2_per_m}};
  j["seconds"] = slam.seconds;
  j["notes"] = slam.notes;
  return j;
}

nlohmann::json MethodSlamJson(const MethodSlam& m) {
  nlohmann::json j;
  j["loop_threshold"] = JsonNumber(m.threshold);
  j["threshold_source"] = m.threshold_source;
  for (const SlamScore& s : m.backends) j[s.backend] = ScoreJson(s);
  j["ate_vs_threshold"] = {
      {"threshold", m.curve_threshold}, {"loops_accepted", m.curve_loops}, {"ate_rmse_m", m.curve_ate_m}};
  return j;
}

std::string SlamMarkdown(const SlamResult& slam, const SlamOptions& options) {
  std::ostringstream md;
  md << "## SLAM consequence (pose graph, ATE / RPE over 1 m, metres)\n\n"
     << "Odometry alone: ATE " << Fixed(slam.odometry.ate_rmse_m) << ", RPE " << Fixed(slam.odometry.rpe_rmse_m)
     << ". Oracle (every query's nearest true match as a loop): ";
  for (const SlamScore& s : slam.oracle) md << s.backend << " ATE " << Fixed(s.ate_rmse_m) << "; ";
  md << "headline back end `" << slam.backend << "`.\n\n| method | threshold (source) | loops | false |";
  for (const std::string& b : PoseGraphBackends()) md << " ATE " << b << " | RPE " << b << " |";
  md << "\n|---|---|---|---|";
  for (size_t i = 0; i < PoseGraphBackends().size(); ++i) md << "---|---|";
  md << "\n";
  for (const MethodSlam& m : slam.methods) {
    md << "| " << m.method << " | " << Fixed(m.threshold, 2) << " (" << m.threshold_source << ") | " << m.loops.size()
       << " | " << (m.backends.empty() ? 0 : m.backends.front().false_loops) << " |";
    for (const SlamScore& s : m.backends) md << " " << Fixed(s.ate_rmse_m) << " | " << Fixed(s.rpe_rmse_m) << " |";
    md << "\n";
  }
  md << "\nLoop edges are appearance-only: zero relative pose, σ = " << options.loop_sd_m
     << " m per axis (a uniform spread over the " << ProtocolOptions().radius_m
     << " m true-match disk) and a weak σ = " << options.loop_yaw_sd_deg
     << "° on yaw; odometry edges are weighted by the scene's odometry "
        "error model. Back ends: `plain` least squares, `cauchy` loss on loops, `dcs` (Dynamic Covariance "
        "Scaling). The graph (g2o) and optimised trajectories (TUM) are in `slam/`.\n\n";
  for (const std::string& note : slam.notes) md << "- " << note << "\n";
  if (!slam.notes.empty()) md << "\n";
  return md.str();
}

std::string PlanarTum(const std::vector<PoseRecord>& poses, const std::vector<Pose2d>& trajectory) {
  std::string out;
  char line[256];
  for (size_t i = 0; i < trajectory.size() && i < poses.size(); ++i) {
    const Pose2d& p = trajectory[i];
    std::snprintf(line, sizeof(line), "%.6f %.9f %.9f 0 0 0 %.9f %.9f\n", poses[i].time_s, p.x_m, p.y_m,
                  std::sin(p.theta_rad / 2), std::cos(p.theta_rad / 2));
    out += line;
  }
  return out;
}

std::vector<std::string> WriteSlamFiles(const SlamResult& slam, const std::vector<PoseRecord>& poses,
                                        const SlamOptions& options, const std::string& dir) {
  const std::vector<Pose2d> truth = TruePoses(poses);
  WriteFileAtomic(dir + "/slam/groundtruth_tum.txt", PlanarTum(poses, truth));
  WriteFileAtomic(dir + "/slam/odometry_tum.txt", PlanarTum(poses, slam.odometry.poses));
  for (const SlamScore& s : slam.oracle) {
    if (s.backend == slam.backend) WriteFileAtomic(dir + "/slam/oracle_tum.txt", PlanarTum(poses, s.poses));
  }
  for (const MethodSlam& m : slam.methods) {
    const SlamScore& s = m.Headline(slam.backend);
    WriteFileAtomic(dir + "/slam/" + m.method + "_tum.txt", PlanarTum(poses, s.poses));
    const PoseGraph graph = BuildPoseGraph(poses, m.loops, slam.noise, options);
    WriteFileAtomic(dir + "/slam/" + m.method + ".g2o", PoseGraphToG2o(graph, graph.nodes));
  }
  // Trajectories: truth, odometry and the optimised path (headline back end) of each method that
  // accepted a loop; the others' paths are the odometry's and would only hide it.
  std::vector<Series> series = {Path("true", truth, poses, cv::Scalar(0, 0, 0)),
                                Path("odometry", slam.odometry.poses, poses, cv::Scalar(160, 160, 160))};
  for (size_t i = 0; i < slam.methods.size(); ++i) {
    const SlamScore& s = slam.methods[i].Headline(slam.backend);
    if (s.loops_accepted > 0) series.push_back(Path(slam.methods[i].method, s.poses, poses, PaletteColour(i)));
  }
  PlotOptions o;
  o.title = "Trajectories after pose-graph optimisation (" + slam.backend + ")";
  o.x_label = "x (m)";
  o.y_label = "y (m)";
  o.equal_aspect = true;
  o.width_px = 1000;
  WritePng(dir + "/slam_trajectories.png", LinePlot(series, o));
  std::vector<Series> curves;
  for (size_t i = 0; i < slam.methods.size(); ++i) {
    Series c;
    c.label = slam.methods[i].method;
    // Scores differ in scale between methods (inliers, fused ranks): plot against loops accepted.
    for (int n : slam.methods[i].curve_loops) c.x.push_back(n);
    c.y = slam.methods[i].curve_ate_m;
    c.markers = true;
    c.colour = PaletteColour(i);
    if (!c.x.empty()) curves.push_back(c);
  }
  PlotOptions co;
  co.title =
      "ATE as the loop threshold falls (" + slam.backend + "; odometry ATE " + Fixed(slam.odometry.ate_rmse_m) + " m)";
  co.x_label = "loops accepted (threshold lowered to the right)";
  co.y_label = "ATE RMSE (m)";
  std::vector<std::string> figures = {"slam_trajectories.png"};
  if (!curves.empty()) {
    WritePng(dir + "/slam_ate_vs_threshold.png", LinePlot(curves, co));
    figures.push_back("slam_ate_vs_threshold.png");
  }
  return figures;
}

}  // namespace hoilcd
