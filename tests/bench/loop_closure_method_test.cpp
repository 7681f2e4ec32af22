#include "hoilcd/bench/loop_closure_method.h"

#include <gtest/gtest.h>

#include "hoilcd/bench/methods.h"
#include "hoilcd/bench/runner.h"
#include "hoilcd/sim/sequence.h"
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
  EXPECT_EQ(DefaultMethods(), (std::vector<std::string>{"slcd", "dlcd", "fusion", "slcd-lo", "dlcd-lo", "dlcd-track",
                                                         "fusion-tc", "thumb", "thumb-seq"}));
  for (const auto& m : RegisteredMethods()) {
    EXPECT_FALSE(m->Description().empty()) << m->Name();
    EXPECT_EQ(CreateMethod(m->Name())->Name(), m->Name());
    for (const std::string& input : m->Inputs()) EXPECT_TRUE(IsMethod(input)) << m->Name() << " reads " << input;
  }
  EXPECT_TRUE(FindMethod("fusion").FromPaper());
  EXPECT_FALSE(FindMethod("thumb").FromPaper());
  EXPECT_EQ(FindMethod("dlcd-track").Features(), ShownFeatures::kHoiPoints);
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
  EXPECT_GT(result.mean_keypoints_per_frame, 0.0);   // slcd's front end ran for its reader
  EXPECT_FALSE(result.tracking_evaluated);           // nobody needed the person front end
  options.methods = {"slcd"};
  const BenchResult slcd = RunBench(dataset, options);
  for (size_t i = 0; i < slcd.queries.size(); ++i) {
    for (size_t j = 0; j < slcd.runs[0].scores[i].size(); ++j) {
      EXPECT_EQ(result.runs[1].scores[i][j], -slcd.runs[0].scores[i][j]);
    }
  }
}

}  // namespace
}  // namespace hoilcd
