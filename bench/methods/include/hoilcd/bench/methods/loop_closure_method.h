// A loop-closure method as an object (as COLMAP's retrieval::VisualIndex): its name, one-line
// description, whether it is one of the paper's, which shared front ends it reads, which other
// methods' scores it combines (composites such as fusion), and how it scores every query against
// its database. Methods are made by name through the registry; the built-ins are listed once in
// bench/methods/src/method_list.h and other code can add its own with RegisterMethod.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hoilcd/bench/evaluation/evaluate.h"
#include "hoilcd/bench/methods/front_ends.h"
#include "hoilcd/bench/methods/method_options.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/matching/matching.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

struct BenchOptions;

// What a method produced for every query.
struct MethodScores {
  std::vector<std::vector<double>> scores;  // per query, parallel to Query::database, finite
  std::vector<double> extract_ms;           // per query: feature extraction of its frame, ms
  std::vector<double> match_ms;             // per query: scoring against its database, ms
  // Optional frames x frames similarity a method computed anyway (thumb), for methods built on it.
  std::vector<std::vector<float>> dense;
};

// Everything a method may read while scoring.
struct MethodContext {
  const Dataset& dataset;
  const BenchOptions& options;                        // the run's: protocol, front ends, threads
  const MethodOptions* own;                           // the method's own, with its --param values (null: none)
  const Labelling& labelling;                         // queries, their databases and which are worth scoring
  const FrontEndOutput& front_ends;                   // the front ends the run's methods asked for
  const std::map<std::string, MethodScores>& scored;  // methods scored so far (Inputs() included)
  uint64_t seed;                                      // the dataset's seed (keyed RNG of RANSAC)
  int threads;                                        // 0 = every core

  const std::vector<Query>& queries() const { return labelling.queries; }
  const MethodScores& Input(const std::string& name) const;                  // HOILCD_CHECK when not scored
  std::vector<double> PerQuery(const std::vector<double>& per_frame) const;  // picks each query's frame
  template <typename T>
  const T& Own() const {  // the method's own options struct (HOILCD_CHECK on another type)
    return OptionsValue<T>(own);
  }
};

// Which per-frame features the report draws for a method's matches: a front end's, as the
// bench keeps them per frame (runner.h FrameFeatures).
enum class ShownFeatures {
  kNone,            // none: the method matches no points (thumbnails, fusion of rankings)
  kKeypoints,       // FrontEnd::kKeypoints' corners
  kHoiPoints,       // FrontEnd::kPersons' HOI points
  kIdealKeypoints,  // FrontEnd::kIdealKeypoints' corners (an oracle's)
  kTrueHoiPoints,   // FrontEnd::kTruePersons' HOI points (an oracle's)
};
// Whether the features are HOI points (with their persons' track ids).
inline bool IsHoi(ShownFeatures features) {
  return features == ShownFeatures::kHoiPoints || features == ShownFeatures::kTrueHoiPoints;
}

// One (query, reference) pair as the report's gallery asks a method to match it again.
struct PairMatchInput {
  const MethodOptions* own;                     // the method's own options as it ran (null: none)
  const std::vector<Point2>& query_points;      // the query frame's shown features (Features()), px
  const std::vector<Point2>& reference_points;  // the reference frame's, px
  // When Features() are HOI points, the same points with their persons' track ids, in the same
  // order; empty otherwise.
  const std::vector<HoiFeature>& query_hoi;
  const std::vector<HoiFeature>& reference_hoi;
  int query_frame, reference_frame;  // frame indices (they key RANSAC's stream)
  int image_height_px;               // the dataset's
  uint64_t seed;                     // the dataset's, as in MethodContext
};

class LoopClosureMethod {
 public:
  virtual ~LoopClosureMethod() = default;
  virtual std::string Name() const = 0;             // as given to --methods
  virtual std::string Description() const = 0;      // one line for the report
  virtual bool FromPaper() const { return false; }  // one of the paper's Table 1 methods
  virtual ShownFeatures Features() const { return ShownFeatures::kNone; }
  virtual std::set<FrontEnd> FrontEnds() const { return {}; }
  virtual std::vector<std::string> Inputs() const { return {}; }  // scored before this one
  // Whether a query's scores depend only on that query and its database's frames (not on other
  // queries or later frames), so the online bench (bench/runner online.h) can score each query
  // against its shortlist as it comes.
  virtual bool Online() const { return false; }
  // The method's own options at their defaults, a fresh copy per call (null: none). The runner
  // sets --param <name>.<field>=VALUE on it and hands it to Score as MethodContext::own; the
  // report prints its resolved values. Declared in the method's folder (method_options.h).
  virtual std::unique_ptr<MethodOptions> Options() const { return nullptr; }
  virtual MethodScores Score(const MethodContext& context) const = 0;
  // The matches behind one pair's score, for the report's gallery (report.html), which re-runs
  // only its sampled pairs: a method whose Features() are shown may return the matches its Score
  // found between those features of the two frames, with their RANSAC inliers (inliers equal to
  // its score). nullopt (the default): nothing to draw but the features; the page says so.
  virtual std::optional<PairMatches> MatchPair(const PairMatchInput& input) const {
    (void)input;
    return std::nullopt;
  }

  // Scoring in one pass with other methods. Methods without Inputs() whose PassKey (under their
  // own options) is the same non-empty text are scored by one ScoreTogether call on the first of
  // them in scoring order, with all of them and their contexts; it returns what each one's
  // Score() would (scores and timing). A key names one family of classes that can score each
  // other (prefix it with the family's name). The point-set methods share each pair's MNN this way.
  virtual std::string PassKey(const MethodContext& context) const {
    (void)context;
    return "";
  }
  virtual std::vector<MethodScores> ScoreTogether(const std::vector<const LoopClosureMethod*>& methods,
                                                  const std::vector<MethodContext>& contexts) const;
};

using MethodFactory = std::function<std::unique_ptr<LoopClosureMethod>()>;

// Adds a method to every later lookup (after the built-ins, in call order). InputError-free:
// HOILCD_CHECK on a name already taken.
void RegisterMethod(const MethodFactory& factory);

// A new instance of the method called `name`; HOILCD_CHECK on unknown names (ParseMethodList
// validates user input first).
std::unique_ptr<LoopClosureMethod> CreateMethod(const std::string& name);

// One instance of every registered method, in report order.
const std::vector<std::unique_ptr<LoopClosureMethod>>& RegisteredMethods();

}  // namespace hoilcd
