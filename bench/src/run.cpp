#include "hoilcd/bench/run.h"

#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "hoilcd/core/dataset.h"
#include "hoilcd/core/dataset_folder.h"
#include "hoilcd/sim/sequence.h"

namespace hoilcd {

std::string RunOptions::Check() const {
  if (cache_dir.empty()) return "cache_dir must not be empty";
  if (threads < 0) return "threads must be 0 (every core) or positive";
  return "";
}

std::string RunFolder(const Scene& scene, const std::string& cache_dir) {
  const std::string hex = scene.hash.substr(scene.hash.find(':') + 1, 12);
  std::string name = scene.name;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  }
  return cache_dir + "/" + name + "-" + hex;
}

namespace {

// Renders `scene` into dataset_dir unless a complete, intact dataset of this very scene is cached
// there, and returns it opened (checksums verified once). *cached says whether it was cached;
// *render_s gets the rendering time.
Dataset EnsureDataset(const Scene& scene, const std::string& dataset_dir, const RunOptions& options, bool* cached,
                      double* render_s) {
  // Reuse the cached dataset only when it is complete, intact, of this very scene and rendered
  // by this simulator. One rendered by another simulator (or with an unreadable manifest) is
  // stale: its files are deleted by their exact names and it is rendered anew. Anything else in
  // the folder is the user's: it is kept, and named in an error.
  *cached = false;
  std::error_code ec;
  const std::string manifest_path = dataset_dir + "/manifest.json";
  if (std::filesystem::exists(manifest_path, ec)) {
    std::string version;
    try {
      version = DatasetManifest::FromJson(ReadFileBytes(manifest_path), manifest_path).hoilcd_version;
    } catch (const InputError&) {
    }
    if (version != SimulatorVersion()) {
      const std::vector<std::string> left = RemoveDatasetFiles(dataset_dir);
      if (!left.empty()) {
        throw InputError(dataset_dir, "held a stale cached dataset (now deleted) beside files hoilcd did not "
                                      "write (" + JoinFileList(left) + "); move them away and run again");
      }
    } else {
      try {
        Dataset existing = Dataset::Open(dataset_dir, /*verify_checksums=*/true);
        if (existing.manifest().scene_hash == scene.hash && existing.num_frames() == scene.frames) {
          *cached = true;
          return existing;
        }
      } catch (const InputError&) {
        // partial or damaged: RenderSequence resumes or re-renders what is bad
      }
    }
  }
  SequenceOptions render;
  render.output_dir = dataset_dir;
  render.threads = options.threads;
  render.cancel = options.cancel;
  *render_s = RenderSequence(scene, render).seconds;
  return Dataset::Open(dataset_dir, /*verify_checksums=*/true);
}

// Each method's threshold at 100 % precision on the calibration sequence (NaN: none reaches it).
std::map<std::string, double> CalibrateLoopThresholds(const Scene& scene, const BenchOptions& bench,
                                                      const RunOptions& options, RunOutcome* out) {
  const auto start = std::chrono::steady_clock::now();
  nlohmann::json doc = scene.resolved;
  doc["seed"] = scene.seed + options.calibration_seed_offset;
  const Scene calibration = SceneFromJson(doc, scene.file + " (calibration seed)");
  out->calibration_dir = RunFolder(calibration, options.cache_dir) + "/dataset";
  bool cached = false;
  double render_s = 0;
  const Dataset dataset = EnsureDataset(calibration, out->calibration_dir, options, &cached, &render_s);
  BenchOptions b = bench;
  b.slam = false;
  const BenchResult result = RunBench(dataset, b);
  std::map<std::string, double> thresholds;
  for (const MethodRun& run : result.runs) {
    thresholds[run.name] =
        ThresholdAtFullPrecision(result.queries, run.scores, dataset.poses(), bench.protocol.radius_m);
  }
  out->calibration_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return thresholds;
}

}  // namespace

RunOutcome RunScene(const Scene& scene, const BenchOptions& bench, const RunOptions& options) {
  if (const std::string problem = options.Check(); !problem.empty()) throw InputError("run", problem);
  RunOutcome out;
  const std::string folder = RunFolder(scene, options.cache_dir);
  out.dataset_dir = folder + "/dataset";
  out.report_dir = options.report_dir.empty() ? folder + "/report" : options.report_dir;

  const Dataset dataset =
      EnsureDataset(scene, out.dataset_dir, options, &out.timing.render_cached, &out.timing.render_s);
  out.warnings = dataset.warnings();
  BenchOptions b = bench;
  b.threads = options.threads;
  if (b.slam && std::isnan(b.slam_options.slam.loop_threshold)) {
    b.slam_options.calibrated_threshold = CalibrateLoopThresholds(scene, b, options, &out);
  }
  out.result = RunBench(dataset, b);
  out.timing.bench_s = out.result.seconds;
  WriteReport(out.result, dataset, b, out.timing, out.report_dir);
  return out;
}

}  // namespace hoilcd
