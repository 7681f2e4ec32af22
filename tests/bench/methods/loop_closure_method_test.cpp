#include "hoilcd/bench/methods/loop_closure_method.h"

#include <optional>
#include <set>

#include <gtest/gtest.h>

#include "hoilcd/bench/methods/method_params.h"
#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/sim/output/sequence.h"
#include "test_dir.h"
#include "tiny_room.h"

namespace hoilcd {
namespace {

Dataset TinyDataset(const test::TestDir& temp) { return test::TinyRoomDataset(temp / "dataset"); }

// A method from outside the built-ins: scores 1 for true matches, 0 otherwise.
class Oracle : public LoopClosureMethod {
 public:
  std::string Name() const override { return "test-oracle"; }
  std::string Description() const override { return "knows the labels"; }
  MethodScores Score(const MethodContext& c) const override {
    MethodScores out;
    for (const Query& q : c.queries()) out.scores.emplace_back(q.is_true_match.begin(), q.is_true_match.end());
    out.extract_ms.assign(c.queries().size(), 0.0);
    out.match_ms.assign(c.queries().size(), 0.0);
    return out;
  }
};

// A composite: SLCD's scores negated (reads another method's scores without asking for it).
class NegatedSlcd : public LoopClosureMethod {
 public:
  std::string Name() const override { return "test-negated-slcd"; }
  std::string Description() const override { return "SLCD upside down"; }
  std::vector<std::string> Inputs() const override { return {"slcd"}; }
  MethodScores Score(const MethodContext& c) const override {
    MethodScores out = c.Input("slcd");
    for (auto& row : out.scores)
      for (double& v : row) v = -v;
    return out;
  }
};

TEST(LoopClosureMethod, TheBuiltInsAreRegisteredInReportOrderWithThePapersThreeMarked) {
  EXPECT_EQ(DefaultMethods(),
            (std::vector<std::string>{"slcd", "dlcd", "fusion", "slcd-lo", "dlcd-lo", "dlcd-track", "fusion-tc",
                                      "thumb", "thumb-seq", "dlcd-oracle", "slcd-ideal"}));
  for (const auto& m : RegisteredMethods()) {
    EXPECT_FALSE(m->Description().empty()) << m->Name();
    EXPECT_EQ(CreateMethod(m->Name())->Name(), m->Name());
    for (const std::string& input : m->Inputs()) EXPECT_TRUE(IsMethod(input)) << m->Name() << " reads " << input;
  }
  EXPECT_TRUE(FindMethod("fusion").FromPaper());
  EXPECT_FALSE(FindMethod("thumb").FromPaper());
  EXPECT_EQ(FindMethod("dlcd-track").Features(), ShownFeatures::kHoiPoints);
}

// The report's gallery draws a method's matches through MatchPair: every method that shows
// features (the point-set methods, their oracles and dlcd-track) replays its matching on them, and
// one that shows none (thumbnails, fusions of rankings) has nothing to replay.
TEST(LoopClosureMethod, EveryMethodThatShowsFeaturesGivesAPairsMatchesThroughMatchPair) {
  // Three seated persons' bottom contours, a point every 6 px, and the same persons 2 px right and
  // 1 px down under other track ids: every point method pairs them all, a pure translation.
  std::vector<HoiFeature> query_hoi, reference_hoi;
  for (int person = 0; person < 3; ++person) {
    for (int i = 0; i < 10; ++i) {
      const float x = 40.0f + 80.0f * person + 6.0f * i, y = 120.0f + 10.0f * person + 0.3f * (i - 5) * (i - 5);
      query_hoi.push_back({Point2(x, y), person + 1});
      reference_hoi.push_back({Point2(x + 2.0f, y + 1.0f), person + 11});
    }
  }
  std::vector<Point2> query_points, reference_points;
  for (const HoiFeature& h : query_hoi) query_points.push_back(h.point);
  for (const HoiFeature& h : reference_hoi) reference_points.push_back(h.point);
  const std::vector<HoiFeature> no_hoi;
  const std::set<std::string> showing = {"slcd",       "dlcd",        "slcd-lo",   "dlcd-lo",
                                         "dlcd-track", "dlcd-oracle", "slcd-ideal"};
  for (const auto& method : RegisteredMethods()) {
    const std::string& name = method->Name();
    EXPECT_EQ(method->Features() != ShownFeatures::kNone, showing.count(name) > 0) << name;
    const bool hoi = IsHoi(method->Features());
    const std::unique_ptr<MethodOptions> own = method->Options();
    const std::optional<PairMatches> pair =
        method->MatchPair({own.get(), query_points, reference_points, hoi ? query_hoi : no_hoi,
                           hoi ? reference_hoi : no_hoi, 5, 9, 192, 7});
    if (method->Features() == ShownFeatures::kNone) {
      EXPECT_FALSE(pair.has_value()) << name;
      continue;
    }
    ASSERT_TRUE(pair.has_value()) << name;
    EXPECT_EQ(pair->matches.size(), query_points.size()) << name;
    ASSERT_EQ(pair->inlier.size(), pair->matches.size()) << name;
    EXPECT_EQ(pair->inliers, static_cast<int>(query_points.size())) << name;
    for (const Correspondence& m : pair->matches) EXPECT_EQ(m.query, m.reference) << name;
  }
}

TEST(LoopClosureMethod, ARegisteredMethodIsScoredByTheBenchLikeABuiltInAndCompositesGetTheirInputs) {
  RegisterMethod([] { return std::make_unique<Oracle>(); });
  RegisterMethod([] { return std::make_unique<NegatedSlcd>(); });
  EXPECT_EQ(ParseMethodList("test-oracle"), std::vector<std::string>{"test-oracle"});
  EXPECT_EQ(DefaultMethods().back(), "test-negated-slcd");
  EXPECT_THROW(RegisterMethod([] { return std::make_unique<Oracle>(); }), std::logic_error);

  const test::TestDir temp;
  const Dataset dataset = TinyDataset(temp);
  BenchOptions options;
  options.methods = {"test-oracle", "test-negated-slcd"};
  const BenchResult result = RunBench(dataset, options);
  ASSERT_EQ(result.runs.size(), 2u);  // slcd was scored as an input, not reported
  EXPECT_EQ(result.runs[0].metrics.mrr, 1.0);
  EXPECT_EQ(result.runs[1].name, "test-negated-slcd");
  EXPECT_GT(result.mean_keypoints_per_frame, 0.0);  // slcd's front end ran for its reader
  EXPECT_FALSE(result.tracking_evaluated);          // nobody needed the person front end
  options.methods = {"slcd"};
  const BenchResult slcd = RunBench(dataset, options);
  for (size_t i = 0; i < slcd.queries.size(); ++i) {
    for (size_t j = 0; j < slcd.runs[0].scores[i].size(); ++j) {
      EXPECT_EQ(result.runs[1].scores[i][j], -slcd.runs[0].scores[i][j]);
    }
  }
}

// Methods of one scoring pass: each scores every pair with its own constant; ScoreTogether
// records whom it was called with.
std::vector<std::vector<std::string>> pass_calls;
class Passing : public LoopClosureMethod {
 public:
  Passing(std::string name, std::string key, double value)
      : name_(std::move(name)), key_(std::move(key)), value_(value) {}
  std::string Name() const override { return name_; }
  std::string Description() const override { return "shares a pass"; }
  MethodScores Score(const MethodContext& c) const override {
    MethodScores out;
    for (const Query& q : c.queries()) out.scores.emplace_back(q.database.size(), value_);
    out.extract_ms.assign(c.queries().size(), 0.0);
    out.match_ms.assign(c.queries().size(), 0.0);
    return out;
  }
  std::string PassKey(const MethodContext&) const override { return key_; }
  std::vector<MethodScores> ScoreTogether(const std::vector<const LoopClosureMethod*>& methods,
                                          const std::vector<MethodContext>& contexts) const override {
    pass_calls.emplace_back();
    std::vector<MethodScores> out;
    for (size_t i = 0; i < methods.size(); ++i) {
      pass_calls.back().push_back(methods[i]->Name());
      out.push_back(methods[i]->Score(contexts[i]));
    }
    return out;
  }

