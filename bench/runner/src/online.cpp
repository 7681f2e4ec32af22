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

// The options an online bench runs with (the manifest's, checked) and the methods it keeps; the
// optional methods left out are added to `skipped`.
BenchOptions OnlineOptions(const Dataset& dataset, const BenchOptions& options_in, const ShortlistOptions& shortlist,
                           std::vector<std::string>* skipped) {
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
  *skipped = KeepOnlineMethods(&options);
  for (std::string& note : LeaveOutUnavailable(dataset, &options)) skipped->push_back(std::move(note));
  return options;
}

// What the pass over the frames gathers: per method slot (options.methods' order) each query's
// record and ms; per processed query the database's size; per inserted frame the ms it took.
struct OnlineTally {
  std::vector<std::vector<QueryRecord>> records;
  std::vector<std::vector<double>> query_ms;
  std::vector<int64_t> processed_sizes;
  std::vector<double> insert_ms;
};

// One pass over the frames in time order: a frame joins the shortlist index once it is older than
// the exclusion window, and each query takes its shortlist and is scored by every method on it.
class OnlinePass {
 public:
  OnlinePass(const Dataset& dataset, const BenchOptions& options, const ResolvedMethods& methods,
             const FrontEndOutput& front_ends, const ShortlistOptions& shortlist)
      : dataset_(dataset),
        options_(options),
        protocol_(options.protocol),
        methods_(methods),
        front_ends_(front_ends),
        shortlist_(shortlist),
        poses_(LabelPoses(dataset.poses(), protocol_.ground_truth)),
        laps_(LapIndexFromPoses(poses_)),
        grid_(poses_, std::max(protocol_.radius_m, 1e-3)),
        index_(static_cast<int>(front_ends.thumbnails.descriptor(0).size()), shortlist) {
    tally_.records.resize(options.methods.size());
    tally_.query_ms.resize(options.methods.size());
  }

  int frames() const { return static_cast<int>(poses_.size()); }
  const ShortlistIndex& index() const { return index_; }
  OnlineTally& tally() { return tally_; }

  // Every frame, in order; counts the processed, scored and shortlist-hit queries into `result`.
  void Run(OnlineResult* result) {
    const int n = frames();
    ProgressReporter progress("online " + std::to_string(shortlist_.k) + "-shortlist", n, "frames");
    const ProgressReporter::ThreadQuiet quiet_per_query;  // each query's scoring pass is its own small call
    for (int q = 0; q < n; ++q, progress.Update()) {
      InsertOlderThanWindow(q);
      if (!IsQueryFrame(protocol_, laps_[q], poses_[q].run)) continue;
      if (inserted_ == 0) {
        RecordEmptyDatabase(q);
      } else {
        ScoreQuery(q, result);
      }
    }
    progress.Done();
  }

 private:
  // The database: every frame older than the exclusion window (frames are in time order).
  void InsertOlderThanWindow(int q) {
    while (inserted_ < q && poses_[q].time_s - poses_[inserted_].time_s > protocol_.exclusion_window_s) {
      const auto t = Clock::now();
      index_.Add(inserted_, front_ends_.thumbnails.descriptor(inserted_));
      tally_.insert_ms.push_back(MsSince(t));
      ++inserted_;
    }
  }

  // A query with nothing older to match: recorded, unscored, in every slot.
  void RecordEmptyDatabase(int q) {
    for (std::vector<QueryRecord>& records : tally_.records) {
      QueryRecord r;
      r.frame = q, r.lap = laps_[q];
      records.push_back(r);
    }
  }

  // The query's shortlist, with each frame's label.
  Query Shortlisted(int q, double* search_ms) {
    Query query;
    query.frame = q;
    query.lap = laps_[q];
    query.run = poses_[q].run;
    const auto t_search = Clock::now();
    query.database = index_.Search(front_ends_.thumbnails.descriptor(q), shortlist_.k);
    *search_ms = MsSince(t_search);
    std::sort(query.database.begin(), query.database.end());
    for (int f : query.database) query.is_true_match.push_back(IsTrueMatch(poses_[q], poses_[f], protocol_) ? 1 : 0);
    return query;
  }

  // Every method's scores of the query's shortlist: one labelling of one query.
  std::map<std::string, MethodScores> ScoreShortlist(const Query& query) const {
    Labelling one;
    one.protocol = protocol_;
    one.frame_rate_hz = dataset_.manifest().frame_rate_hz;
    one.ground_truth = protocol_.ground_truth;
    one.queries = {query};
    one.to_score = {true};
    return ScoreMethods(dataset_, options_, methods_, one, front_ends_);
  }

