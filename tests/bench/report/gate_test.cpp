#include "hoilcd/bench/report/gate.h"

#include <cmath>

#include <gtest/gtest.h>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/safe_text.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

nlohmann::json Report(double slcd_mrr, double slcd_r1, double dlcd_mrr) {
  nlohmann::json j;
  j["methods"]["slcd"] = {{"mrr", slcd_mrr}, {"recall_at_1", slcd_r1}};
  j["methods"]["dlcd"] = {{"mrr", dlcd_mrr}, {"recall_at_1", 0.1}};
  return j;
}

TEST(Gate, AReportComparedWithItselfHasNoRegression) {
  const nlohmann::json r = Report(0.5, 0.4, 0.2);
  EXPECT_TRUE(CompareToBaseline(r, r, 0.0).empty());
}

TEST(Gate, OnlyDropsLargerThanTheAllowedOneAreRegressionsAndEachNamesMethodMetricOldAndNew) {
  const nlohmann::json baseline = Report(0.5, 0.4, 0.2);
  const nlohmann::json current = Report(0.45, 0.39, 0.2);
  const auto regressions = CompareToBaseline(baseline, current, 0.02);
  ASSERT_EQ(regressions.size(), 1u);
  EXPECT_EQ(regressions[0].method, "slcd");
  EXPECT_EQ(regressions[0].metric, "mrr");
  EXPECT_EQ(regressions[0].ToString(0.02),
            "regression: method slcd, mrr old 0.5000 new 0.4500 (dropped by more than 0.0200)");
  EXPECT_EQ(CompareToBaseline(baseline, current, 0.1).size(), 0u);
  EXPECT_EQ(CompareToBaseline(baseline, current, 0.0).size(), 2u);  // R@1 0.40 -> 0.39 too
}

TEST(Gate, MethodsInOnlyOneReportAreNotComparedAndAMissingNewValueIsARegression) {
  nlohmann::json baseline = Report(0.5, 0.4, 0.2);
  baseline["methods"]["thumb"] = {{"mrr", 0.9}, {"recall_at_1", 0.9}};
  nlohmann::json current = Report(0.5, 0.4, 0.2);
  current["methods"]["mine"] = {{"mrr", 0.0}, {"recall_at_1", 0.0}};
  EXPECT_TRUE(CompareToBaseline(baseline, current, 0.0).empty());
  EXPECT_EQ(MethodsOnlyInBaseline(baseline, current), std::vector<std::string>{"thumb"});
  current["methods"]["dlcd"]["mrr"] = nullptr;
  const auto regressions = CompareToBaseline(baseline, current, 0.5);
  ASSERT_EQ(regressions.size(), 1u);
  EXPECT_NE(regressions[0].ToString(0.5).find("dlcd, mrr old 0.2000 new none"), std::string::npos);
}

TEST(Gate, WithTheIntervalADropIsARegressionOnlyWhenTheBaselineLiesAboveTheNewInterval) {
  const nlohmann::json baseline = Report(0.5, 0.4, 0.2);
  nlohmann::json current = Report(0.45, 0.39, 0.2);
  DropAllowance ci;
  ci.interval = true;
  // slcd's MRR fell by 0.05, but its interval reaches 0.52: the queries explain the drop.
  current["methods"]["slcd"]["intervals"] = {{"mrr", {0.38, 0.52}}, {"recall_at_1", {0.30, 0.45}}};
  current["methods"]["dlcd"]["intervals"] = {{"mrr", {0.15, 0.25}}, {"recall_at_1", {0.05, 0.15}}};
  EXPECT_TRUE(CompareToBaseline(baseline, current, ci).empty());
  // A narrower interval no longer reaches the old value.
  current["methods"]["slcd"]["intervals"]["mrr"] = {0.41, 0.49};
  const auto regressions = CompareToBaseline(baseline, current, ci);
  ASSERT_EQ(regressions.size(), 1u);
  EXPECT_EQ(
      regressions[0].ToString(ci),
      "regression: method slcd, mrr old 0.5000 new 0.4500 (old above the new run's 95 % interval [0.4100, 0.4900])");
  // Without an interval the allowance is zero; a missing new value is always a regression.
  current["methods"]["dlcd"].erase("intervals");
  current["methods"]["dlcd"]["mrr"] = 0.19;
  EXPECT_EQ(CompareToBaseline(baseline, current, ci).size(), 2u);
  current["methods"]["dlcd"]["mrr"] = nullptr;
  EXPECT_EQ(CompareToBaseline(baseline, current, ci).size(), 2u);
}

