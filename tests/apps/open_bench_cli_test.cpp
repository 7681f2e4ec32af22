// End to end through the command line: bench --dump-scores -> evaluate --scores reproduces every
// method's metrics exactly; the CI gate's exit codes; evaluate's errors; evaluate's and inspect's
// -o folders and the guard they share with bench; the protocol flags' defaults in the help.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core/utility.hpp>
#include <sys/stat.h>

#include "cli.h"
#include "hoilcd/bench/evaluation/protocol.h"
#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/sim/output/sequence.h"
#include "test_dir.h"
#include "tiny_room.h"

namespace hoilcd {
namespace {

int Hoilcd(std::vector<std::string> args) {
  args.insert(args.begin(), {"hoilcd", "-q"});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  return RunCommandLine(static_cast<int>(argv.size()), argv.data());
}

std::string RenderTiny(const test::TestDir& temp) { return test::RenderTinyRoom(temp / "dataset"); }

nlohmann::json Json(const std::string& path) { return nlohmann::json::parse(ReadFileBytes(path)); }

// hoilcd's loops use the threads --threads gives them; OpenCV's own pool (an arena of every
// core) would add a spinning worker to a --threads 1 bench.
TEST(OpenBenchCli, TheCommandLineTurnsOpenCvsOwnThreadsOff) {
  cv::setNumThreads(-1);  // OpenCV's default: every core
  EXPECT_EQ(Hoilcd({"validate", std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/tiny_room.json"}), 0);
  const std::thread::id caller = std::this_thread::get_id();
  std::mutex mutex;
  std::set<std::thread::id> seen;
  cv::parallel_for_(cv::Range(0, 500), [&](const cv::Range& range) {
    for (int i = range.start; i < range.end; ++i) {
      std::this_thread::sleep_for(std::chrono::microseconds(20));  // long enough to share
      std::lock_guard<std::mutex> lock(mutex);
      seen.insert(std::this_thread::get_id());
    }
  });
  EXPECT_EQ(seen, std::set<std::thread::id>{caller});
}

TEST(OpenBenchCli, DumpedScoresThroughEvaluateReproduceEveryMethodsMetricsExactly) {
  const test::TestDir temp;
  const std::string dataset = RenderTiny(temp);
  ASSERT_EQ(Hoilcd({"bench", dataset, "-o", temp / "report", "--dump-scores", temp / "scores", "--threads", "2"}), 0);
  const nlohmann::json report = Json(temp / "report/report.json");
  for (const std::string& method : DefaultMethods()) {
    const std::string out = temp / ("evaluated/" + method + "/report.json");
    ASSERT_EQ(Hoilcd({"evaluate", dataset, "--scores", temp / ("scores/" + method + ".csv"), "-o",
                      temp / ("evaluated/" + method)}),
              0)
        << method;
    const nlohmann::json mine = Json(out)["methods"][method];
    const nlohmann::json theirs = report["methods"][method];
    for (const char* key : {"mrr", "recall_at_1", "recall_at_5", "recall_at_10", "pr_auc", "recall_at_100p",
                            "queries_scored", "per_lap"}) {
      EXPECT_EQ(mine[key], theirs[key]) << method << " " << key;
    }
    EXPECT_EQ(Json(out)["other_ground_truth"]["methods"][method]["mrr"],
              report["other_ground_truth"]["methods"][method]["mrr"])
        << method;
  }
}

TEST(OpenBenchCli, DumpedScoresOfEveryMethodAreByteIdenticalAtOneAndTwoThreads) {
  const test::TestDir temp;
  const std::string dataset = RenderTiny(temp);
  for (const char* threads : {"1", "2"}) {
    ASSERT_EQ(Hoilcd({"bench", dataset, "--methods", "all", "-o", temp / (std::string("report") + threads),
                      "--dump-scores", temp / (std::string("scores") + threads), "--threads", threads}),
              0);
  }
  for (const std::string& method : DefaultMethods()) {
    const std::string one = ReadFileBytes(temp / ("scores1/" + method + ".csv"));
    EXPECT_GT(std::count(one.begin(), one.end(), '\n'), 10) << method;
    EXPECT_EQ(one, ReadFileBytes(temp / ("scores2/" + method + ".csv"))) << method;
  }
  const nlohmann::json a = Json(temp / "report1/report.json"), b = Json(temp / "report2/report.json");
  EXPECT_EQ(a["tracking"], b["tracking"]);
}

TEST(OpenBenchCli, TheGateExitsThreeAgainstABetterBaselineAndZeroAgainstItsOwnReport) {
  const test::TestDir temp;
  const std::string dataset = RenderTiny(temp);
  ASSERT_EQ(Hoilcd({"bench", dataset, "--methods", "slcd,thumb", "-o", temp / "report", "--dump-scores",
                    temp / "scores", "--junit", temp / "junit.xml"}),
            0);
  const std::string own = temp / "report/report.json";
  nlohmann::json better = Json(own);
  better["methods"]["thumb"]["mrr"] = better["methods"]["thumb"]["mrr"].get<double>() + 0.05;
  WriteFileAtomic(temp / "better.json", better.dump());

  EXPECT_EQ(Hoilcd({"bench", dataset, "--methods", "slcd,thumb", "-o", temp / "again", "--baseline", own}), 0);
  testing::internal::CaptureStdout();
  const int code = Hoilcd({"bench", dataset, "--methods", "slcd,thumb", "-o", temp / "again", "--baseline",
                           temp / "better.json", "--max-drop", "0.01", "--junit", temp / "junit.xml"});
  const std::string out = testing::internal::GetCapturedStdout();
  EXPECT_EQ(code, 3);
  EXPECT_NE(out.find("regression: method thumb, mrr old "), std::string::npos) << out;
  EXPECT_EQ(out.find("method slcd"), std::string::npos) << out;
  const std::string junit = ReadFileBytes(temp / "junit.xml");
  EXPECT_NE(junit.find("tests=\"2\" failures=\"1\""), std::string::npos) << junit;

  // evaluate: the same gate on one method's scores.
  EXPECT_EQ(Hoilcd({"evaluate", dataset, "--scores", temp / "scores/thumb.csv", "--baseline", own}), 0);
  EXPECT_EQ(Hoilcd({"evaluate", dataset, "--scores", temp / "scores/thumb.csv", "--baseline", temp / "better.json",
                    "--max-drop", "0.01"}),
            3);
  EXPECT_EQ(Hoilcd({"evaluate", dataset, "--scores", temp / "scores/thumb.csv", "--baseline", temp / "better.json",
                    "--max-drop", "0.1"}),
            0);

  // --max-drop ci: the run's own interval decides. Its own report passes; a baseline far above the
  // interval does not, and the line names the interval.
  const double high = Json(own)["methods"]["thumb"]["intervals"]["mrr"][1].get<double>();
  nlohmann::json above = Json(own);
  above["methods"]["thumb"]["mrr"] = high + 0.01;
  WriteFileAtomic(temp / "above.json", above.dump());
  EXPECT_EQ(Hoilcd({"evaluate", dataset, "--scores", temp / "scores/thumb.csv", "--baseline", own, "--max-drop", "ci"}),
            0);
  testing::internal::CaptureStdout();
  EXPECT_EQ(Hoilcd({"evaluate", dataset, "--scores", temp / "scores/thumb.csv", "--baseline", temp / "above.json",
                    "--max-drop", "ci"}),
            3);
  const std::string ci_out = testing::internal::GetCapturedStdout();
  EXPECT_NE(ci_out.find("(old above the new run's 95 % interval ["), std::string::npos) << ci_out;
}

TEST(OpenBenchCli, TheOverlapGroundTruthLabelsTheRunAndTheReportComparesTheThreeLabellings) {
  const test::TestDir temp;
  const std::string dataset = RenderTiny(temp);
  ASSERT_EQ(Hoilcd({"bench", dataset, "--methods", "thumb", "--ground-truth", "overlap", "--overlap-threshold", "0.6",
                    "-o", temp / "report"}),
            0);
  const nlohmann::json report = Json(temp / "report/report.json");
  EXPECT_EQ(report["protocol"]["ground_truth"], "overlap");
  EXPECT_EQ(report["protocol"]["overlap_threshold"], 0.6);
  EXPECT_EQ(report["other_ground_truth"]["ground_truth"], "odometry");
  ASSERT_EQ(report["label_agreement"].size(), 3u);
  EXPECT_EQ(report["label_agreement"][2]["a"], "overlap");
  EXPECT_EQ(report["label_agreement"][2]["b"], "true");
  EXPECT_GT(report["label_agreement"][2]["pairs_true_in_a"].get<int64_t>(), 0);
  const std::string md = ReadFileBytes(temp / "report/report.md");
  EXPECT_NE(md.find("at least 60 % of the query's static pixels"), std::string::npos) << md.substr(0, 600);
  EXPECT_NE(md.find("### How the ground truths agree"), std::string::npos);
  EXPECT_NE(md.find("| overlap vs odometry | "), std::string::npos);
}

TEST(OpenBenchCli, EvaluateNamesTheBadScoresFileAndLineAndABadBaselineFailsBeforeAnyWork) {
  const test::TestDir temp;
  const std::string dataset = RenderTiny(temp);
  WriteFileAtomic(temp / "bad.csv", "query,reference,score\n0,1,0.5\n0,99999,1\n");
  testing::internal::CaptureStderr();
  EXPECT_EQ(Hoilcd({"evaluate", dataset, "--scores", temp / "bad.csv"}), 1);
  std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find(temp / "bad.csv" + ":3: reference '99999': expected a frame index in 0.."), std::string::npos)
      << err;

  WriteFileAtomic(temp / "baseline.json", "[]");
  testing::internal::CaptureStderr();
  EXPECT_EQ(Hoilcd({"bench", dataset, "--methods", "thumb", "-o", temp / "r", "--baseline", temp / "baseline.json"}),
            1);
  err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("baseline.json: /methods: expected an object of methods"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(temp / "r"));

  testing::internal::CaptureStderr();
  EXPECT_NE(Hoilcd({"evaluate", dataset, "--scores", temp / "bad.csv", "--max-drop", "0.1"}), 0) << "a usage error";
  err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("--max-drop requires --baseline"), std::string::npos) << err;
}

TEST(OpenBenchCli, AScoresPathOrNameThatIsNotUtf8IsWrittenEscapedIntoTheReport) {
  const test::TestDir temp;
  const std::string dataset = RenderTiny(temp);
  ASSERT_EQ(Hoilcd({"bench", dataset, "--methods", "thumb", "-o", temp / "report", "--dump-scores", temp / "scores"}),
            0);
  const std::string latin1 = temp / "caf\xe9.csv";  // "café.csv" in Latin-1: not UTF-8
  WriteFileAtomic(latin1, ReadFileBytes(temp / "scores/thumb.csv"));
  testing::internal::CaptureStdout();
  ASSERT_EQ(Hoilcd({"evaluate", dataset, "--scores", latin1, "-o", temp / "by_path"}), 0);
  EXPECT_NE(testing::internal::GetCapturedStdout().find("caf\\xe9 (odometry ground truth): MRR "), std::string::npos);
  const nlohmann::json by_path = Json(temp / "by_path/report.json");
  ASSERT_TRUE(by_path["methods"].contains("caf\\xe9"));
  EXPECT_EQ(by_path["methods"]["caf\\xe9"]["description"], "scores from " + temp / "caf\\xe9.csv");
  EXPECT_EQ(by_path["methods"]["caf\\xe9"]["mrr"], Json(temp / "report/report.json")["methods"]["thumb"]["mrr"]);
  EXPECT_NE(ReadFileBytes(temp / "by_path/report.md").find("| caf\\xe9 | "), std::string::npos);

  testing::internal::CaptureStdout();
  ASSERT_EQ(Hoilcd({"evaluate", dataset, "--scores", temp / "scores/thumb.csv", "--name", "caf\xe9\x1b[2J", "-o",
                    temp / "by_name"}),
            0);
  testing::internal::GetCapturedStdout();
  EXPECT_TRUE(Json(temp / "by_name/report.json")["methods"].contains("caf\\xe9\\x1b[2J"));
}

TEST(OpenBenchCli, EvaluateRefusesAFifoOrADeviceAsScoresWithoutBlocking) {
  const test::TestDir temp;
  const std::string dataset = RenderTiny(temp);
  const std::string fifo = temp / "scores.csv";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& scores : {fifo, std::string("/dev/zero")}) {
    testing::internal::CaptureStderr();
    EXPECT_EQ(Hoilcd({"evaluate", dataset, "--scores", scores}), 1);
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find("error: " + scores + ": is a "), std::string::npos) << err;
    EXPECT_NE(err.find(": expected a regular file"), std::string::npos) << err;
  }
}

TEST(OpenBenchCli, EvaluateRefusesScoresFilesWithoutAScore) {
  const test::TestDir temp;
  const std::string dataset = RenderTiny(temp);
  WriteFileAtomic(temp / "header_only.csv", "query,reference,score\n");
  testing::internal::CaptureStderr();
  EXPECT_EQ(Hoilcd({"evaluate", dataset, "--scores", temp / "header_only.csv", "-o", temp / "r"}), 1);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("error: " + temp / "header_only.csv" + ": holds the header and no pair"), std::string::npos)
      << err;
  EXPECT_FALSE(std::filesystem::exists(temp / "r"));
}