  void ScoreQuery(int q, OnlineResult* result) {
    const int true_matches = grid_.CountTrueMatches(q, inserted_, protocol_);
    double search_ms = 0;
    const Query query = Shortlisted(q, &search_ms);
    const std::map<std::string, MethodScores> scored = ScoreShortlist(query);
    for (size_t m = 0; m < options_.methods.size(); ++m) {
      const MethodScores& s = scored.at(options_.methods[m]);
      tally_.records[m].push_back(ShortlistRecord(query, s.scores.front(), inserted_, true_matches, poses_));
      tally_.query_ms[m].push_back(search_ms + s.match_ms.front());
    }
    ++result->queries_processed;
    tally_.processed_sizes.push_back(inserted_);
    result->search_ms.push_back(search_ms);
    if (true_matches > 0) {
      ++result->queries_scored;
      if (query.NumTrueMatches() > 0) ++result->shortlist_hits;
    }
  }

  const Dataset& dataset_;
  const BenchOptions& options_;
  const ProtocolOptions& protocol_;
  const ResolvedMethods& methods_;
  const FrontEndOutput& front_ends_;
  const ShortlistOptions& shortlist_;
  const std::vector<PoseRecord> poses_;
  const std::vector<int> laps_;
  const PositionGrid grid_;
  ShortlistIndex index_;
  OnlineTally tally_;
  int inserted_ = 0;  // frames in the index: [0, inserted_)
};

// Each method slot's metrics and timing from the tally, in options.methods' order.
std::vector<OnlineMethodRun> MethodRuns(const std::vector<std::string>& names, const ResolvedMethods& methods,
                                        OnlineTally* tally) {
  std::vector<OnlineMethodRun> runs;
  for (size_t m = 0; m < names.size(); ++m) {
    OnlineMethodRun run;
    run.name = names[m];
    run.metrics = SummariseQueries(tally->records[m]);
    run.query_ms = std::move(tally->query_ms[m]);
    run.p50_ms = Quantile(run.query_ms, 0.5);
    run.p99_ms = Quantile(run.query_ms, 0.99);
    run.by_database_size = TimingByDatabaseSize(tally->processed_sizes, run.query_ms);
    if (methods.resolved.count(run.name)) run.options = methods.resolved.at(run.name);
    runs.push_back(std::move(run));
  }
  return runs;
}

// The bootstrap plan over every method's queries, each method's intervals and the metrics per recording run.
void AddIntervals(const Dataset& dataset, const BenchOptions& options, OnlineResult* result) {
  std::vector<const std::vector<QueryRecord>*> all_records;
  for (const OnlineMethodRun& run : result->runs) all_records.push_back(&run.metrics.queries);
  result->bootstrap = PlanBootstrap(all_records, dataset.manifest().frame_rate_hz, options.bootstrap);
  for (OnlineMethodRun& run : result->runs) {
    run.intervals = BootstrapHeadline(run.metrics.queries, result->bootstrap, options.bootstrap.seed, options.threads);
  }
  result->per_run = MetricsPerRun(dataset.runs(), options.methods, all_records, result->bootstrap,
                                  options.bootstrap.seed, options.threads);
}

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
  OnlineResult result;
  result.shortlist = shortlist;
  const BenchOptions options = OnlineOptions(dataset, options_in, shortlist, &result.skipped);
  const std::vector<const LoopClosureMethod*> order = ScoringOrder(options.methods);
  std::set<FrontEnd> needed = NeededFrontEnds(order);
  needed.insert(FrontEnd::kThumbnails);  // the shortlist's global descriptors
  CheckFrontEndSizes(dataset, options, needed);
  const ResolvedMethods methods = ResolveMethods(options, order);
  const FrontEndOutput front_ends = RunFrontEndsWithParams(dataset, options, needed);

  OnlinePass pass(dataset, options, methods, front_ends, shortlist);
  result.protocol = options.protocol.protocol;
  result.ground_truth = options.protocol.ground_truth;
  result.frames = pass.frames();
  pass.Run(&result);

  OnlineTally& tally = pass.tally();
  result.shortlist_recall =
      result.queries_scored ? static_cast<double>(result.shortlist_hits) / result.queries_scored : NAN;
  result.search_by_database_size = TimingByDatabaseSize(tally.processed_sizes, result.search_ms);
  result.insert_p50_ms = Quantile(tally.insert_ms, 0.5);
  result.insert_p99_ms = Quantile(tally.insert_ms, 0.99);
  result.index_bytes = pass.index().MemoryBytes();
  result.runs = MethodRuns(options.methods, methods, &tally);
  AddIntervals(dataset, options, &result);
  result.peak_rss_bytes = PeakResidentBytes();
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace hoilcd