TEST(Gate, TheAllowanceIsANumberInZeroToOneOrCi) {
  EXPECT_TRUE(DropAllowance::Parse("ci", "--max-drop").interval);
  EXPECT_DOUBLE_EQ(DropAllowance::Parse("0.02", "--max-drop").max_drop, 0.02);
  for (const char* bad : {"", "CI", "nan", "-0.1", "1.5", "0.1x"}) {
    try {
      DropAllowance::Parse(bad, "--max-drop");
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--max-drop"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("a number in [0, 1] or 'ci'"), std::string::npos) << e.what();
    }
  }
}

TEST(Gate, JUnitHasOneTestCasePerMethodAndAFailureForEachRegressedOne) {
  const nlohmann::json current = Report(0.3, 0.4, 0.2);
  const std::string xml = JUnitXml(current, CompareToBaseline(Report(0.5, 0.4, 0.2), current, 0.0), 0.0);
  EXPECT_NE(xml.find("<testsuite name=\"hoilcd\" tests=\"2\" failures=\"1\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<testcase classname=\"hoilcd.loop_closure\" name=\"slcd\">\n    <failure"), std::string::npos)
      << xml;
  EXPECT_NE(xml.find("<testcase classname=\"hoilcd.loop_closure\" name=\"dlcd\">\n    <system-out>"), std::string::npos)
      << xml;
}

TEST(Gate, JUnitOfAMethodNamedWithControlAndLatin1BytesIsWellFormedXml10) {
  nlohmann::json current = Report(0.3, 0.4, 0.2);
  const std::string name = "m\x01y <caf\xe9> \xef\xbf\xbe";
  current["methods"][name] = {{"mrr", 0.1}, {"recall_at_1", 0.1}};
  nlohmann::json baseline = Report(0.3, 0.4, 0.2);
  baseline["methods"][name] = {{"mrr", 0.9}, {"recall_at_1", 0.9}};
  const std::string xml = JUnitXml(current, CompareToBaseline(baseline, current, 0.0), 0.0);
  // The name shows its bytes visibly, in the test case and in the failure text.
  EXPECT_NE(xml.find("name=\"m\\x01y &lt;caf\\xe9&gt; \\xef\\xbf\\xbe\">"), std::string::npos) << xml;
  EXPECT_NE(xml.find("method m\\x01y &lt;caf\\xe9&gt; \\xef\\xbf\\xbe, mrr"), std::string::npos) << xml;
  // XML 1.0's characters: valid UTF-8 (SafeText leaves it alone) with no control character but
  // line feeds, and neither U+FFFE nor U+FFFF.
  std::string without_line_feeds = xml;
  for (char& c : without_line_feeds)
    if (c == '\n') c = ' ';
  EXPECT_EQ(SafeText(without_line_feeds), without_line_feeds);
  EXPECT_EQ(xml.find("\xef\xbf\xbe"), std::string::npos);
}

TEST(Gate, ABaselineThatIsNotAReportIsAnErrorNamingTheFileAndWhatWasExpected) {
  const test::TestDir temp;
  auto error = [&](const std::string& text) {
    WriteFileAtomic(temp / "b.json", text);
    try {
      ReadReportJson(temp / "b.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error("{nope").find("b.json: is not JSON: expected a hoilcd report.json"), std::string::npos);
  EXPECT_NE(error("{}").find("b.json: /methods: expected an object of methods"), std::string::npos);
  EXPECT_NE(error("{\"methods\": {\"slcd\": {\"mrr\": \"high\", \"recall_at_1\": 1}}}")
                .find("b.json: /methods/slcd/mrr: expected a number or null"),
            std::string::npos);
  EXPECT_EQ(error(Report(0.1, 0.1, 0.1).dump()), "");
}

}  // namespace
}  // namespace hoilcd
