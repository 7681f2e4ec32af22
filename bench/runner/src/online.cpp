#include "hoilcd/bench/runner/online.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>

#include "hoilcd/bench/evaluation/protocol.h"
#include "hoilcd/bench/methods/manifest_options.h"
#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/memory.h"
#include "hoilcd/core/util/progress.h"
#include "hoilcd/core/util/stats.h"
#include "steps.h"

namespace hoilcd {
namespace {

using Clock = std::chrono::steady_clock;

double MsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The asked methods that can run online (with the methods they combine): KeepMethods' rules.
std::vector<std::string> KeepOnlineMethods(BenchOptions* options) {
  return KeepMethods(options, "online", [](const std::string& m, bool named) {
    std::string not_online;
    for (const LoopClosureMethod* part : ScoringOrder({m})) {
      if (!part->Online()) not_online = part->Name();
    }
    if (not_online.empty()) return std::string();
    const std::string why =
        "cannot run online: " + (not_online == m ? "it scores" : "it combines " + not_online + ", which scores") +
        " from more than a query and its database (online methods: point-set methods and fusion)";
    if (named) throw InputError("--methods", m + " " + why);
    return why;
  });
}

// Frames by cell of a grid as fine as the true-match radius, so a query's true matches among the
// older frames are found among its 3 x 3 cells instead of the whole sequence.
class PositionGrid {
 public:
  PositionGrid(const std::vector<PoseRecord>& poses, double cell_m) : poses_(poses), cell_m_(cell_m) {
    for (size_t f = 0; f < poses.size(); ++f)
      cells_[Key(Cell(poses[f].x_m), Cell(poses[f].y_m))].push_back(static_cast<int>(f));
  }
  // True matches of `query` among frames [0, before).
  int CountTrueMatches(int query, int before, const ProtocolOptions& protocol) const {
    const PoseRecord& q = poses_[query];
    const int64_t cx = Cell(q.x_m), cy = Cell(q.y_m);
    int count = 0;
    for (int64_t dx = -1; dx <= 1; ++dx) {
      for (int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(Key(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (int f : it->second) {
          if (f >= before) break;  // frames ascend within a cell
          if (IsTrueMatch(q, poses_[f], protocol)) ++count;
        }
      }
    }
    return count;
  }

 private:
  int64_t Cell(double v) const { return static_cast<int64_t>(std::floor(v / cell_m_)); }
  static int64_t Key(int64_t x, int64_t y) { return x * 2654435761LL ^ y; }
  const std::vector<PoseRecord>& poses_;
  double cell_m_;
  std::unordered_map<int64_t, std::vector<int>> cells_;
};

}  // namespace

const OnlineMethodRun* OnlineResult::Find(const std::string& name) const {
  for (const OnlineMethodRun& r : runs)
    if (r.name == name) return &r;
  return nullptr;
}

std::vector<OnlineTimingRow> TimingByDatabaseSize(const std::vector<int64_t>& database_sizes,
                                                  const std::vector<double>& ms) {
  HOILCD_CHECK(database_sizes.size() == ms.size());
  // Bucket edges 0, 1000, 2000, 5000, 10000, 20000, 50000, ...
  auto bucket_of = [](int64_t size) {
    int64_t low = 0, high = 1000;
    const int64_t steps[3] = {2, 5, 10};
    int64_t decade = 1000;
    int step = 0;
    while (size >= high) {
      low = high;
      high = steps[step] * decade;
      if (++step == 3) step = 0, decade *= 10;
    }
    return std::make_pair(low, high);
  };
  std::map<std::pair<int64_t, int64_t>, std::vector<double>> buckets;
  for (size_t i = 0; i < ms.size(); ++i) buckets[bucket_of(database_sizes[i])].push_back(ms[i]);
  std::vector<OnlineTimingRow> rows;
  for (const auto& [range, values] : buckets) {
    OnlineTimingRow row;
    row.database_from = range.first;
    row.database_to = range.second;
    row.queries = static_cast<int>(values.size());
    row.p50_ms = Quantile(values, 0.5);
    row.p99_ms = Quantile(values, 0.99);
    rows.push_back(row);
  }
  return rows;
}

OnlineResult RunOnlineBench(const Dataset& dataset, const BenchOptions& options_in, const ShortlistOptions& shortlist) {
  const auto start = Clock::now();
  if (const std::string problem = shortlist.Check(); !problem.empty()) throw InputError("--shortlist", problem);
  BenchOptions options = WithManifest(options_in, dataset.manifest());
  if (options.methods.empty()) options.methods = options.optional_methods = DefaultMethods();
  if (const std::string problem = options.Check(); !problem.empty()) throw InputError("bench", problem);
  CheckProtocolFits(dataset, options.protocol);
  if (options.protocol.ground_truth == "overlap") {
    throw InputError("--ground-truth",
                     "online: overlap labels pairs from the EXR frames, which a robot does not "
                     "have; use odometry (the paper's) or true");
  }
  OnlineResult result;
  result.shortlist = shortlist;
  result.skipped = KeepOnlineMethods(&options);
  for (std::string& note : LeaveOutUnavailable(dataset, &options)) result.skipped.push_back(std::move(note));
  const std::vector<const LoopClosureMethod*> order = ScoringOrder(options.methods);
  std::set<FrontEnd> needed = NeededFrontEnds(order);
  needed.insert(FrontEnd::kThumbnails);  // the shortlist's global descriptors
  CheckFrontEndSizes(dataset, options, needed);
  const ResolvedMethods methods = ResolveMethods(options, order);
  const FrontEndOutput front_ends = RunFrontEndsWithParams(dataset, options, needed);

  const ProtocolOptions& protocol = options.protocol;
  const std::vector<PoseRecord> poses = LabelPoses(dataset.poses(), protocol.ground_truth);
  const std::vector<int> laps = LapIndexFromPoses(poses);
  const int n = static_cast<int>(poses.size());
  result.protocol = protocol.protocol;
  result.ground_truth = protocol.ground_truth;
  result.frames = n;
  const PositionGrid grid(poses, std::max(protocol.radius_m, 1e-3));
  ShortlistIndex index(static_cast<int>(front_ends.thumbnails.descriptor(0).size()), shortlist);

  const size_t runs = options.methods.size();
  std::vector<std::vector<QueryRecord>> records(runs);
  std::vector<std::vector<double>> query_ms(runs);
  std::vector<int64_t> processed_sizes;
  std::vector<double> insert_ms;
  ProgressReporter progress("online " + std::to_string(shortlist.k) + "-shortlist", n, "frames");
  const ProgressReporter::ThreadQuiet quiet_per_query;  // each query's scoring pass is its own small call
  int inserted = 0;
  for (int q = 0; q < n; ++q, progress.Update()) {
    // The database: every frame older than the exclusion window (frames are in time order).
    while (inserted < q && poses[q].time_s - poses[inserted].time_s > protocol.exclusion_window_s) {
      const auto t = Clock::now();
      index.Add(inserted, front_ends.thumbnails.descriptor(inserted));
      insert_ms.push_back(MsSince(t));
      ++inserted;
    }
    if (!IsQueryFrame(protocol, laps[q], poses[q].run)) continue;
    Query query;
    query.frame = q;
    query.lap = laps[q];
    query.run = poses[q].run;
    const int true_matches = inserted > 0 ? grid.CountTrueMatches(q, inserted, protocol) : 0;
    if (inserted == 0) {
      for (size_t m = 0; m < runs; ++m) {
        QueryRecord r;
        r.frame = q, r.lap = laps[q];
        records[m].push_back(r);
      }
      continue;
    }
    const auto t_search = Clock::now();
    query.database = index.Search(front_ends.thumbnails.descriptor(q), shortlist.k);
    const double search_ms = MsSince(t_search);
    std::sort(query.database.begin(), query.database.end());
    for (int f : query.database) query.is_true_match.push_back(IsTrueMatch(poses[q], poses[f], protocol) ? 1 : 0);
    Labelling one;
    one.protocol = protocol;
    one.frame_rate_hz = dataset.manifest().frame_rate_hz;
    one.ground_truth = protocol.ground_truth;
    one.queries = {query};
    one.to_score = {true};
    const std::map<std::string, MethodScores> scored = ScoreMethods(dataset, options, methods, one, front_ends);
    for (size_t m = 0; m < runs; ++m) {
      const MethodScores& s = scored.at(options.methods[m]);
      records[m].push_back(ShortlistRecord(query, s.scores.front(), inserted, true_matches, poses));
      query_ms[m].push_back(search_ms + s.match_ms.front());
    }
    ++result.queries_processed;
    processed_sizes.push_back(inserted);
    result.search_ms.push_back(search_ms);
    if (true_matches > 0) {
      ++result.queries_scored;
      if (query.NumTrueMatches() > 0) ++result.shortlist_hits;
    }
  }
  progress.Done();

  result.shortlist_recall =
      result.queries_scored ? static_cast<double>(result.shortlist_hits) / result.queries_scored : NAN;
  result.search_by_database_size = TimingByDatabaseSize(processed_sizes, result.search_ms);
  result.insert_p50_ms = Quantile(insert_ms, 0.5);
  result.insert_p99_ms = Quantile(insert_ms, 0.99);
  result.index_bytes = index.MemoryBytes();
  std::vector<const std::vector<QueryRecord>*> all_records;
  for (size_t m = 0; m < runs; ++m) {
    OnlineMethodRun run;
    run.name = options.methods[m];
    run.metrics = SummariseQueries(records[m]);
    run.query_ms = std::move(query_ms[m]);
    run.p50_ms = Quantile(run.query_ms, 0.5);
    run.p99_ms = Quantile(run.query_ms, 0.99);
    run.by_database_size = TimingByDatabaseSize(processed_sizes, run.query_ms);
    if (methods.resolved.count(run.name)) run.options = methods.resolved.at(run.name);
    result.runs.push_back(std::move(run));
  }
  for (const OnlineMethodRun& run : result.runs) all_records.push_back(&run.metrics.queries);
  result.bootstrap = PlanBootstrap(all_records, dataset.manifest().frame_rate_hz, options.bootstrap);
  for (OnlineMethodRun& run : result.runs) {
    run.intervals = BootstrapHeadline(run.metrics.queries, result.bootstrap, options.bootstrap.seed, options.threads);
  }
  result.per_run = MetricsPerRun(dataset.runs(), options.methods, all_records, result.bootstrap, options.bootstrap.seed,
                                 options.threads);
  result.peak_rss_bytes = PeakResidentBytes();
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace hoilcd
