#include "hoilcd/bench/runner/online.h"

#include <gtest/gtest.h>

#include "hoilcd/bench/evaluation/metrics.h"
#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/bench/report/online_report.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "input_error_of.h"
#include "recording_runs.h"
#include "test_dir.h"
#include "tiny_room.h"

namespace hoilcd {
namespace {

BenchOptions PaperOptions(const std::string& protocol, int threads = 0) {
  BenchOptions options;
  options.methods = ParseMethodList("paper");
  options.protocol.protocol = protocol;
  options.threads = threads;
  return options;
}

ShortlistOptions Shortlist(int k, const std::string& index = "hnsw") {
  ShortlistOptions s;
  s.k = k;
  s.index = index;
  return s;
}

TEST(Online, WithEveryFrameShortlistedItScoresExactlyAsTheOfflineRevisitProtocol) {
  const test::TestDir temp;
  const Dataset dataset = test::TinyRoomDataset(temp / "d");
  const BenchResult offline = RunBench(dataset, PaperOptions("revisit"));
  const OnlineResult online = RunOnlineBench(dataset, PaperOptions("revisit"), Shortlist(0));
  ASSERT_EQ(online.runs.size(), 3u);
  EXPECT_EQ(online.shortlist_recall, 1.0);
  for (const OnlineMethodRun& run : online.runs) {
    const MethodMetrics& o = offline.Find(run.name)->metrics;
    EXPECT_GT(run.metrics.queries_scored, 0) << run.name;
    EXPECT_EQ(run.metrics.queries_scored, o.queries_scored) << run.name;
    EXPECT_DOUBLE_EQ(run.metrics.mrr, o.mrr) << run.name;
    EXPECT_DOUBLE_EQ(run.metrics.recall_at_1, o.recall_at_1) << run.name;
    EXPECT_DOUBLE_EQ(run.metrics.pr_auc, o.pr_auc) << run.name;
    EXPECT_EQ(run.query_ms.size(), static_cast<size_t>(online.queries_processed)) << run.name;
  }
}

TEST(Online, AShortShortlistMissesSomeTrueMatchesAndTheRecallCountsThem) {
  const test::TestDir temp;
  const Dataset dataset = test::TinyRoomDataset(temp / "d");
  const OnlineResult one = RunOnlineBench(dataset, PaperOptions("laps", 1), Shortlist(3, "flat"));
  EXPECT_GT(one.queries_scored, 0);
  EXPECT_LE(one.shortlist_hits, one.queries_scored);
  EXPECT_DOUBLE_EQ(one.shortlist_recall, static_cast<double>(one.shortlist_hits) / one.queries_scored);
  // A query whose shortlist holds no true match ranks it among the unranked rest, below the 3.
  for (const OnlineMethodRun& run : one.runs) {
    for (const QueryRecord& r : run.metrics.queries) {
      if (r.scored && r.first_true_rank > 3) {
        EXPECT_LT(r.reciprocal_rank, 1.0 / 3) << run.name << " " << r.frame;
      }
    }
  }
  // Laps: only later laps query, but the database is every older frame.
  for (const QueryRecord& r : one.runs.front().metrics.queries) EXPECT_GT(r.lap, 0);
  // The same at two threads.
  const OnlineResult two = RunOnlineBench(dataset, PaperOptions("laps", 2), Shortlist(3, "flat"));
  for (size_t m = 0; m < one.runs.size(); ++m) {
    EXPECT_EQ(one.runs[m].metrics.mrr, two.runs[m].metrics.mrr) << one.runs[m].name;
    EXPECT_EQ(one.runs[m].intervals.mrr.low, two.runs[m].intervals.mrr.low) << one.runs[m].name;
  }
  EXPECT_EQ(one.shortlist_hits, two.shortlist_hits);
}

TEST(Online, MethodsThatNeedTheWholeSequenceAreRefusedByNameOrLeftOutWithANote) {
  const test::TestDir temp;
  const Dataset dataset = test::TinyRoomDataset(temp / "d");
  BenchOptions options;
  options.methods = {"slcd", "thumb"};
  EXPECT_NE(test::InputErrorOf([&] { RunOnlineBench(dataset, options, Shortlist(5)); }).find("thumb cannot run online"),
            std::string::npos);
  options.methods = ParseMethodList("all", &options.optional_methods);
  const OnlineResult result = RunOnlineBench(dataset, options, Shortlist(5));
  EXPECT_NE(result.Find("fusion"), nullptr);
  EXPECT_EQ(result.Find("thumb"), nullptr);
  EXPECT_EQ(result.Find("fusion-tc"), nullptr);  // combines fusion over time
  bool noted = false;
  for (const std::string& s : result.skipped) noted |= s.rfind("thumb:", 0) == 0;
  EXPECT_TRUE(noted);
  BenchOptions overlap = PaperOptions("laps");
  overlap.protocol.ground_truth = "overlap";
  EXPECT_NE(test::InputErrorOf([&] { RunOnlineBench(dataset, overlap, Shortlist(5)); }).find("--ground-truth"),
            std::string::npos);
}

TEST(Online, TheReportFolderHoldsItsJsonMarkdownAndHtml) {
  const test::TestDir temp;
  const Dataset dataset = test::TinyRoomDataset(temp / "d");
  const OnlineResult result = RunOnlineBench(dataset, PaperOptions("laps"), Shortlist(5));
  WriteOnlineReport(result, dataset, temp / "report");
  const nlohmann::json json = nlohmann::json::parse(ReadFileBytes(temp / "report/report.json"));
  EXPECT_EQ(json["mode"], "online");
  EXPECT_EQ(json["online"]["shortlist"]["k"], 5);
  EXPECT_TRUE(json["methods"]["slcd"]["mrr"].is_number());
  EXPECT_TRUE(json["methods"]["fusion"]["p99_ms"].is_number());
  EXPECT_NE(ReadFileBytes(temp / "report/report.md").find("shortlist recall"), std::string::npos);
  const std::string html = ReadFileBytes(temp / "report/report.html");
  EXPECT_NE(html.find("<td>slcd</td>"), std::string::npos);
  EXPECT_NE(html.find("shortlist held a true match"), std::string::npos);
  WriteOnlineReport(result, dataset, temp / "report");  // over its own earlier report
}

// Two recording runs: the runs protocol queries the second run only (its database every older
// frame, as online always); each run's figures with every frame shortlisted are the offline ones.
TEST(Online, ADatasetOfRecordingRunsIsReportedPerRunAsOffline) {
  const test::TestDir temp;
  const Dataset dataset = test::TinyRoomTwoRuns(temp.str(), 230);
  BenchOptions options;
  options.methods = {"slcd"};
  options.protocol.protocol = "runs";
  const OnlineResult runs = RunOnlineBench(dataset, options, Shortlist(5));
  EXPECT_EQ(runs.queries_processed, 230);
  ASSERT_EQ(runs.per_run.size(), 2u);
  EXPECT_EQ(runs.per_run[0].queries, 0);
  EXPECT_EQ(runs.per_run[1].queries, 230);
  WriteOnlineReport(runs, dataset, temp / "report");
  EXPECT_EQ(nlohmann::json::parse(ReadFileBytes(temp / "report/report.json"))["recording_runs"].size(), 2u);
  EXPECT_NE(ReadFileBytes(temp / "report/report.md").find("### Results by recording run"), std::string::npos);

  options.protocol.protocol = "revisit";
  const OnlineResult online = RunOnlineBench(dataset, options, Shortlist(0));
  const BenchResult offline = RunBench(dataset, options);
  ASSERT_EQ(online.per_run.size(), 2u);
  EXPECT_GT(online.per_run[1].queries_scored, 0);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(online.per_run[k].queries_scored, offline.per_run[k].queries_scored) << k;
    if (online.per_run[k].queries_scored == 0) continue;  // a run without a revisit: no figures
    EXPECT_DOUBLE_EQ(online.per_run[k].mrr[0], offline.per_run[k].mrr[0]) << k;
    EXPECT_DOUBLE_EQ(online.per_run[k].recall_at_1[0], offline.per_run[k].recall_at_1[0]) << k;
  }
}

TEST(Online, TimingRowsSplitDecadesOneTwoFive) {
  const std::vector<OnlineTimingRow> rows =
      TimingByDatabaseSize({0, 999, 1000, 1999, 2000, 4999, 5000, 120000}, {1, 2, 3, 4, 5, 6, 7, 8});
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[0].database_from, 0);
  EXPECT_EQ(rows[0].database_to, 1000);
  EXPECT_EQ(rows[0].queries, 2);
  EXPECT_EQ(rows[1].database_to, 2000);
  EXPECT_EQ(rows[2].database_to, 5000);
  EXPECT_EQ(rows[3].database_to, 10000);
  EXPECT_EQ(rows[4].database_from, 100000);
  EXPECT_EQ(rows[4].database_to, 200000);
  EXPECT_DOUBLE_EQ(rows[1].p50_ms, 3.5);
}

