#include "hoilcd/bench/evaluation/protocol.h"

#include <algorithm>
#include <cmath>

#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

double WrapAngleRad(double angle_rad) { return std::remainder(angle_rad, 2.0 * M_PI); }

}  // namespace

ProtocolOptions::ProtocolOptions() { Table().FillDefaults(this); }

const OptionTable<ProtocolOptions>& ProtocolOptions::Table() {
  using O = ProtocolOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("protocol", &O::protocol, "laps", {"laps", "revisit", "runs"},
               "laps: database = first lap, queries = later laps; revisit: every frame older than the exclusion "
               "window; runs: database = the first recording run, queries = the later runs")
          .Add("radius_m", &O::radius_m, 0.2, "m", R::Any().Above(0),
               "base positions this close make a true match (paper)")
          .Add("heading_tolerance_deg", &O::heading_tolerance_deg, -1, "deg", R::Any().AtMost(180),
               "max heading difference of a true match (negative: off)")
          .Add("exclusion_window_s", &O::exclusion_window_s, 10, "s", R::Any().AtLeast(0),
               "frames with |t_query - t_ref| at most this are left out of the query's database")
          .Add("ground_truth", &O::ground_truth, "odometry", {"odometry", "true", "overlap"},
               "what decides true matches: odometric positions (paper), true positions, or the view the frames share")
          .Add("overlap_threshold", &O::overlap_threshold, 0.5, "", R::Any().Above(0).AtMost(1),
               "ground truth overlap: fraction of the query's static pixels the reference must see")
          .Add("overlap_stride_px", &O::overlap_stride_px, 4, "px", R::Any().AtLeast(1).AtMost(64),
               "ground truth overlap: sample every this-th pixel of the query's rows and columns")
          .Add("overlap_depth_tolerance_m", &O::overlap_depth_tolerance_m, 0.05, "m", R::Any().Above(0).AtMost(1),
               "ground truth overlap: a reprojected point this far outside the reference's depths is not seen");
  return table;
}

std::string ProtocolOptions::Check() const { return Table().FirstProblem(*this); }

void CheckProtocolFits(const Dataset& dataset, const ProtocolOptions& options) {
  if (options.protocol == "runs" && dataset.runs().size() < 2) {
    throw InputError(dataset.dir(),
                     "holds one recording run; --protocol runs needs two or more (render a scene "
                     "with /runs)");
  }
}

bool IsQueryFrame(const ProtocolOptions& options, int lap, int run) {
  if (options.protocol == "revisit") return true;
  return options.protocol == "runs" ? run > 0 : lap > 0;
}

int Query::NumTrueMatches() const {
  return static_cast<int>(std::count(is_true_match.begin(), is_true_match.end(), 1));
}

std::vector<PoseRecord> LabelPoses(const std::vector<PoseRecord>& poses, const std::string& ground_truth) {
  HOILCD_CHECK_MSG(ground_truth == "odometry" || ground_truth == "true" || ground_truth == "overlap", ground_truth);
  std::vector<PoseRecord> out = poses;
  if (ground_truth == "odometry") {
    for (PoseRecord& p : out) {
      p.x_m = p.odo_x_m;
      p.y_m = p.odo_y_m;
      p.theta_rad = p.odo_theta_rad;
    }
  }
  return out;
}

std::string OtherGroundTruth(const std::string& ground_truth) {
  return ground_truth == "odometry" ? "true" : "odometry";  // overlap is compared with the paper's
}

std::vector<int> LapIndexFromPoses(const std::vector<PoseRecord>& poses) {
  // The heading turned since the start of the frame's run: each run starts at the dock afresh.
  std::vector<double> turned_rad(poses.size(), 0.0);
  double turned_by_all_runs_rad = 0;
  for (size_t i = 0; i < poses.size(); ++i) {
    const bool run_starts = i == 0 || poses[i].run != poses[i - 1].run;
    if (!run_starts) turned_rad[i] = turned_rad[i - 1] + WrapAngleRad(poses[i].theta_rad - poses[i - 1].theta_rad);
    if (i + 1 == poses.size() || poses[i + 1].run != poses[i].run) turned_by_all_runs_rad += turned_rad[i];
  }
  const double direction = turned_by_all_runs_rad < 0 ? -1.0 : 1.0;
  // A lap that ends exactly at 2π (up to rounding) belongs to the next lap.
  constexpr double kToleranceRad = 1e-9;
  std::vector<int> laps(poses.size(), 0);
  int lap = 0, run_first_lap = 0;
  for (size_t i = 0; i < poses.size(); ++i) {
    if (i > 0 && poses[i].run != poses[i - 1].run) run_first_lap = ++lap;  // a run's first lap is a new one
    const double laps_turned = (direction * turned_rad[i] + kToleranceRad) / (2.0 * M_PI);
    lap = std::max(lap, run_first_lap + static_cast<int>(std::floor(std::max(0.0, laps_turned))));
    laps[i] = lap;
  }
  return laps;
}