TEST(OpenBenchCli, EvaluateOfADatasetWithoutATrueMatchFailsSayingWhyBeforeReadingTheScores) {
  const test::TestDir temp;
  const std::string dataset = test::RenderTinyRoom(temp / "short", {"frames=150"});
  for (const char* protocol : {"laps", "revisit"}) {
    testing::internal::CaptureStderr();
    EXPECT_EQ(Hoilcd({"evaluate", dataset, "--scores", temp / "never_written.csv", "--protocol", protocol}), 1);
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find("error: " + dataset + ": no query has a true match, so MRR, Recall@K and PR are undefined: "),
              std::string::npos)
        << err;
    EXPECT_EQ(err.find("never_written.csv"), std::string::npos) << err;
  }
}

TEST(OpenBenchCli, TheRunsProtocolOnADatasetOfOneRecordingRunIsAnErrorNamingItBeforeAnyWork) {
  const test::TestDir temp;
  const std::string dataset = test::RenderTinyRoom(temp / "short", {"frames=12"});
  for (const std::vector<std::string>& command :
       {std::vector<std::string>{"bench", dataset, "-o", temp / "report"},
        std::vector<std::string>{"bench", dataset, "--online", "-o", temp / "report"},
        std::vector<std::string>{"evaluate", dataset, "--scores", temp / "never_written.csv", "-o", temp / "report"},
        std::vector<std::string>{"inspect", dataset, "-o", temp / "report"}}) {
    std::vector<std::string> args = command;
    args.insert(args.end(), {"--protocol", "runs"});
    testing::internal::CaptureStderr();
    EXPECT_EQ(Hoilcd(args), 1) << command[0];
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(err, "error: " + dataset +
                       ": holds one recording run; --protocol runs needs two or more (render a "
                       "scene with /runs)\n")
        << command[0];
    EXPECT_FALSE(std::filesystem::exists(temp / "report")) << command[0];
  }
}

