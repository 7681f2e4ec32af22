#include "point_set/point_set_method.h"

#include <cstdio>

#include "hoilcd/bench/methods/method_params.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/progress.h"

namespace hoilcd {
namespace {

const RetrievalIndex& IndexOf(const FrontEndOutput& front_ends, FrontEnd front_end) {
  switch (front_end) {
    case FrontEnd::kKeypoints:
      return front_ends.keypoint_index;
    case FrontEnd::kIdealKeypoints:
      return front_ends.ideal_keypoint_index;
    case FrontEnd::kTruePersons:
      return front_ends.true_hoi_index;
    default:
      return front_ends.hoi_index;
  }
}

const std::vector<double>& ExtractMsOf(const FrontEndOutput& front_ends, FrontEnd front_end) {
  switch (front_end) {
    case FrontEnd::kKeypoints:
      return front_ends.keypoints_ms;
    case FrontEnd::kIdealKeypoints:
      return front_ends.ideal_keypoints_ms;
    case FrontEnd::kTruePersons:
      return front_ends.true_persons_ms;
    default:
      return front_ends.persons_ms;
  }
}

// The matching a method runs: its own tolerance, the dataset's image height.
MatchOptions MatchOf(const MethodContext& context) {
  MatchOptions match = context.Own<PointSetOptions>().match;
  match.image_height_px = context.dataset.manifest().intrinsics.height;
  return match;
}

}  // namespace

// The features of the front end the method's index holds (the bench keeps each one's per frame).
ShownFeatures PointSetMethod::Features() const {
  switch (front_end_) {
    case FrontEnd::kKeypoints:
      return ShownFeatures::kKeypoints;
    case FrontEnd::kPersons:
      return ShownFeatures::kHoiPoints;
    case FrontEnd::kIdealKeypoints:
      return ShownFeatures::kIdealKeypoints;
    case FrontEnd::kTruePersons:
      return ShownFeatures::kTrueHoiPoints;
    default:
      return ShownFeatures::kNone;
  }
}

const OptionTable<PointSetOptions>& PointSetOptions::Table(bool lo) {
  using O = PointSetOptions;
  static const OptionTable<O> plain =
      OptionTable<O>().Flatten(&O::ransac, RansacParams()).Flatten(&O::match, MatchParams());
  static const OptionTable<O> with_lo =
      OptionTable<O>(plain).Flatten(&O::ransac, RansacOptions::Table()
                                                    .Only({"local_optimisation_refits"})
                                                    .Rename("local_optimisation_refits", "lo_refits")
                                                    .WithDefault("lo_refits", 2));
  return lo ? with_lo : plain;
}

std::unique_ptr<MethodOptions> PointSetMethod::Options() const {
  return std::make_unique<OptionsOf<PointSetOptions>>(PointSetOptions::Table(lo_));
}

MethodScores PointSetMethod::Score(const MethodContext& context) const {
  return ScoreTogether({this}, {context}).front();
}

// The pair's MNN, vertical filter and RANSAC as ScoreDatabases runs them (the same key, options
// and stream), on the shown features, which are the index's points.
std::optional<PairMatches> PointSetMethod::MatchPair(const PairMatchInput& input) const {
  if (Features() == ShownFeatures::kNone) return std::nullopt;
  const PointSetOptions& own = OptionsValue<PointSetOptions>(input.own);
  MatchOptions match = own.match;
  match.image_height_px = input.image_height_px;
  return hoilcd::MatchPair(input.query_points, input.reference_points, match, own.ransac, input.seed, input.query_frame,
                           input.reference_frame);
}

// The index and the matching decide the MNN; the seed is the dataset's for every method.
std::string PointSetMethod::PassKey(const MethodContext& context) const {
  const MatchOptions match = MatchOf(context);
  char key[120];
  std::snprintf(key, sizeof(key), "point-set %s vertical_tolerance=%.17g image_height_px=%d",
                FrontEndName(front_end_).c_str(), match.vertical_tolerance, match.image_height_px);
  return key;
}

std::vector<MethodScores> PointSetMethod::ScoreTogether(const std::vector<const LoopClosureMethod*>& methods,
                                                        const std::vector<MethodContext>& contexts) const {
  HOILCD_CHECK_MSG(methods.size() == contexts.size() && !methods.empty() && methods.front() == this,
                   "a scoring pass is called on its first method, with one context per method");
  // Only the first context's matching options, seed, threads, queries and front ends are used.
  const MethodContext& context = contexts.front();
  std::vector<RansacOptions> variants;
  std::string title;
  for (size_t m = 0; m < methods.size(); ++m) {
    const auto* method = dynamic_cast<const PointSetMethod*>(methods[m]);
    const MethodContext& c = contexts[m];
    HOILCD_CHECK_MSG(method != nullptr && method->front_end_ == front_end_ && MatchOf(c) == MatchOf(context) &&
                         c.seed == context.seed && c.threads == context.threads && &c.labelling == &context.labelling &&
                         &c.front_ends == &context.front_ends,
                     methods[m]->Name() << " cannot share " << Name() << "'s scoring pass");
    variants.push_back(c.Own<PointSetOptions>().ransac);
    title += (m ? " + " : "") + methods[m]->Name();
  }
  const std::vector<Query>& queries = context.queries();
  // Every scored query in one parallel call; skipped queries are not scored (all 0).
  std::vector<size_t> scored;
  std::vector<int> frames;
  std::vector<std::vector<int>> databases;
  for (size_t i = 0; i < queries.size(); ++i) {
    if (!context.labelling.to_score[i] || queries[i].database.empty()) continue;
    scored.push_back(i);
    frames.push_back(queries[i].frame);
    databases.push_back(queries[i].database);
  }
  int64_t pairs = 0;
  for (const std::vector<int>& d : databases) pairs += static_cast<int64_t>(d.size());
  ProgressReporter progress(title, pairs, "pairs");
  std::vector<std::vector<int64_t>> time_ns;
  const auto tables = IndexOf(context.front_ends, front_end_)
                          .ScoreDatabases(frames, databases, MatchOf(context), variants, context.seed, context.threads,
                                          &time_ns, &progress);
  progress.Done();
  std::vector<MethodScores> out(methods.size());
  for (size_t m = 0; m < methods.size(); ++m) {
    out[m].scores.resize(queries.size());
    out[m].match_ms.assign(queries.size(), 0.0);
    for (size_t i = 0; i < queries.size(); ++i) out[m].scores[i].assign(queries[i].database.size(), 0.0);
    for (size_t k = 0; k < scored.size(); ++k) {
      out[m].scores[scored[k]].assign(tables[m][k].begin(), tables[m][k].end());
      out[m].match_ms[scored[k]] = 1e-6 * static_cast<double>(time_ns[m][k]);
    }
    out[m].extract_ms = contexts[m].PerQuery(ExtractMsOf(context.front_ends, front_end_));
  }
  return out;
}

}  // namespace hoilcd