double BaseDistanceM(const PoseRecord& a, const PoseRecord& b) { return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m); }

bool IsTrueMatch(const PoseRecord& query, const PoseRecord& reference, const ProtocolOptions& options) {
  if (BaseDistanceM(query, reference) > options.radius_m) return false;
  if (options.heading_tolerance_deg < 0) return true;
  const double difference_deg = std::abs(WrapAngleRad(query.theta_rad - reference.theta_rad)) * 180.0 / M_PI;
  return difference_deg <= options.heading_tolerance_deg;
}

std::vector<Query> BuildQueries(const std::vector<PoseRecord>& poses, const ProtocolOptions& options) {
  const std::string problem = options.Check();
  HOILCD_CHECK_MSG(problem.empty(), problem);
  const std::vector<PoseRecord> label = LabelPoses(poses, options.ground_truth);
  const std::vector<int> laps = LapIndexFromPoses(label);
  // The database of every query: the frames that are not queries (laps, runs); revisit: older frames.
  const bool revisit = options.protocol == "revisit";
  std::vector<uint8_t> is_query(poses.size());
  for (size_t f = 0; f < poses.size(); ++f) is_query[f] = IsQueryFrame(options, laps[f], poses[f].run);
  std::vector<Query> queries;
  for (size_t q = 0; q < poses.size(); ++q) {
    if (!is_query[q]) continue;
    Query query;
    query.frame = poses[q].frame;
    query.lap = laps[q];
    query.run = poses[q].run;
    for (size_t r = 0; r < poses.size(); ++r) {
      const double dt_s = poses[q].time_s - poses[r].time_s;
      if (std::abs(dt_s) <= options.exclusion_window_s) continue;
      if (revisit ? dt_s < 0 : is_query[r]) continue;
      query.database.push_back(poses[r].frame);
      query.is_true_match.push_back(IsTrueMatch(label[q], label[r], options) ? 1 : 0);
    }
    queries.push_back(std::move(query));
  }
  return queries;
}

std::vector<Query> RelabelQueries(const std::vector<Query>& queries, const std::vector<PoseRecord>& poses,
                                  const ProtocolOptions& options, const std::string& ground_truth) {
  HOILCD_CHECK_MSG(ground_truth != "overlap", "RelabelQueries labels by position; overlap needs OverlapLabels");
  const std::vector<PoseRecord> label = LabelPoses(poses, ground_truth);
  std::vector<Query> out = queries;
  for (Query& q : out) {
    for (size_t j = 0; j < q.database.size(); ++j) {
      q.is_true_match[j] = IsTrueMatch(label[q.frame], label[q.database[j]], options) ? 1 : 0;
    }
  }
  return out;
}

LabelDisagreement CompareLabels(const std::vector<Query>& a, const std::vector<Query>& b) {
  HOILCD_CHECK(a.size() == b.size());
  LabelDisagreement d;
  for (size_t i = 0; i < a.size(); ++i) {
    HOILCD_CHECK(a[i].frame == b[i].frame && a[i].database == b[i].database);
    ++d.queries;
    bool differs = false;
    for (size_t j = 0; j < a[i].database.size(); ++j) {
      ++d.pairs;
      const bool true_in_a = a[i].is_true_match[j] != 0, true_in_b = b[i].is_true_match[j] != 0;
      d.pairs_true_in_a += true_in_a;
      d.pairs_true_in_b += true_in_b;
      d.pairs_only_in_a += true_in_a && !true_in_b;
      d.pairs_only_in_b += true_in_b && !true_in_a;
      if (true_in_a != true_in_b) {
        ++d.pairs_differing;
        differs = true;
      }
    }
    if (differs) ++d.queries_differing;
    const bool in_a = a[i].NumTrueMatches() > 0, in_b = b[i].NumTrueMatches() > 0;
    if (in_a && !in_b) ++d.scored_only_in_a;
    if (in_b && !in_a) ++d.scored_only_in_b;
  }
  return d;
}

}  // namespace hoilcd