TEST(OpenBenchCli, BenchOfADatasetWithoutATrueMatchWarnsWhyMrrIsUndefined) {
  const test::TestDir temp;
  const std::string dataset = test::RenderTinyRoom(temp / "short", {"frames=150"});
  testing::internal::CaptureStderr();
  testing::internal::CaptureStdout();
  EXPECT_EQ(Hoilcd({"bench", dataset, "--methods", "thumb", "-o", temp / "report"}), 0);
  testing::internal::GetCapturedStdout();
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("warning: no query has a true match, so MRR, Recall@K and PR are undefined: the laps protocol "
                     "queries the laps after the first, and the 150 frames never complete a first lap"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("('-' in the table)"), std::string::npos) << err;
}

// The bench checks each file against manifest.json as it reads it: a changed thermal frame stops
// it with the file's name and writes no report; an EXR it never reads is never read.
TEST(OpenBenchCli, BenchRefusesAChangedFrameItReadsAndIgnoresAChangedFileItDoesNotRead) {
  const test::TestDir temp;
  const std::string dataset = RenderTiny(temp);
  const auto flip_a_byte = [](const std::string& path) {
    std::string bytes = ReadFileBytes(path);
    bytes[bytes.size() / 2] ^= 0x01;
    WriteFileAtomic(path, bytes);
  };
  flip_a_byte(dataset + "/exr/000003.exr");
  EXPECT_EQ(Hoilcd({"bench", dataset, "--methods", "slcd,thumb", "-o", temp / "r1"}), 0);
  flip_a_byte(dataset + "/thermal/000002.png");
  testing::internal::CaptureStderr();
  EXPECT_EQ(Hoilcd({"bench", dataset, "--methods", "slcd,thumb", "-o", temp / "r2", "--threads", "2"}), 1);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("error: " + dataset + "/thermal/000002.png: checksum mismatch"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(temp / "r2"));
}

