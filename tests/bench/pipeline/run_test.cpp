#include "hoilcd/bench/pipeline/run.h"

#include <cmath>
#include <filesystem>
#include <map>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/sim/output/sequence.h"
#include "input_error_of.h"
#include "option_properties.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

// Rewrites the hoilcd_version of a dataset's manifest, as an older build would have written it.
void MarkRenderedBy(const std::string& dataset_dir, const std::string& version) {
  const std::string path = dataset_dir + "/manifest.json";
  DatasetManifest manifest = DatasetManifest::FromJson(ReadFileBytes(path), path);
  manifest.hoilcd_version = version;
  WriteFileAtomic(path, manifest.ToJson());
}

// The tiny room at 64 x 48 px: half the CPU time of its 128 x 96, and its SLAM calibration
// sequence (seed 1001) still gives slcd, dlcd and thumb a finite threshold of 100 % precision.
Scene TinyRoom() {
  return LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/tiny_room.json",
                   {"camera.width_px=64", "camera.height_px=48"});
}

BenchOptions SlcdOnly() {
  BenchOptions bench;
  bench.methods = {"slcd"};
  return bench;
}

// A run that caches its datasets in `cache_dir`, on two threads.
RunOptions CachedIn(const std::string& cache_dir) {
  RunOptions options;
  options.cache_dir = cache_dir;
  options.threads = 2;
  return options;
}

TEST(RunOptions, HoldTheirTablesDefaultsAndEveryBoundIsChecked) {
  const RunOptions options;
  EXPECT_EQ(options.cache_dir, "runs");
  EXPECT_EQ(options.calibration_seed_offset, 1000u);
  EXPECT_EQ(options.cancel, nullptr);
  ExpectConstructedHoldsTheTableDefaults<RunOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<RunOptions>(), 1);
}

TEST(RunScene, ReusesItsCacheButRendersAgainWhenAnotherSimulatorMadeIt) {
  const test::TestDir temp;
  const fs::path cache = temp.path() / "cache";
  const Scene scene = TinyRoom();
  const BenchOptions bench = SlcdOnly();
  const RunOptions options = CachedIn(cache.string());

  const RunOutcome first = RunScene(scene, bench, options);
  EXPECT_FALSE(first.timing.render_cached);
  EXPECT_TRUE(RunScene(scene, bench, options).timing.render_cached);

  MarkRenderedBy(first.dataset_dir, "0.0.1+sim0");
  const RunOutcome stale = RunScene(scene, bench, options);
  EXPECT_FALSE(stale.timing.render_cached);
  EXPECT_EQ(Dataset::Open(stale.dataset_dir).manifest().hoilcd_version, SimulatorVersion());
  EXPECT_TRUE(RunScene(scene, bench, options).timing.render_cached);

  // `hoilcd render` into a folder another simulator wrote refuses, naming both versions.
  MarkRenderedBy(first.dataset_dir, "0.0.1+sim0");
  SequenceOptions render;
  render.output_dir = first.dataset_dir;
  try {
    RenderSequence(scene, render);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rendered by hoilcd 0.0.1+sim0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(SimulatorVersion()), std::string::npos) << e.what();
  }
}

TEST(RunScene, StaleCacheWithAnUnreadableManifestKeepsAndNamesTheUsersFiles) {
  const test::TestDir temp;
  const Scene scene = TinyRoom();
  const BenchOptions bench = SlcdOnly();
  const RunOptions options = CachedIn(temp.str());
  const RunOutcome first = RunScene(scene, bench, options);
  WriteFileAtomic(first.dataset_dir + "/manifest.json", "{ damaged");
  WriteFileAtomic(first.dataset_dir + "/notes.txt", "mine");
  try {
    RunScene(scene, bench, options);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("(notes.txt)"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ReadFileBytes(first.dataset_dir + "/notes.txt"), "mine");
  EXPECT_FALSE(fs::exists(first.dataset_dir + "/thermal/000000.png"));
  // Once the user's file is moved away, the cache renders again.
  fs::remove(first.dataset_dir + "/notes.txt");
  EXPECT_FALSE(RunScene(scene, bench, options).timing.render_cached);
}

// Each method's loop threshold as the SLAM section used it (NaN when none), by method.
std::map<std::string, double> ThresholdsOf(const RunOutcome& outcome) {
  std::map<std::string, double> out;
  for (const MethodSlam& m : outcome.result.slam.methods) out[m.method] = m.threshold;
  return out;
}

void ExpectSameThresholds(const std::map<std::string, double>& a, const std::map<std::string, double>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [name, t] : a) {
    ASSERT_EQ(b.count(name), 1u) << name;
    if (std::isnan(t)) {
      EXPECT_TRUE(std::isnan(b.at(name))) << name;
    } else {
      EXPECT_EQ(t, b.at(name)) << name;
    }
  }
}

