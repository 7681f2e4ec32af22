#include "hoilcd/bench/evaluation/report_json.h"

#include <string>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hoilcd/core/util/file_io.h"
#include "input_error_of.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

using test::InputErrorOf;

std::string TextError(const std::string& text) {
  return InputErrorOf([&] { ReportJsonFromText(text, "b.json"); });
}

TEST(ReportJson, AReportWithHeadlineMetricsOrNullReadsBack) {
  const std::string text = R"({"methods": {"slcd": {"mrr": 0.5, "recall_at_1": null, "pr_auc": 7}}})";
  EXPECT_EQ(TextError(text), "");
  EXPECT_EQ(ReportJsonFromText(text, "b.json")["methods"]["slcd"]["mrr"], 0.5);
}

TEST(ReportJson, ABaselineThatIsNotAReportNamesTheFileThePointerAndWhatWasExpected) {
  EXPECT_NE(TextError("{nope").find("b.json: is not JSON: expected a hoilcd report.json (parse error at line 1, "
                                    "column 3: "),
            std::string::npos);
  EXPECT_NE(TextError("[]").find("b.json: /methods: expected an object of methods"), std::string::npos);
  EXPECT_NE(TextError(R"({"methods": {"a/b~c": 3}})")
                .find("b.json: /methods/a~1b~0c: expected an object of the "
                      "method's metrics"),
            std::string::npos);
  EXPECT_NE(TextError(R"({"methods": {"slcd": {"mrr": "high", "recall_at_1": 1}}})")
                .find("b.json: /methods/slcd/mrr: expected a number or null (a fraction, in [0, 1])"),
            std::string::npos);
  EXPECT_NE(TextError(R"({"methods": {"slcd": {"mrr": 0.5}}})").find("/methods/slcd/recall_at_1: expected a number"),
            std::string::npos);
  EXPECT_NE(TextError(R"({"methods": {"slcd": {"mrr": 1.5, "recall_at_1": 0}}})").find("/methods/slcd/mrr: expected"),
            std::string::npos);
  EXPECT_NE(TextError(R"({"methods": {"slcd": {"mrr": 1e400, "recall_at_1": 0}}})")
                .find("b.json: is not JSON: expected a hoilcd report.json ("),
            std::string::npos);
}

TEST(ReportJson, ControlCharactersAndNulInTheTextAreShownEscaped) {
  std::string text = R"({"methods": {"a\u0000\u001b": {"mrr": "x"}}})";
  std::string error = TextError(text);
  EXPECT_NE(error.find("b.json: /methods/a\\x00\\x1b/mrr: expected a number"), std::string::npos) << error;
  text = std::string("{\"methods\": \0\xff}", 16);
  error = TextError(text);
  EXPECT_EQ(error.find('\0'), std::string::npos) << error;
  EXPECT_NE(error.find("b.json: is not JSON: expected a hoilcd report.json ("), std::string::npos) << error;
}

TEST(ReportJson, NestingDeeperThanAnyReportIsRefusedBeforeItIsBuilt) {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  const std::string error = TextError(deep);
  EXPECT_NE(error.find("b.json: /0/0/0/"), std::string::npos) << error;
  EXPECT_NE(error.find(": nests deeper than 64 levels of objects and arrays"), std::string::npos) << error;
}

TEST(ReportJson, RefusesAFifoWithoutBlocking) {
  const test::TestDir dir;
  ASSERT_EQ(::mkfifo((dir / "baseline.json").c_str(), 0600), 0);
  EXPECT_NE(InputErrorOf([&] {
              ReadReportJson(dir / "baseline.json");
            }).find(dir / "baseline.json" + ": is a FIFO: expected a regular file"),
            std::string::npos);
}

TEST(ReportJson, AHugeSparseBaselineIsRefusedByItsSizeBeforeItIsRead) {
  const test::TestDir dir;
  const std::string path = dir / "baseline.json";
  WriteFileAtomic(path, "{");
  ASSERT_EQ(::truncate(path.c_str(), off_t{1} << 33), 0);
  EXPECT_NE(InputErrorOf([&] {
              ReadReportJson(path);
            }).find(path + ": is 8589934592 bytes: expected a hoilcd report.json, at most 64 MiB"),
            std::string::npos);
}

}  // namespace
}  // namespace hoilcd