// The names under a folder (sorted; folders with a trailing '/'), to see what a command wrote.
std::vector<std::string> Listing(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    names.push_back(e.path().filename().string() + (e.is_directory() ? "/" : ""));
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST(OpenBenchCli, EvaluateOutputIsAReportFolderWithTheBenchsReportJsonAndQueriesCsv) {
  const test::TestDir temp;
  const std::string dataset = RenderTiny(temp);
  ASSERT_EQ(
      Hoilcd({"bench", dataset, "--methods", "slcd,thumb", "-o", temp / "report", "--dump-scores", temp / "scores"}),
      0);
  ASSERT_EQ(Hoilcd({"evaluate", dataset, "--scores", temp / "scores/thumb.csv", "-o", temp / "new/thumb"}), 0);
  EXPECT_EQ(Listing(temp / "new/thumb"), (std::vector<std::string>{"mrr_per_lap.png", "pr_curves.png", "queries.csv",
                                                                   "report.html", "report.json", "report.md"}));
  const nlohmann::json report = Json(temp / "new/thumb/report.json");
  EXPECT_EQ(report["methods"]["thumb"]["mrr"], Json(temp / "report/report.json")["methods"]["thumb"]["mrr"]);
  EXPECT_EQ(report["methods"]["thumb"]["description"], "scores from " + temp / "scores/thumb.csv");
  // queries.csv: the bench's rows of that method, as the bench wrote them.
  const std::string bench_csv = ReadFileBytes(temp / "report/queries.csv");
  std::istringstream lines(bench_csv);
  std::string line, thumb_rows;
  std::getline(lines, line);
  thumb_rows = line + "\n";
  while (std::getline(lines, line))
    if (line.rfind("thumb,", 0) == 0) thumb_rows += line + "\n";
  EXPECT_GT(std::count(thumb_rows.begin(), thumb_rows.end(), '\n'), 10);
  EXPECT_EQ(ReadFileBytes(temp / "new/thumb/queries.csv"), thumb_rows);
  const std::string md = ReadFileBytes(temp / "new/thumb/report.md");
  EXPECT_NE(md.find("| thumb | "), std::string::npos) << md;
  EXPECT_NE(md.find("![pr_curves.png](pr_curves.png)"), std::string::npos) << md;

  // Its own earlier report folder is written again; so is a bench's (both have report.json).
  EXPECT_EQ(Hoilcd({"evaluate", dataset, "--scores", temp / "scores/slcd.csv", "-o", temp / "new/thumb"}), 0);
  EXPECT_TRUE(Json(temp / "new/thumb/report.json")["methods"].contains("slcd"));
  EXPECT_EQ(Hoilcd({"evaluate", dataset, "--scores", temp / "scores/thumb.csv", "-o", temp / "report"}), 0);
}

TEST(OpenBenchCli, EvaluateAndInspectRefuseAFolderOfTheUsersNamingWhatItHoldsAndWriteNothing) {
  const test::TestDir temp;
  const std::string dataset = RenderTiny(temp);
  ASSERT_EQ(Hoilcd({"bench", dataset, "--methods", "thumb", "-o", temp / "report", "--dump-scores", temp / "scores"}),
            0);
  const std::string mine = temp / "mine";
  WriteFileAtomic(mine + "/notes.txt", "my own notes");
  for (const std::vector<std::string>& command :
       {std::vector<std::string>{"evaluate", dataset, "--scores", temp / "scores/thumb.csv", "-o", mine},
        std::vector<std::string>{"inspect", dataset, "-o", mine},
        std::vector<std::string>{"bench", dataset, "--methods", "thumb", "-o", mine}}) {
    testing::internal::CaptureStderr();
    EXPECT_EQ(Hoilcd(command), 1) << command[0];
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find("error: " + mine + ": exists, is not empty (it holds notes.txt) and holds no earlier hoilcd "),
              std::string::npos)
        << err;
    EXPECT_NE(err.find("refusing to overwrite files in it"), std::string::npos) << err;
    EXPECT_EQ(Listing(mine), std::vector<std::string>{"notes.txt"}) << command[0];
    EXPECT_EQ(ReadFileBytes(mine + "/notes.txt"), "my own notes");
  }
  // inspect writes beside nothing but an earlier inspect.json: a report folder is not its own.
  testing::internal::CaptureStderr();
  EXPECT_EQ(Hoilcd({"inspect", dataset, "-o", temp / "report"}), 1);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("holds no earlier hoilcd inspect output (inspect.json)"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(temp / "report/inspect.json"));
  // A file where the folder should be.
  testing::internal::CaptureStderr();
  EXPECT_EQ(Hoilcd({"evaluate", dataset, "--scores", temp / "scores/thumb.csv", "-o", mine + "/notes.txt"}), 1);
  EXPECT_NE(testing::internal::GetCapturedStderr().find(mine + "/notes.txt: is a file: expected a folder"),
            std::string::npos);
}