TEST(Online, AShortlistRecordRanksTheUnlistedRestBelowAsOneTie) {
  std::vector<PoseRecord> poses(10);
  for (int f = 0; f < 10; ++f) poses[f].frame = f, poses[f].x_m = f;
  Query q;
  q.frame = 9;
  q.database = {2, 5};
  q.is_true_match = {0, 0};
  // 8 frames in the database, 2 shortlisted (neither true), 3 true among the other 6.
  const QueryRecord r = ShortlistRecord(q, {4.0, 1.0}, 8, 3, poses);
  ASSERT_TRUE(r.scored);
  EXPECT_EQ(r.top1_frame, 2);
  EXPECT_DOUBLE_EQ(r.first_true_rank, 2 + 7.0 / 4);  // 2 above, then a tie of 6 holding 3 true
  EXPECT_DOUBLE_EQ(r.recall_at_1, 0.0);
  // With the whole database shortlisted it is the offline record.
  Query all;
  all.frame = 9;
  all.database = {1, 2, 3};
  all.is_true_match = {0, 1, 0};
  const std::vector<double> scores = {3, 2, 2};
  const MethodMetrics offline = ComputeMetrics({all}, {scores}, poses);
  const QueryRecord listed = ShortlistRecord(all, scores, 3, 1, poses);
  EXPECT_DOUBLE_EQ(listed.reciprocal_rank, offline.queries.front().reciprocal_rank);
  EXPECT_EQ(listed.top1_frame, offline.queries.front().top1_frame);
}

}  // namespace
}  // namespace hoilcd