 private:
  std::string name_, key_;
  double value_;
};

TEST(LoopClosureMethod, MethodsWithTheSamePassKeyAreScoredInOneCallAndEachGetsItsOwnScores) {
  RegisterMethod([] { return std::make_unique<Passing>("test-pass-a", "shared", 1.0); });
  RegisterMethod([] { return std::make_unique<Passing>("test-pass-b", "other", 2.0); });
  RegisterMethod([] { return std::make_unique<Passing>("test-pass-c", "shared", 3.0); });
  const test::TestDir temp;
  const Dataset dataset = TinyDataset(temp);
  BenchOptions options;
  options.methods = {"test-pass-c", "test-pass-b", "test-pass-a"};
  pass_calls.clear();
  const BenchResult result = RunBench(dataset, options);
  // c comes first in the scoring order, so its pass takes a too; b has a pass of its own and
  // is scored alone, by Score().
  EXPECT_EQ(pass_calls, (std::vector<std::vector<std::string>>{{"test-pass-c", "test-pass-a"}}));
  ASSERT_EQ(result.runs.size(), 3u);
  for (const MethodRun& run : result.runs) {
    const double expected = run.name == "test-pass-a" ? 1.0 : run.name == "test-pass-b" ? 2.0 : 3.0;
    for (const std::vector<double>& row : run.scores)
      for (double v : row) EXPECT_EQ(v, expected) << run.name;
  }
}

// The point-set methods on one index with the same matching have one pass key (so the runner
// scores them in one pass, as the test above shows for any key); any matching option a --param
// sets gives another key. In a pass or alone, each gets the scores it gets when benched alone.
TEST(LoopClosureMethod, PointSetMethodsOnOneIndexWithOneMatchingShareAPassAndScoreAsWhenBenchedAlone) {
  const test::TestDir temp;
  const Dataset dataset = TinyDataset(temp);
  const std::vector<std::string> point_sets = {"slcd", "dlcd", "slcd-lo", "dlcd-lo"};
  {
    const BenchOptions options;
    const Labelling labelling = LabelQueries(dataset, options.protocol);
    const FrontEndOutput front_ends;
    const std::map<std::string, MethodScores> scored;
    // Each method's key under its own options with `params` set.
    const auto key = [&](const std::string& method, const std::vector<std::string>& params = {}) {
      const auto own = OptionsWithParams(FindMethod(method), params);
      return FindMethod(method).PassKey(
          MethodContext{dataset, options, own.get(), labelling, front_ends, scored, 1, 1});
    };
    EXPECT_NE(key("slcd").find("image_height_px=" + std::to_string(dataset.manifest().intrinsics.height)),
              std::string::npos)
        << key("slcd");  // the vertical filter's height is the dataset's
    EXPECT_EQ(key("slcd"), key("slcd-lo"));
    EXPECT_EQ(key("dlcd"), key("dlcd-lo"));
    EXPECT_NE(key("slcd"), key("dlcd"));
    EXPECT_NE(key("slcd"), key("slcd-lo", {"slcd-lo.vertical_tolerance=0.2"}));
    EXPECT_EQ(key("slcd"), key("slcd-lo", {"slcd-lo.lo_refits=5", "slcd-lo.ransac_trials=7"}));  // RANSAC only
    EXPECT_EQ(key("fusion"), "");
    // Every matching option a --param can set is in the key: a changed value, another pass.
    for (const OptionInfo& info : MatchParams().List()) {
      ASSERT_TRUE(info.kind == OptionInfo::Kind::kNumber || info.kind == OptionInfo::Kind::kInteger) << info.name;
      const double value = std::stod(info.default_json);
      const std::string param =
          "slcd." + info.name + "=" + std::to_string(info.kind == OptionInfo::Kind::kInteger ? value + 1 : value / 2);
      EXPECT_NE(key("slcd", {param}), key("slcd")) << info.name;
    }
  }
  for (const std::vector<std::string>& params :
       {std::vector<std::string>{},
        std::vector<std::string>{"slcd-lo.vertical_tolerance=0.2", "dlcd.ransac_trials=30"}}) {
    BenchOptions options;
    options.params = params;
    options.methods = point_sets;
    const BenchResult together = RunBench(dataset, options);
    ASSERT_EQ(together.runs.size(), point_sets.size());
    for (const MethodRun& run : together.runs) {
      BenchOptions own = options;  // only its own --param values: others name methods not run
      own.methods = {run.name};
      own.params.clear();
      for (const std::string& p : params)
        if (p.rfind(run.name + ".", 0) == 0) own.params.push_back(p);
      const BenchResult alone = RunBench(dataset, own);
      EXPECT_EQ(run.scores, alone.runs[0].scores) << run.name << " with " << params.size() << " params";
      EXPECT_EQ(run.metrics.mrr, alone.runs[0].metrics.mrr) << run.name;
      bool some_score = false;
      for (const std::vector<double>& row : run.scores)
        for (double v : row) some_score |= v > 0;
      EXPECT_TRUE(some_score) << run.name;
    }
  }
}

}  // namespace
}  // namespace hoilcd