TEST(OpenBenchCli, InspectOutputIsAFolderHoldingInspectJsonAsPrintedByJson) {
  const test::TestDir temp;
  const std::string dataset = RenderTiny(temp);
  testing::internal::CaptureStdout();
  const int code = Hoilcd({"inspect", dataset, "--json", "-o", temp / "checks"});
  const std::string printed = testing::internal::GetCapturedStdout();
  ASSERT_EQ(code, 0);
  EXPECT_EQ(Listing(temp / "checks"), std::vector<std::string>{"inspect.json"});
  EXPECT_EQ(ReadFileBytes(temp / "checks/inspect.json"), printed);
  EXPECT_TRUE(Json(temp / "checks/inspect.json").contains("labels"));
  // Its own earlier folder is written again.
  testing::internal::CaptureStdout();
  EXPECT_EQ(Hoilcd({"inspect", dataset, "-o", temp / "checks", "--radius", "0.5"}), 0);
  testing::internal::GetCapturedStdout();
  EXPECT_NE(ReadFileBytes(temp / "checks/inspect.json"), printed);
}

// The protocol flags' help shows the defaults ProtocolOptions() holds, not copies of them.
TEST(OpenBenchCli, TheProtocolFlagsHelpShowsTheDefaultsOfProtocolOptions) {
  const ProtocolOptions defaults = ProtocolOptions();
  const auto text = [](double value) {
    std::ostringstream out;
    out << value;
    return out.str();
  };
  const std::vector<std::pair<std::string, std::string>> flags = {
      {"--protocol", defaults.protocol},
      {"--radius", text(defaults.radius_m)},
      {"--exclusion-window", text(defaults.exclusion_window_s)},
      {"--ground-truth", defaults.ground_truth},
      {"--heading-tolerance", text(defaults.heading_tolerance_deg)}};
  for (const char* command : {"bench", "run", "evaluate", "inspect"}) {
    testing::internal::CaptureStdout();
    EXPECT_EQ(Hoilcd({command, "--help"}), 0);
    std::istringstream help(testing::internal::GetCapturedStdout());
    std::map<std::string, std::string> usage;  // flag -> its line
    for (std::string line; std::getline(help, line);) {
      const size_t at = line.find("--");
      if (at == std::string::npos || line.find_first_not_of(' ') != at) continue;  // a long flag's first line
      usage[line.substr(at, line.find(' ', at) - at)] = line;
    }
    for (const auto& [flag, value] : flags) {
      if (std::string(command) == "inspect" && flag != "--protocol" && flag != "--radius") continue;
      ASSERT_EQ(usage.count(flag), 1u) << command << " " << flag;
      const std::string& line = usage[flag];
      const size_t at = line.find("=" + value);
      ASSERT_NE(at, std::string::npos) << command << ": " << line;
      const size_t end = at + 1 + value.size();
      EXPECT_TRUE(end == line.size() || line[end] == ' ') << command << ": " << line;
    }
  }
}

}  // namespace
}  // namespace hoilcd
