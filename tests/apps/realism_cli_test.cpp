// End to end through the command line: hoilcd realism on a tiny rendered dataset against real-frame
// folders the test writes itself (the dataset's own frames as 16-bit centikelvin PNGs, as a float
// TIFF in kelvin, and as 8-bit PNG and JPEG), the report folder's files, its guard and its errors.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/file_io.h"
#include "run_cli.h"
#include "test_dir.h"
#include "tiny_room.h"

namespace hoilcd {
namespace {

using test::RunCli;

class RealismCli : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TestDir("realism_dataset");
    test::RenderTinyRoom(*dir_ / "dataset", {"frames=24"});
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string Dataset() { return *dir_ / "dataset"; }
  static test::TestDir* dir_;
};
test::TestDir* RealismCli::dir_ = nullptr;

nlohmann::json ReadJson(const std::string& path) { return nlohmann::json::parse(ReadFileBytes(path)); }

const nlohmann::json& Statistic(const nlohmann::json& report, const std::string& key) {
  for (const nlohmann::json& s : report["statistics"]) {
    if (s["key"] == key) return s;
  }
  ADD_FAILURE() << "no statistic " << key;
  return report;
}

TEST_F(RealismCli, TheDatasetsOwnFramesAsRealFramesAreAtDistanceZero) {
  const test::TestDir temp;
  const hoilcd::Dataset dataset = hoilcd::Dataset::Open(Dataset());
  std::filesystem::create_directories(temp / "real");
  for (int f = 0; f < dataset.num_frames(); f += 2) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%02d.png", f);
    ASSERT_TRUE(cv::imwrite(temp / ("real/" + std::string(name)), dataset.RadiometricCentikelvin(f)));
  }
  std::ofstream(temp / "real/SOURCES.txt") << "rendered by the test";
  const test::CliOutcome r = RunCli({"realism", Dataset(), temp / "real", "-o", temp / "out", "--stride", "2",
                                     "--scale", "0.01", "--offset", "-273.15"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("report: " + temp / "out" + "/realism.md"), std::string::npos) << r.out;
  const nlohmann::json j = ReadJson(temp / "out/realism.json");
  EXPECT_EQ(j["synthetic"]["frames"], 12);
  EXPECT_EQ(j["real"]["frames"], 12);
  EXPECT_EQ(j["real"]["radiometric"], 12);
  EXPECT_EQ(j["real"]["skipped"], nlohmann::json::array({"SOURCES.txt"}));
  for (const char* key :
       {"shi_tomasi_corners", "slcd_corners", "fast_corners", "strong_edge_fraction", "entropy_bits", "spectrum_slope",
        "temperature_p50_c", "temperature_spread_k", "wall_residual_k", "flat_noise_k", "flat_noise_lag1"}) {
    const nlohmann::json& s = Statistic(j, key)["all_views"];
    EXPECT_NEAR(s["wasserstein1"].get<double>(), 0.0, 1e-9) << key;
    if (!s["median_ratio"].is_null()) {
      EXPECT_NEAR(s["median_ratio"].get<double>(), 1.0, 1e-9) << key;
    }
    EXPECT_EQ(s["real"]["count"], s["synthetic"]["count"]) << key;
  }
  // One camera on each side: one frame-size group each, the same figures.
  ASSERT_EQ(j["by_frame_size"]["real"].size(), 1u);
  EXPECT_EQ(j["by_frame_size"]["real"], j["by_frame_size"]["synthetic"]);
  EXPECT_EQ(j["by_frame_size"]["real"][0]["width_px"], dataset.RadiometricC(0).cols);
  EXPECT_TRUE(std::filesystem::exists(temp / "out/realism.md"));
  for (const char* key : {"shi_tomasi_corners", "spectrum_slope", "wall_residual_k", "temporal_noise_k"}) {
    const cv::Mat png = cv::imread(temp / ("out/histograms/" + std::string(key) + ".png"));
    EXPECT_FALSE(png.empty()) << key;
  }
  // Run again into its own earlier output: allowed.
  EXPECT_EQ(RunCli({"realism", Dataset(), temp / "real", "-o", temp / "out", "--stride", "2", "--scale", "0.01",
                    "--offset", "-273.15"})
                .exit_code,
            0);
}

TEST_F(RealismCli, EightBitFramesSkipTemperatureStatisticsBesideAKelvinTiff) {
  const test::TestDir temp;
  const hoilcd::Dataset dataset = hoilcd::Dataset::Open(Dataset());
  std::filesystem::create_directories(temp / "real");
  ASSERT_TRUE(cv::imwrite(temp / "real/a.png", dataset.Thermal(0)));
  ASSERT_TRUE(cv::imwrite(temp / "real/b.jpg", dataset.Thermal(5)));
  cv::Mat kelvin;
  dataset.RadiometricC(10).convertTo(kelvin, CV_32F, 1.0, 273.15);
  ASSERT_TRUE(cv::imwrite(temp / "real/c.tiff", kelvin));  // float TIFF, read as kelvin by its median
  const test::CliOutcome r = RunCli({"realism", Dataset(), temp / "real", "-o", temp / "out", "--stride", "6"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("2 real frames are 8-bit: no temperature statistics for those"), std::string::npos) << r.out;
  const nlohmann::json j = ReadJson(temp / "out/realism.json");
  EXPECT_EQ(j["real"]["radiometric"], 1);
  EXPECT_EQ(Statistic(j, "temperature_spread_k")["all_views"]["real"]["count"], 1);
  EXPECT_EQ(Statistic(j, "shi_tomasi_corners")["all_views"]["real"]["count"], 3);
  const nlohmann::json& c = j["real"]["per_frame"][2];
  EXPECT_EQ(c["frame"], "c.tiff");
  EXPECT_NEAR(c["temperature_p50_c"].get<double>(), j["synthetic"]["per_frame"][0]["temperature_p50_c"].get<double>(),
              10.0);
  EXPECT_NE(ReadFileBytes(temp / "out/realism.md").find("2 8-bit: no temperature statistics for those"),
            std::string::npos);
}

TEST_F(RealismCli, BadInputIsRefusedNamingWhatWasExpected) {
  const test::TestDir temp;
  std::filesystem::create_directories(temp / "empty");
  std::filesystem::create_directories(temp / "counts");
  const hoilcd::Dataset dataset = hoilcd::Dataset::Open(Dataset());
  ASSERT_TRUE(cv::imwrite(temp / "counts/f.png", dataset.RadiometricCentikelvin(0)));
  const auto err = [&](std::vector<std::string> args) {
    const test::CliOutcome r = RunCli(std::move(args));
    EXPECT_NE(r.exit_code, 0);
    return r.err;
  };
  EXPECT_NE(err({"realism", Dataset(), temp / "missing", "-o", temp / "o1"}).find("no such folder"), std::string::npos);
  EXPECT_NE(err({"realism", Dataset(), temp / "empty", "-o", temp / "o2"}).find("holds no frame"), std::string::npos);
  EXPECT_NE(err({"realism", Dataset(), temp / "counts", "-o", temp / "o3"}).find(temp / "counts/f.png"),
            std::string::npos);
  EXPECT_NE(err({"realism", Dataset(), temp / "counts", "-o", temp / "o4", "--scale", "-1", "--offset", "0"})
                .find("--scale -1: expected kelvin per count"),
            std::string::npos);
  // -o: a folder holding something else is refused before any work.
  std::filesystem::create_directories(temp / "busy");
  std::ofstream(temp / "busy/notes.txt") << "mine";
  const std::string busy =
      err({"realism", Dataset(), temp / "counts", "-o", temp / "busy", "--scale", "0.01", "--offset", "-273.15"});
  EXPECT_NE(busy.find("notes.txt"), std::string::npos) << busy;
  EXPECT_FALSE(std::filesystem::exists(temp / "busy/realism.json"));
}

TEST_F(RealismCli, InspectGivesTheSyntheticSideOfTheFrameStatistics) {
  const test::CliOutcome r = RunCli({"inspect", Dataset(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("frame_statistics")) << r.out;
  const nlohmann::json& s = j["frame_statistics"];
  EXPECT_EQ(s["frames"], 24);
  for (const char* key : {"shi_tomasi_corners_median", "shi_tomasi_corners_median_not_blank", "spectrum_slope_median",
                          "strong_edge_fraction_median", "wall_residual_k_median", "flat_noise_k_median",
                          "flat_noise_lag1_median", "blank_views_pct", "static_pairs"}) {
    EXPECT_TRUE(s.contains(key)) << key;
  }
  EXPECT_GT(s["shi_tomasi_corners_median"].get<double>(), 0);
}

}  // namespace
}  // namespace hoilcd
