// Evaluation protocol: which database frames each query is ranked against, and which of them are
// true loop closures (robot positions within radius_m, optionally headings within a tolerance).
// Positions are the odometry's, as the paper's ground truth (section 5.1), or the true poses'.
// Frames within the temporal exclusion window of a query never enter its database. A dataset of
// several recording runs (runs.h) is one sequence of frames: laps count on across its runs, and the
// runs protocol asks the first run for the later runs' places.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// Defaults and ranges: Table() in protocol.cpp.
struct ProtocolOptions {
  // "laps": database = first lap, queries = later laps; "revisit": every frame is a query and its
  // database is every frame older than the exclusion window (SLAM style); "runs": database = the
  // first recording run, queries = every frame of the later runs (CheckProtocolFits: 2+ runs).
  std::string protocol;
  double radius_m;               // m, base positions this close make a true match (paper)
  double heading_tolerance_deg;  // deg, max heading difference of a true match; < 0 = off
  double exclusion_window_s;     // s, frames with |t_query - t_ref| <= this are left out
  // What decides true matches: "odometry" (the paper's: the robot's odometric positions within
  // radius_m), "true" (the ground-truth positions within radius_m) or "overlap" (the share of the
  // query's static view the reference sees, overlap.h; laps and databases from the true poses).
  std::string ground_truth;
  double overlap_threshold;          // fraction of the query's static pixels shared to be a true match
  int overlap_stride_px;             // px, the overlap samples every this-th pixel of rows and columns
  double overlap_depth_tolerance_m;  // m, a reprojected point this far from the reference's depth is unseen

  ProtocolOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<ProtocolOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// InputError naming the dataset when `options` cannot be applied to it: the runs protocol on a
// dataset of one recording run. Callers check before any work.
void CheckProtocolFits(const Dataset& dataset, const ProtocolOptions& options);

// Whether a frame of lap `lap` and recording run `run` is a query: revisit every frame; laps the
// later laps; runs the later runs. Under laps and runs the other frames are every query's database.
bool IsQueryFrame(const ProtocolOptions& options, int lap, int run);

struct Query {
  int frame = 0;                       // query frame
  int lap = 0;                         // lap of the query frame, 0 = first (LapIndexFromPoses)
  int run = 0;                         // recording run of the query frame (PoseRecord::run)
  std::vector<int> database;           // frames to rank, ascending
  std::vector<uint8_t> is_true_match;  // parallel to database: 1 when a true loop closure
  int NumTrueMatches() const;          // 0 => the query is skipped (not scored)
};

// The poses whose x, y, theta are those `ground_truth` labels with: for "odometry" a copy with the
// odometric pose in x_m, y_m, theta_rad; for "true" and "overlap" the poses as given.
std::vector<PoseRecord> LabelPoses(const std::vector<PoseRecord>& poses, const std::string& ground_truth);

// The ground truth the report compares with: "odometry" <-> "true"; "overlap" -> "odometry" (the
// paper's).
std::string OtherGroundTruth(const std::string& ground_truth);

// Lap number per pose (0 = first lap), from the cumulative unwrapped ground-truth heading: a new
// lap starts each time the heading has turned a further 2π in the sequence's overall turning
// direction (−2π per clockwise lap). A recording run (PoseRecord::run) starts at the dock: the
// heading is unwrapped afresh from its first frame, and its first lap is one more than the last of
// the run before. Never decreases along the sequence.
std::vector<int> LapIndexFromPoses(const std::vector<PoseRecord>& poses);

// Euclidean distance between the robot base positions (x, y) of two poses, in metres.
double BaseDistanceM(const PoseRecord& a, const PoseRecord& b);

// Whether `reference` is a true match of `query` (radius and heading tolerance only; the
// exclusion window is a property of the database, not of the pair).
bool IsTrueMatch(const PoseRecord& query, const PoseRecord& reference, const ProtocolOptions& options);

// Queries in frame order; those without a true match are kept (NumTrueMatches() == 0) so they can
// be counted as skipped. `poses` are the dataset's rows (frames 0..N-1 in time order); laps and
// true matches come from options.ground_truth's positions (LabelPoses). Under "overlap" the
// pairs are labelled by true position: OverlapLabels (overlap.h) relabels them from the images.
std::vector<Query> BuildQueries(const std::vector<PoseRecord>& poses, const ProtocolOptions& options);

// The same queries and databases, labelled with `ground_truth`'s positions instead (so one set of
// scores can be measured under both labellings); "odometry" or "true".
std::vector<Query> RelabelQueries(const std::vector<Query>& queries, const std::vector<PoseRecord>& poses,
                                  const ProtocolOptions& options, const std::string& ground_truth);

// How two labellings of the same queries differ.
struct LabelDisagreement {
  int queries = 0;              // queries compared
  int queries_differing = 0;    // queries whose set of true matches differs
  int scored_only_in_a = 0;     // queries with a true match under a only
  int scored_only_in_b = 0;     // queries with a true match under b only
  int64_t pairs = 0;            // (query, database frame) pairs compared
  int64_t pairs_differing = 0;  // pairs labelled differently
  int64_t pairs_true_in_a = 0;  // true matches under a
  int64_t pairs_true_in_b = 0;  // true matches under b
  int64_t pairs_only_in_a = 0;  // true under a, not under b: the pairs a adds to b
  int64_t pairs_only_in_b = 0;  // true under b, not under a: the pairs a removes from b
};
LabelDisagreement CompareLabels(const std::vector<Query>& a, const std::vector<Query>& b);

}  // namespace hoilcd