TEST(RunScene, TheSlamCalibrationIsCachedDatasetAndThresholdsAndRedoneWhenItsInputsChange) {
  const test::TestDir temp;
  const Scene scene = TinyRoom();
  BenchOptions bench;
  bench.methods = {"slcd", "thumb"};
  bench.slam = true;
  const RunOptions options = CachedIn(temp.str());
  const RunOutcome first = RunScene(scene, bench, options);
  ASSERT_FALSE(first.calibration_dir.empty());
  EXPECT_FALSE(first.timing.calibration_render_cached);
  EXPECT_FALSE(first.timing.calibration_bench_cached);
  EXPECT_GT(first.timing.calibration_s, 0.0);
  for (const MethodSlam& m : first.result.slam.methods) {
    EXPECT_EQ(m.threshold_source, "calibration") << m.method;
    EXPECT_TRUE(std::isfinite(m.threshold)) << m.method;  // so that the comparisons below compare figures
  }

  const RunOutcome second = RunScene(scene, bench, options);
  EXPECT_TRUE(second.timing.calibration_render_cached);
  EXPECT_TRUE(second.timing.calibration_bench_cached);
  ExpectSameThresholds(ThresholdsOf(first), ThresholdsOf(second));

  // A damaged cache file is benched again and rewritten, never trusted or fatal.
  const std::string cache = fs::path(first.calibration_dir).parent_path() / "calibration.json";
  WriteFileAtomic(cache, "{ damaged");
  const RunOutcome repaired = RunScene(scene, bench, options);
  EXPECT_FALSE(repaired.timing.calibration_bench_cached);
  ExpectSameThresholds(ThresholdsOf(first), ThresholdsOf(repaired));
  EXPECT_TRUE(RunScene(scene, bench, options).timing.calibration_bench_cached);

  // Another true-match radius changes what 100 % precision means: benched again, not reused.
  BenchOptions wider = bench;
  wider.protocol.radius_m = 0.3;
  const RunOutcome other = RunScene(scene, wider, options);
  EXPECT_TRUE(other.timing.calibration_render_cached);
  EXPECT_FALSE(other.timing.calibration_bench_cached);

  // So does a method parameter (--param): fewer RANSAC trials score every pair differently.
  RunScene(scene, bench, options);  // the cache holds `bench`'s thresholds again
  BenchOptions fewer_trials = bench;
  fewer_trials.params = {"slcd.ransac_trials=10"};
  EXPECT_FALSE(RunScene(scene, fewer_trials, options).timing.calibration_bench_cached);
}

TEST(RunScene, WithoutKeepingDatasetsTheReportStaysAndTheDatasetsGo) {
  const test::TestDir temp;
  const Scene scene = TinyRoom();
  BenchOptions bench;
  bench.methods = {"slcd", "thumb"};
  bench.slam = true;
  RunOptions dropping = CachedIn((temp.path() / "dropping").string());
  dropping.keep_datasets = false;
  const RunOutcome dropped = RunScene(scene, bench, dropping);
  EXPECT_TRUE(fs::exists(dropped.report_dir + "/report.json"));
  EXPECT_FALSE(fs::exists(dropped.dataset_dir)) << dropped.dataset_dir;
  ASSERT_FALSE(dropped.calibration_dir.empty());
  EXPECT_FALSE(fs::exists(dropped.calibration_dir)) << dropped.calibration_dir;
  // The same figures as a run that keeps them.
  const RunOutcome kept = RunScene(scene, bench, CachedIn((temp.path() / "keeping").string()));
  EXPECT_TRUE(fs::exists(kept.dataset_dir));
  ASSERT_EQ(kept.result.runs.size(), dropped.result.runs.size());
  for (size_t i = 0; i < kept.result.runs.size(); ++i) {
    EXPECT_EQ(kept.result.runs[i].metrics.mrr, dropped.result.runs[i].metrics.mrr) << kept.result.runs[i].name;
  }
}

