#include "hoilcd/bench/runner/runner.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <set>

#include "hoilcd/bench/evaluation/evaluate.h"
#include "hoilcd/bench/methods/front_ends.h"
#include "hoilcd/bench/methods/loop_closure_method.h"
#include "hoilcd/bench/methods/manifest_options.h"
#include "hoilcd/bench/methods/method_params.h"
#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/core/util/allocator.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/memory.h"
#include "hoilcd/core/util/parallel.h"
#include "steps.h"

namespace hoilcd {

std::vector<const LoopClosureMethod*> ScoringOrder(const std::vector<std::string>& asked) {
  std::vector<const LoopClosureMethod*> order;
  std::set<std::string> seen;
  std::function<void(const std::string&)> visit = [&](const std::string& name) {
    if (!seen.insert(name).second) return;
    const LoopClosureMethod& method = FindMethod(name);
    for (const std::string& input : method.Inputs()) visit(input);
    order.push_back(&method);
  };
  for (const std::string& name : asked) visit(name);
  return order;
}

namespace {

// What a method (with the methods it combines) needs from the dataset that it lacks: the first
// missing output and the front end that wants it; empty when it has everything.
std::pair<std::string, FrontEnd> MissingOutput(const Dataset& dataset, const std::string& method) {
  for (const LoopClosureMethod* m : ScoringOrder({method})) {
    for (FrontEnd f : m->FrontEnds()) {
      for (const std::string& output : GroundTruthOutputs(f)) {
        if (!dataset.manifest().outputs.Has(output)) return {output, f};
      }
    }
  }
  return {"", FrontEnd::kKeypoints};
}

}  // namespace

std::vector<std::string> KeepMethods(BenchOptions* options, const std::string& context,
                                     const std::function<std::string(const std::string&, bool)>& why_not) {
  std::vector<std::string> kept, notes;
  const auto& optional = options->optional_methods;
  for (const std::string& m : options->methods) {
    const bool named = std::find(optional.begin(), optional.end(), m) == optional.end();
    const std::string why = why_not(m, named);
    if (why.empty()) {
      kept.push_back(m);
    } else {
      notes.push_back(m + ": not run, " + why);
    }
  }
  if (kept.empty()) throw InputError("--methods", "no method can run " + context + ": " + notes.front());
  options->methods = kept;
  return notes;
}

std::vector<std::string> LeaveOutUnavailable(const Dataset& dataset, BenchOptions* options) {
  return KeepMethods(options, "on " + dataset.dir(), [&](const std::string& m, bool named) {
    const auto [output, front_end] = MissingOutput(dataset, m);
    if (output.empty()) return std::string();
    const std::string needed_for = "method " + m + " (its " + FrontEndName(front_end) + " front end)";
    if (named) dataset.RequireOutput(output, needed_for);
    return "the dataset has no " + output + " output, which " + needed_for + " needs (rendered with --outputs " +
           dataset.manifest().outputs.ToText() + ")";
  });
}

std::set<FrontEnd> NeededFrontEnds(const std::vector<const LoopClosureMethod*>& order) {
  std::set<FrontEnd> needed;
  for (const LoopClosureMethod* m : order) {
    const std::set<FrontEnd> f = m->FrontEnds();
    needed.insert(f.begin(), f.end());
  }
  return needed;
}

namespace {

// `options` with the --param values of the front ends in `needed`.
BenchOptions WithNeededFrontEndParams(const BenchOptions& options, const std::set<FrontEnd>& needed) {
  BenchOptions front = options;
  for (FrontEnd f : needed) front = WithFrontEndParams(front, f);
  return front;
}

}  // namespace

void CheckFrontEndSizes(const Dataset& dataset, const BenchOptions& options, const std::set<FrontEnd>& needed) {
  if (!needed.count(FrontEnd::kThumbnails)) return;
  const ThumbnailOptions& thumbnail = WithNeededFrontEndParams(options, needed).thumbnail;
  const std::string scope = FrontEndName(FrontEnd::kThumbnails);
  const CameraIntrinsics& image = dataset.manifest().intrinsics;
  if (const std::string problem = thumbnail.CheckImage(image.width, image.height); !problem.empty()) {
    throw InputError("--param", scope + "." + problem + " (the dataset's camera image)");
  }
  CheckAllocation(thumbnail.DatabaseBytes(dataset.num_frames()),
                  "--param " + scope + ".width_px, " + scope + ".height_px",
                  "the thumbnail database (" + std::to_string(dataset.num_frames()) + " frames of " +
                      std::to_string(thumbnail.width_px) + " x " + std::to_string(thumbnail.height_px) + " px)");
}

FrontEndOutput RunFrontEndsWithParams(const Dataset& dataset, const BenchOptions& options,
                                      const std::set<FrontEnd>& needed) {
  const BenchOptions front = WithNeededFrontEndParams(options, needed);
  FrontEndOptions front_options;
  front_options.keypoints = front.keypoints;
  front_options.detector = front.detector;
  front_options.tracker = front.tracker;
  front_options.hoi = front.hoi;
  front_options.thumbnail = front.thumbnail;
  front_options.threads = options.threads;
  return RunFrontEnds(dataset, needed, front_options);
}

namespace {

// The front ends' features per frame and the ground truth's person views, into *result; the
// tracking metrics when the dataset has people and the person front end ran.
void AddFeaturesAndTracking(const Dataset& dataset, const BenchOptions& options, const FrontEndOutput& front_ends,
                            BenchResult* result) {
  const int n = dataset.num_frames();
  result->features.resize(n);
  double kp = 0, hp = 0;
  for (int f = 0; f < n; ++f) {
    if (front_ends.Ran(FrontEnd::kKeypoints)) result->features[f].keypoints = front_ends.keypoints[f];
    if (front_ends.Ran(FrontEnd::kPersons)) result->features[f].hoi = front_ends.hoi[f];
    if (front_ends.Ran(FrontEnd::kIdealKeypoints)) result->features[f].ideal_keypoints = front_ends.ideal_keypoints[f];
    if (front_ends.Ran(FrontEnd::kTruePersons)) result->features[f].true_hoi = front_ends.true_hoi[f];
    kp += result->features[f].keypoints.size(), hp += result->features[f].hoi.size();
  }
  result->mean_keypoints_per_frame = n ? kp / n : 0;
  result->mean_hoi_points_per_frame = n ? hp / n : 0;
  // People ground truth is optional (hoilcd render --outputs without persons): no tracking metrics then.
  const bool has_persons = dataset.manifest().outputs.persons;
  for (const FramePersons& f : has_persons ? dataset.persons() : std::vector<FramePersons>()) {
    result->ground_truth_person_views += static_cast<int64_t>(f.persons.size());
  }
  if (has_persons && front_ends.Ran(FrontEnd::kPersons)) {
    result->tracking = ComputeTrackingMetrics(dataset.persons(), front_ends.tracks, options.tracking_metrics);
    result->tracking_evaluated = true;
  }
}

}  // namespace

ResolvedMethods ResolveMethods(const BenchOptions& options, std::vector<const LoopClosureMethod*> order) {
  ResolvedMethods methods;
  methods.order = std::move(order);
  for (const LoopClosureMethod* m : methods.order) {
    methods.own.push_back(OptionsWithParams(*m, options.params));
    if (methods.own.back() != nullptr) methods.resolved[m->Name()] = methods.own.back()->ToJson();
  }
  return methods;
}

std::map<std::string, MethodScores> ScoreMethods(const Dataset& dataset, const BenchOptions& options,
                                                 const ResolvedMethods& methods, const Labelling& labelling,
                                                 const FrontEndOutput& front_ends) {
  const std::vector<const LoopClosureMethod*>& order = methods.order;
  std::map<std::string, MethodScores> scored;
  const auto context_of = [&](size_t i) {
    return MethodContext{dataset,    options, methods.own[i].get(),    labelling,
                         front_ends, scored,  dataset.manifest().seed, options.threads};
  };
  std::vector<std::string> pass_keys;
  for (size_t i = 0; i < order.size(); ++i) {
    pass_keys.push_back(order[i]->Inputs().empty() ? order[i]->PassKey(context_of(i)) : "");
  }
  for (size_t i = 0; i < order.size(); ++i) {
    if (scored.count(order[i]->Name())) continue;
    std::vector<const LoopClosureMethod*> pass = {order[i]};
    std::vector<MethodContext> contexts = {context_of(i)};
    for (size_t j = i + 1; j < order.size() && !pass_keys[i].empty(); ++j) {
      if (pass_keys[j] == pass_keys[i]) pass.push_back(order[j]), contexts.push_back(context_of(j));
    }
    std::vector<MethodScores> scores = pass.size() == 1 ? std::vector<MethodScores>{order[i]->Score(contexts.front())}
                                                        : order[i]->ScoreTogether(pass, contexts);
    HOILCD_CHECK_MSG(scores.size() == pass.size(), order[i]->Name() << " scored " << scores.size() << " of "
                                                                    << pass.size() << " methods in its pass");
    for (size_t k = 0; k < pass.size(); ++k) scored[pass[k]->Name()] = std::move(scores[k]);
  }
  return scored;
}

namespace {

// Step 5: the metrics per stratum of the queries' conditions (query_conditions.h), a 95 % interval
// on every headline metric, the metrics per recording run (run_metrics.h) and the paired comparison
// of every pair of methods, all from the same resampled blocks of queries (bootstrap.h).
void AddIntervals(const Dataset& dataset, const BenchOptions& options, BenchResult* result) {
  std::vector<const std::vector<QueryRecord>*> records;
  std::vector<std::string> names;
  for (const MethodRun& run : result->runs) records.push_back(&run.metrics.queries), names.push_back(run.name);
  if (records.empty()) return;
  result->strata =
      Stratify(result->conditions, names, records, options.strata.empty() ? DefaultStratifications() : options.strata);
  result->bootstrap = PlanBootstrap(records, dataset.manifest().frame_rate_hz, options.bootstrap);
  const uint64_t seed = options.bootstrap.seed;
  for (MethodRun& run : result->runs) {
    run.intervals = BootstrapHeadline(run.metrics.queries, result->bootstrap, seed, options.threads);
  }
  result->per_run = MetricsPerRun(dataset.runs(), names, records, result->bootstrap, seed, options.threads);
  for (size_t a = 0; a < result->runs.size(); ++a) {
    for (size_t b = a + 1; b < result->runs.size(); ++b) {
      const MethodRun& ra = result->runs[a];
      const MethodRun& rb = result->runs[b];
      result->comparisons.push_back(PairedBootstrap(ra.name, ra.metrics.queries, rb.name, rb.metrics.queries,
                                                    result->bootstrap, seed, options.threads));
    }
  }
}

}  // namespace

std::vector<Point2> FrameFeatures::Points(ShownFeatures shown) const {
  switch (shown) {
    case ShownFeatures::kKeypoints:
      return keypoints;
    case ShownFeatures::kIdealKeypoints:
      return ideal_keypoints;
    default:
      break;
  }
  std::vector<Point2> points;
  for (const HoiFeature& h : Hoi(shown)) points.push_back(h.point);
  return points;
}

const std::vector<HoiFeature>& FrameFeatures::Hoi(ShownFeatures shown) const {
  static const std::vector<HoiFeature> kNoHoi;
  if (shown == ShownFeatures::kHoiPoints) return hoi;
  return shown == ShownFeatures::kTrueHoiPoints ? true_hoi : kNoHoi;
}

const MethodRun* BenchResult::Find(const std::string& name) const {
  for (const MethodRun& r : runs)
    if (r.name == name) return &r;
  return nullptr;
}

BenchResult RunBench(const Dataset& dataset, const BenchOptions& options_in) {
  KeepFreedMemoryForReuse();  // decoded frames and per-pair buffers come and go on every thread
  BenchOptions options = WithManifest(options_in, dataset.manifest());
  if (options.methods.empty()) options.methods = options.optional_methods = DefaultMethods();
  if (const std::string problem = options.Check(); !problem.empty()) throw InputError("bench", problem);
  CheckProtocolFits(dataset, options.protocol);
  std::vector<std::string> skipped = LeaveOutUnavailable(dataset, &options);
  const std::vector<const LoopClosureMethod*> order = ScoringOrder(options.methods);
  CheckFrontEndSizes(dataset, options, NeededFrontEnds(order));
  const auto start = std::chrono::steady_clock::now();

  // Step 1: the protocol's queries, labelled under both ground truths.
  const Labelling labelling = LabelQueries(dataset, options.protocol, options.threads);
  BenchResult result;
  result.skipped = std::move(skipped);
  result.queries = labelling.queries;
  result.ground_truth = labelling.ground_truth;
  result.other_ground_truth = labelling.other_ground_truth;
  result.other_queries = labelling.other_queries;
  result.label_disagreement = labelling.disagreement;
  result.label_agreements = labelling.agreements;
  result.no_true_match = NoTrueMatchReason(labelling);
  result.conditions = ComputeQueryConditions(dataset, labelling.queries, options.threads);

  // Every method scores every pair: their scores must fit before the front ends run.
  double pairs = 0;
  for (const Query& q : labelling.queries) pairs += static_cast<double>(q.database.size());
  CheckAllocation(pairs * sizeof(double) * static_cast<double>(order.size()), "--methods",
                  "the scores of " + std::to_string(order.size()) + " methods over " +
                      std::to_string(static_cast<int64_t>(pairs)) + " query pairs");

  // Step 2: the front ends the methods need, once each; step 3: every method's scores.
  const FrontEndOutput front_ends = RunFrontEndsWithParams(dataset, options, NeededFrontEnds(order));
  AddFeaturesAndTracking(dataset, options, front_ends, &result);
  const ResolvedMethods methods = ResolveMethods(options, order);
  const std::map<std::string, nlohmann::json>& resolved = methods.resolved;
  std::map<std::string, MethodScores> scored = ScoreMethods(dataset, options, methods, labelling, front_ends);

  // Step 4: metrics of the asked methods under both labellings, one method per task.
  result.runs.resize(options.methods.size());
  for (size_t i = 0; i < options.methods.size(); ++i) {
    if (resolved.count(options.methods[i])) result.runs[i].options = resolved.at(options.methods[i]);
  }
  ParallelFor(static_cast<int64_t>(options.methods.size()), options.threads, [&](int64_t i) {
    MethodRun& run = result.runs[static_cast<size_t>(i)];
    run.name = options.methods[static_cast<size_t>(i)];
    MethodScores& s = scored.at(run.name);
    const MethodReport report = EvaluateQueryScores(labelling, run.name, s.scores);
    run.metrics = report.metrics;
    run.metrics.SetTiming(s.extract_ms, s.match_ms);
    run.other_metrics = report.other_metrics;
    run.other_metrics.SetTiming(s.extract_ms, s.match_ms);
    run.scores = std::move(s.scores);
  });
  AddIntervals(dataset, options, &result);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (options.slam) AddSlam(dataset, options, &result);
  return result;
}

void AddSlam(const Dataset& dataset, const BenchOptions& options, BenchResult* result) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<NamedScores> named;
  for (const MethodRun& r : result->runs) named.push_back({r.name, &r.scores});
  SlamRunOptions slam_options = options.slam_options;
  slam_options.threads = options.threads;
  result->slam =
      RunSlam(dataset.poses(), dataset.scene_json(), dataset.dir() + "/scene.json", dataset.manifest().frame_rate_hz,
              options.protocol.radius_m, result->queries, named, slam_options);
  result->slam_evaluated = true;
  result->seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace hoilcd
