#include "hoilcd/bench/runner.h"

#include <algorithm>
#include <chrono>
#include <numeric>
#include <set>
#include <set>

#include "hoilcd/bench/front_end_input.h"
#include "hoilcd/bench/manifest_options.h"
#include "hoilcd/bench/methods.h"
#include "hoilcd/core/error.h"
#include "hoilcd/core/parallel.h"
#include "hoilcd/core/progress.h"
#include "hoilcd/core/rank_fusion.h"
#include "hoilcd/core/retrieval_index.h"

namespace hoilcd {
namespace {

using Clock = std::chrono::steady_clock;
double MsSince(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

bool Wants(const std::vector<std::string>& methods, const std::string& name) {
  return std::find(methods.begin(), methods.end(), name) != methods.end();
}

// Per-query scores of a point-set method: each query against its own database, in parallel
// inside RetrievalIndex; per-query matching time recorded.
std::vector<std::vector<double>> ScoreQueries(const RetrievalIndex& index, const std::vector<Query>& queries,
                                              const std::vector<bool>& to_score,
                                              const MatchOptions& match, const RansacOptions& ransac,
                                              uint64_t seed, int threads, const std::string& title,
                                              std::vector<double>* match_ms) {
  std::vector<std::vector<double>> scores(queries.size());
  match_ms->assign(queries.size(), 0.0);
  ProgressReporter progress(title, static_cast<int64_t>(queries.size()), "queries");
  for (size_t i = 0; i < queries.size(); ++i) {
    const Query& q = queries[i];
    const auto start = Clock::now();
    if (to_score[i] && !q.database.empty()) {
      const auto row = index.ScoreAll({q.frame}, q.database, match, ransac, seed, threads);
      scores[i].assign(row[0].begin(), row[0].end());
    } else {
      scores[i].assign(q.database.size(), 0.0);  // skipped queries are not scored
    }
    (*match_ms)[i] = MsSince(start);
    progress.Update();
  }
  progress.Done();
  return scores;
}

// Temporal consistency over per-query databases: scores go into the union of all databases
// (frames absent from a query's own database score below everything), then back.
std::vector<std::vector<double>> TemporalConsistencyOfQueries(const std::vector<Query>& queries,
                                                             const std::vector<std::vector<double>>& scores,
                                                             const TemporalConsistencyOptions& options) {
  std::set<int> union_frames;
  double lowest = 0;
  for (size_t i = 0; i < queries.size(); ++i) {
    union_frames.insert(queries[i].database.begin(), queries[i].database.end());
    for (double v : scores[i]) lowest = std::min(lowest, v);
  }
  const std::vector<int> database(union_frames.begin(), union_frames.end());
  std::vector<int> column(database.empty() ? 0 : database.back() + 1, -1);
  for (size_t j = 0; j < database.size(); ++j) column[database[j]] = static_cast<int>(j);
  std::vector<int> query_frames;
  std::vector<std::vector<float>> table(queries.size(), std::vector<float>(database.size(), static_cast<float>(lowest - 1)));
  for (size_t i = 0; i < queries.size(); ++i) {
    query_frames.push_back(queries[i].frame);
    for (size_t j = 0; j < queries[i].database.size(); ++j) {
      table[i][column[queries[i].database[j]]] = static_cast<float>(scores[i][j]);
    }
  }
  const auto gated = TemporalConsistencyScores(query_frames, database, table, options);
  std::vector<std::vector<double>> out(queries.size());
  for (size_t i = 0; i < queries.size(); ++i) {
    for (int r : queries[i].database) out[i].push_back(gated[i][column[r]]);
  }
  return out;
}

// Picks each query's database columns out of a dense frame x frame matrix.
std::vector<std::vector<double>> FromDense(const std::vector<std::vector<float>>& dense,
                                           const std::vector<Query>& queries) {
  std::vector<std::vector<double>> scores(queries.size());
  for (size_t i = 0; i < queries.size(); ++i) {
    for (int r : queries[i].database) scores[i].push_back(dense[queries[i].frame][r]);
  }
  return scores;
}

std::vector<double> PerQueryExtract(const std::vector<double>& frame_ms, const std::vector<Query>& queries) {
  std::vector<double> out;
  for (const Query& q : queries) out.push_back(frame_ms[q.frame]);
  return out;
}

}  // namespace

std::string BenchOptions::Check() const {
  for (const std::string& m : methods) {
    const auto& catalog = MethodCatalog();
    if (std::none_of(catalog.begin(), catalog.end(), [&](const MethodInfo& i) { return i.name == m; })) {
      return "unknown method '" + m + "'";
    }
  }
  for (const std::string& problem :
       {protocol.Check(), match.Check(), ransac.Check(), keypoints.Check(), detector.Check(),
        tracker.Check(), hoi.Check(), track_aware.Check(), thumbnail.Check(), sequence.Check(),
        temporal.Check(), tracking_metrics.Check(), slam_options.Check()}) {
    if (!problem.empty()) return problem;
  }
  if (lo_refits < 1) return "lo_refits must be positive";
  if (rrf_k < 0) return "rrf_k must be non-negative";
  if (threads < 0) return "threads must be 0 (every core) or positive";
  return "";
}

const MethodRun* BenchResult::Find(const std::string& name) const {
  for (const MethodRun& r : runs)
    if (r.name == name) return &r;
  return nullptr;
}

BenchResult RunBench(const Dataset& dataset, const BenchOptions& options_in) {
  BenchOptions options = WithManifest(options_in, dataset.manifest());
  if (options.methods.empty()) options.methods = DefaultMethods();
  if (const std::string problem = options.Check(); !problem.empty()) throw InputError("bench", problem);
  const auto start = Clock::now();
  const int n = dataset.num_frames();
  const uint64_t seed = dataset.manifest().seed;
  const std::vector<std::string>& methods = options.methods;

  BenchResult result;
  result.queries = BuildQueries(dataset.poses(), options.protocol);
  const std::string other_ground_truth = OtherGroundTruth(options.protocol.ground_truth);
  result.ground_truth = options.protocol.ground_truth;
  result.other_ground_truth = other_ground_truth;
  result.other_queries = RelabelQueries(result.queries, dataset.poses(), options.protocol, other_ground_truth);
  result.label_disagreement = CompareLabels(result.queries, result.other_queries);
  const std::vector<PoseRecord> label_poses = LabelPoses(dataset.poses(), options.protocol.ground_truth);
  const std::vector<PoseRecord> other_label_poses = LabelPoses(dataset.poses(), other_ground_truth);
  // A query is scored when it has a true match under either labelling, so both can be measured.
  std::vector<bool> to_score(result.queries.size());
  for (size_t i = 0; i < to_score.size(); ++i) {
    to_score[i] = result.queries[i].NumTrueMatches() > 0 || result.other_queries[i].NumTrueMatches() > 0;
  }
  result.features.resize(n);

  const bool need_slcd = Wants(methods, "slcd") || Wants(methods, "slcd-lo") ||
                         Wants(methods, "fusion") || Wants(methods, "fusion-tc");
  const bool need_dlcd = Wants(methods, "dlcd") || Wants(methods, "dlcd-lo") ||
                         Wants(methods, "dlcd-track") || Wants(methods, "fusion") ||
                         Wants(methods, "fusion-tc");
  const bool need_thumb = Wants(methods, "thumb") || Wants(methods, "thumb-seq");

  // Features of every frame, once. SLCD and thumbnails are per frame (parallel); DLCD's tracker
  // carries state from frame to frame, so it runs in order.
  std::vector<double> slcd_ms(n, 0.0), dlcd_ms(n, 0.0), thumb_ms(n, 0.0);
  RetrievalIndex slcd_index, dlcd_index;
  std::vector<std::vector<HoiFeature>> hoi(n);
  ThumbnailIndex thumbnails(options.thumbnail);
  std::vector<FrameTracks> tracks;
  {
    ProgressReporter progress("features", n, "frames");
    std::vector<cv::Mat> thumb_frames;
    DlcdFrontEnd front_end(options.detector, options.tracker, options.hoi);
    const bool video_mode = IsVideoMode(dataset);
    for (int f = 0; f < n; ++f) {
      const FrontEndInput input = ReadFrontEndInput(dataset, f, video_mode, need_dlcd);
      const cv::Mat& thermal = input.thermal_u8;
      if (need_slcd) {
        const auto t = Clock::now();
        result.features[f].keypoints = DetectKeypoints(thermal, options.keypoints);
        slcd_ms[f] = MsSince(t);
        slcd_index.Add(result.features[f].keypoints);
      }
      if (need_dlcd) {
        const auto t = Clock::now();
        hoi[f] = front_end.Process(thermal, input.radiometric_c);
        dlcd_ms[f] = MsSince(t);
        result.features[f].hoi = hoi[f];
        std::vector<Point2> points;
        for (const HoiFeature& h : hoi[f]) points.push_back(h.point);
        dlcd_index.Add(points);
        FrameTracks ft;
        ft.frame = f;
        for (const Track& track : front_end.last_tracks()) {
          TrackedBox box{track.id, track.box, {}};
          for (const HoiFeature& h : hoi[f])
            if (h.track_id == track.id) box.hoi_points_px.push_back(h.point);
          ft.tracks.push_back(box);
        }
        tracks.push_back(ft);
      }
      if (need_thumb) {
        const auto t = Clock::now();
        thumbnails.Add(thermal);
        thumb_ms[f] = MsSince(t);
      }
      progress.Update();
    }
  }
  double kp = 0, hp = 0;
  for (const FrameFeatures& f : result.features) kp += f.keypoints.size(), hp += f.hoi.size();
  result.mean_keypoints_per_frame = n ? kp / n : 0;
  result.mean_hoi_points_per_frame = n ? hp / n : 0;
  for (const FramePersons& f : dataset.persons()) result.ground_truth_person_views += static_cast<int64_t>(f.persons.size());
  if (need_dlcd) {
    result.tracking = ComputeTrackingMetrics(dataset.persons(), tracks, options.tracking_metrics);
    result.tracking_evaluated = true;
  }

  std::map<std::string, MethodRun> runs;
  std::map<std::string, std::vector<double>> match_times;
  auto finish = [&](const std::string& name, std::vector<std::vector<double>> scores,
                    const std::vector<double>& extract_ms, const std::vector<double>& match_ms) {
    MethodRun run;
    run.name = name;
    run.metrics = ComputeMetrics(result.queries, scores, label_poses);
    run.metrics.SetTiming(extract_ms, match_ms);
    run.other_metrics = ComputeMetrics(result.other_queries, scores, other_label_poses);
    run.other_metrics.SetTiming(extract_ms, match_ms);
    run.scores = std::move(scores);
    runs[name] = std::move(run);
    match_times[name] = match_ms;
  };
  RansacOptions lo = options.ransac;
  lo.local_optimisation_refits = options.lo_refits;
  std::vector<double> match_ms;
  // The point-set methods: one index each, plain or locally optimised RANSAC.
  struct PointMethod {
    const char* name;
    bool wanted;
    const RetrievalIndex* index;
    const RansacOptions* ransac;
    const std::vector<double>* extract_ms;
  };
  for (const PointMethod& m : {PointMethod{"slcd", need_slcd, &slcd_index, &options.ransac, &slcd_ms},
                               PointMethod{"slcd-lo", Wants(methods, "slcd-lo"), &slcd_index, &lo, &slcd_ms},
                               PointMethod{"dlcd", need_dlcd, &dlcd_index, &options.ransac, &dlcd_ms},
                               PointMethod{"dlcd-lo", Wants(methods, "dlcd-lo"), &dlcd_index, &lo, &dlcd_ms}}) {
    if (!m.wanted) continue;
    auto s = ScoreQueries(*m.index, result.queries, to_score, options.match, *m.ransac, seed, options.threads, m.name, &match_ms);
    finish(m.name, std::move(s), PerQueryExtract(*m.extract_ms, result.queries), match_ms);
  }
  if (Wants(methods, "dlcd-track")) {
    std::vector<std::vector<double>> scores(result.queries.size());
    match_ms.assign(result.queries.size(), 0.0);
    ProgressReporter progress("dlcd-track", static_cast<int64_t>(result.queries.size()), "queries");
    for (size_t i = 0; i < result.queries.size(); ++i) {
      const Query& q = result.queries[i];
      const auto t = Clock::now();
      scores[i].assign(q.database.size(), 0.0);
      if (to_score[i]) {
        ParallelFor(static_cast<int64_t>(q.database.size()), options.threads, [&](int64_t j) {
          const int r = q.database[j];
          scores[i][j] = ScoreTrackAwarePair(hoi[q.frame], hoi[r], options.track_aware, options.ransac,
                                             seed, q.frame, r);
        });
      }
      match_ms[i] = MsSince(t);
      progress.Update();
    }
    progress.Done();
    finish("dlcd-track", std::move(scores), PerQueryExtract(dlcd_ms, result.queries), match_ms);
  }
  if (Wants(methods, "fusion") || Wants(methods, "fusion-tc")) {
    const MethodRun& s = runs.at("slcd");
    const MethodRun& d = runs.at("dlcd");
    std::vector<std::vector<double>> fused(result.queries.size());
    std::vector<double> extract(result.queries.size()), match(result.queries.size());
    for (size_t i = 0; i < result.queries.size(); ++i) {
      const auto t = Clock::now();
      fused[i] = ReciprocalRankFusionOfScores({s.scores[i], d.scores[i]}, options.rrf_k);
      // Fusion costs both methods' extraction and matching plus the fusion itself.
      extract[i] = slcd_ms[result.queries[i].frame] + dlcd_ms[result.queries[i].frame];
      match[i] = match_times.at("slcd")[i] + match_times.at("dlcd")[i] + MsSince(t);
    }
    finish("fusion", fused, extract, match);
    if (Wants(methods, "fusion-tc")) {
      const auto t = Clock::now();
      auto gated = TemporalConsistencyOfQueries(result.queries, fused, options.temporal);
      const double per_query = MsSince(t) / std::max<size_t>(1, result.queries.size());
      std::vector<double> tc_match(match);
      for (double& m : tc_match) m += per_query;
      finish("fusion-tc", std::move(gated), extract, tc_match);
    }
  }
  if (need_thumb) {
    const auto t = Clock::now();
    std::vector<int> all(n);
    std::iota(all.begin(), all.end(), 0);
    const std::vector<std::vector<float>> dense = thumbnails.ScoreAll(all, all, options.threads);
    const double per_query_ms = MsSince(t) / std::max(1, n);
    std::vector<double> m(result.queries.size(), per_query_ms);
    if (Wants(methods, "thumb")) finish("thumb", FromDense(dense, result.queries), PerQueryExtract(thumb_ms, result.queries), m);
    if (Wants(methods, "thumb-seq")) {
      const auto t2 = Clock::now();
      const auto seq = SequenceScores(dense, options.sequence, options.threads);
      const double seq_ms = MsSince(t2) / std::max(1, n);
      for (double& v : m) v += seq_ms;
      finish("thumb-seq", FromDense(seq, result.queries), PerQueryExtract(thumb_ms, result.queries), m);
    }
  }
  for (const std::string& name : methods) result.runs.push_back(std::move(runs.at(name)));
  if (options.slam) {
    std::vector<NamedScores> named;
    for (const MethodRun& r : result.runs) named.push_back({r.name, &r.scores});
    SlamRunOptions slam_options = options.slam_options;
    slam_options.threads = options.threads;
    result.slam = RunSlam(dataset.poses(), dataset.scene_json(), dataset.dir() + "/scene.json",
                          dataset.manifest().frame_rate_hz, options.protocol.radius_m, result.queries, named,
                          slam_options);
    result.slam_evaluated = true;
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace hoilcd