// slcd, dlcd and thumb with the SLAM section, so with the calibration.
BenchOptions SlcdDlcdThumbWithSlam() {
  BenchOptions bench;
  bench.methods = {"slcd", "dlcd", "thumb"};
  bench.slam = true;
  return bench;
}

TEST(RunScene, TheCalibrationDatasetHoldsOnlyWhatTheThresholdsNeedAndAFullOneServesAsWell) {
  const test::TestDir temp;
  const Scene scene = TinyRoom();
  const BenchOptions bench = SlcdDlcdThumbWithSlam();
  const RunOptions options = CachedIn(temp.str());
  const RunOutcome first = RunScene(scene, bench, options);
  EXPECT_EQ(Dataset::Open(first.calibration_dir).manifest().outputs.ToText(), "thermal,radiometric");
  EXPECT_FALSE(fs::exists(first.calibration_dir + "/exr"));
  EXPECT_FALSE(fs::exists(first.calibration_dir + "/persons.json"));
  EXPECT_FALSE(fs::exists(first.calibration_dir + "/thermal.mp4"));
  EXPECT_EQ(Dataset::Open(first.dataset_dir).manifest().outputs.ToText(), "thermal,radiometric,exr,video,persons");

  // The same calibration sequence rendered with every output (as before this change) is reused
  // as it is, and gives the same thresholds.
  nlohmann::json doc = scene.resolved;
  doc["seed"] = scene.seed + options.calibration_seed_offset;
  const Scene calibration = SceneFromJson(doc, "calibration");
  fs::remove_all(fs::path(first.calibration_dir).parent_path());
  SequenceOptions full;
  full.output_dir = first.calibration_dir;
  RenderSequence(calibration, full);
  const RunOutcome second = RunScene(scene, bench, options);
  EXPECT_TRUE(second.timing.calibration_render_cached);
  EXPECT_FALSE(second.timing.calibration_bench_cached);
  ExpectSameThresholds(ThresholdsOf(first), ThresholdsOf(second));

  // A partial calibration dataset with other outputs is stale: rendered again, not an error.
  fs::remove_all(fs::path(first.calibration_dir).parent_path());
  full.frames = 3;
  RenderSequence(calibration, full);
  DatasetManifest partial = DatasetManifest::FromJson(ReadFileBytes(first.calibration_dir + "/manifest.json"), "m");
  partial.complete = false;
  partial.frame_count = calibration.frames;
  WriteFileAtomic(first.calibration_dir + "/manifest.json", partial.ToJson());
  const RunOutcome third = RunScene(scene, bench, options);
  EXPECT_FALSE(third.timing.calibration_render_cached);
  ExpectSameThresholds(ThresholdsOf(first), ThresholdsOf(third));
  EXPECT_EQ(Dataset::Open(first.calibration_dir).manifest().outputs.ToText(), "thermal,radiometric");
}

// The calibration renders and benches beside the scene's render: both datasets are byte for byte
// those each render writes alone, and the thresholds those of its dataset benched alone.
TEST(RunScene, TheCalibrationBesideTheRenderGivesTheBytesAndThresholdsOfEachAlone) {
  const test::TestDir temp;
  const Scene scene = TinyRoom();
  const BenchOptions bench = SlcdDlcdThumbWithSlam();
  const RunOptions options = CachedIn(temp / "cache");
  const RunOutcome run = RunScene(scene, bench, options);

  SequenceOptions alone;
  alone.output_dir = temp / "alone";
  alone.threads = 2;
  RenderSequence(scene, alone);
  EXPECT_EQ(Dataset::Open(run.dataset_dir).manifest().files, Dataset::Open(alone.output_dir).manifest().files);
  nlohmann::json doc = scene.resolved;
  doc["seed"] = scene.seed + options.calibration_seed_offset;
  alone.output_dir = temp / "calibration_alone";
  alone.outputs = "thermal,radiometric";
  RenderSequence(SceneFromJson(doc, "calibration"), alone);
  EXPECT_EQ(Dataset::Open(run.calibration_dir).manifest().files, Dataset::Open(alone.output_dir).manifest().files);

  // Its thresholds benched again from the cached dataset, with no render beside them.
  fs::remove(fs::path(run.calibration_dir).parent_path() / "calibration.json");
  const RunOutcome again = RunScene(scene, bench, options);
  EXPECT_TRUE(again.timing.render_cached);
  EXPECT_FALSE(again.timing.calibration_bench_cached);
  ExpectSameThresholds(ThresholdsOf(run), ThresholdsOf(again));
}

// A failing render does not wait for the calibration beside it: its render stops after its
// current frame, and the error comes out at once.
TEST(RunScene, AFailingRenderStopsTheCalibrationBesideIt) {
  const test::TestDir temp;
  const Scene scene = TinyRoom();
  const RunOptions options = CachedIn(temp / "cache");
  // A stale dataset beside a file hoilcd did not write: an InputError before any frame.
  const std::string dataset_dir = RunFolder(scene, options.cache_dir) + "/dataset";
  WriteFileAtomic(dataset_dir + "/manifest.json", "{ not a manifest");
  WriteFileAtomic(dataset_dir + "/notes.txt", "mine");
  EXPECT_THROW(RunScene(scene, SlcdDlcdThumbWithSlam(), options), InputError);
  nlohmann::json doc = scene.resolved;
  doc["seed"] = scene.seed + options.calibration_seed_offset;
  const std::string calibration_manifest =
      RunFolder(SceneFromJson(doc, "calibration"), options.cache_dir) + "/dataset/manifest.json";
  if (fs::exists(calibration_manifest)) {  // stopped part-way: a resume point at most
    EXPECT_FALSE(DatasetManifest::FromJson(ReadFileBytes(calibration_manifest), "manifest.json").complete);
  }
  EXPECT_EQ(ReadFileBytes(dataset_dir + "/notes.txt"), "mine");
}

// With calibration_seed_offset 0 the calibration sequence is the scene itself: it is benched
// after the render, from the same dataset, not rendered beside it into the same folder.
TEST(RunScene, ACalibrationOfTheSceneItselfIsBenchedAfterItsRender) {
  const test::TestDir temp;
  RunOptions options = CachedIn(temp / "cache");
  options.calibration_seed_offset = 0;
  const RunOutcome run = RunScene(TinyRoom(), SlcdDlcdThumbWithSlam(), options);
  EXPECT_EQ(run.calibration_dir, run.dataset_dir);
  EXPECT_TRUE(run.timing.calibration_render_cached);
  EXPECT_FALSE(run.timing.calibration_bench_cached);
  for (const MethodSlam& m : run.result.slam.methods) EXPECT_EQ(m.threshold_source, "calibration") << m.method;
}

// The runs protocol on a scene of one run is refused before anything is rendered.
TEST(RunScene, TheRunsProtocolOnASceneOfOneRunIsRefusedBeforeTheRender) {
  const test::TestDir cache;
  BenchOptions bench = SlcdOnly();
  bench.protocol.protocol = "runs";
  const Scene scene = TinyRoom();
  const std::string message = test::InputErrorOf([&] { RunScene(scene, bench, CachedIn(cache.str())); });
  EXPECT_NE(message.find(scene.file + ": has one recording run; --protocol runs needs two or more"), std::string::npos)
      << message;
  EXPECT_TRUE(std::filesystem::is_empty(cache.str()) || !std::filesystem::exists(cache.str()));
}

}  // namespace
}  // namespace hoilcd
