#include "hoilcd/bench/pipeline/run.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <future>
#include <map>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/dataset/dataset_folder.h"
#include "hoilcd/core/util/folder_lock.h"
#include "hoilcd/core/util/json_reader.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/progress.h"
#include "hoilcd/sim/output/sequence.h"

namespace hoilcd {

RunOptions::RunOptions() { Table().FillDefaults(this); }

const OptionTable<RunOptions>& RunOptions::Table() {
  using O = RunOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("cache_dir", &O::cache_dir, "runs", {}, "datasets and reports go to CACHE/<scene>-<hash>/")
          .Rule("cache_dir", [](const O& o) { return o.cache_dir.empty() ? "must not be empty" : ""; })
          .Add("report_dir", &O::report_dir, "", {}, "the report folder (empty: CACHE/<scene>-<hash>/report)")
          .Add("threads", &O::threads, 0, "", R::Any().AtLeast(0), "threads (0: every core)")
          .Add("keep_datasets", &O::keep_datasets, true,
               "keep each rendered dataset in the cache; false deletes it (and its SLAM calibration's) once the report "
               "is written, for suites and sweeps too large to keep (~1 GB a thousand frames)")
          .Add("calibration_seed_offset", &O::calibration_seed_offset, uint64_t{1000}, "", R::Any().AtLeast(0),
               "the SLAM calibration run renders the scene with seed + this");
  return table;
}

std::string RunOptions::Check() const { return Table().FirstProblem(*this); }

nlohmann::json BenchSettingsJson(const BenchOptions& options) {
  const std::vector<std::string> methods = options.methods.empty() ? DefaultMethods() : options.methods;
  nlohmann::json settings = ProtocolOptions::Table().ToJson(options.protocol);
  settings["methods"] = methods;
  settings["keypoint_detector"] = options.keypoints.detector;
  settings["params"] = options.params;  // every method's own options are set only by --param
  // What else changes a report: a rerun with other strata or SLAM settings must not keep the old one.
  settings["strata"] = options.strata;
  settings["slam"] = options.slam;
  if (options.slam) {
    const SlamOptions& slam = options.slam_options.slam;
    settings["slam_backend"] = slam.graph.backend;
    settings["loop_threshold"] =
        std::isnan(slam.loop_threshold) ? nlohmann::json() : nlohmann::json(slam.loop_threshold);
  }
  return settings;
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

// What the thresholds need: the methods read the thermal and radiometric frames; the EXRs, the
// video and the people's ground truth (only the tracking metrics read it) would never be looked at.
DatasetOutputs CalibrationOutputs() {
  DatasetOutputs outputs;
  outputs.exr = outputs.video = outputs.persons = false;
  return outputs;
}

// A dataset of the cache, opened, with the shared lock of its folder that keeps it while it is read
// (no --drop-datasets of another process deletes it meanwhile).
struct CachedDataset {
  std::unique_ptr<FolderLock> lock;  // first: let go of after the dataset
  Dataset dataset;
};

// Renders `scene` into dataset_dir with `outputs` unless a complete, intact dataset of this very
// scene with at least those outputs is cached there, and returns it opened (checksums verified
// once). *cached says whether it was cached; *render_s gets the rendering time; the render's
// warnings (SequenceResult) go to *warnings.
CachedDataset EnsureDataset(const Scene& scene, const std::string& dataset_dir, const DatasetOutputs& outputs,
                            const RunOptions& options, bool* cached, double* render_s,
                            std::vector<std::string>* warnings) {
  // Reuse the cached dataset only when it is complete, intact, of this very scene and rendered
  // by this simulator. One rendered by another simulator (or with an unreadable manifest) is
  // stale: its files are deleted by their exact names and it is rendered anew. Anything else in
  // the folder is the user's: it is kept, and named in an error.
  *cached = false;
  // One process at a time decides, renders and checks: a second one (another suite sharing the
  // cache) waits, then finds the dataset cached. Shared while the dataset is read.
  auto lock = std::make_unique<FolderLock>(dataset_dir, FolderLock::IfBusy::kWait);
  std::error_code ec;
  const std::string manifest_path = dataset_dir + "/manifest.json";
  if (std::filesystem::exists(manifest_path, ec)) {
    std::optional<DatasetManifest> old;
    try {
      old = DatasetManifest::FromJson(ReadFileBytes(manifest_path), manifest_path);
    } catch (const InputError&) {
    }
    // A complete dataset serves when it has every output wanted; a partial one resumes only with
    // its own outputs. Otherwise it is stale too.
    bool has_outputs = old.has_value();
    for (const std::string& name : outputs.Names()) has_outputs = has_outputs && old->outputs.Has(name);
    if (!old || old->hoilcd_version != SimulatorVersion() || !has_outputs || old->frame_count != scene.frames ||
        (!old->complete && old->outputs != outputs)) {
      const std::vector<std::string> left = RemoveDatasetFiles(dataset_dir);
      if (!left.empty()) {
        throw InputError(dataset_dir,
                         "held a stale cached dataset (now deleted) beside files hoilcd did not "
                         "write (" +
                             JoinFileList(left) + "); move them away and run again");
      }
    } else {
      try {
        Dataset existing = Dataset::Open(dataset_dir, Verify::kEveryFile, options.threads);
        if (existing.manifest().scene_hash == scene.hash && existing.num_frames() == scene.frames) {
          *cached = true;
          lock->Share();
          return {std::move(lock), std::move(existing)};
        }
      } catch (const InputError&) {
        // partial or damaged: RenderSequence resumes or re-renders what is bad
      }
    }
  }
  SequenceOptions render;
  render.output_dir = dataset_dir;
  render.outputs = outputs.ToText();
  render.threads = options.threads;
  render.cancel = options.cancel;
  const SequenceResult rendered = RenderSequence(scene, render);
  warnings->insert(warnings->end(), rendered.warnings.begin(), rendered.warnings.end());
  *render_s = rendered.seconds;
  // Not verified up front: the render just checksummed every byte it wrote, and every frame it
  // kept from an interrupted run (re-reading ~0.9 GB cost 5-9 s per dataset on 2 cores). What
  // the bench reads is still checked as it is read.
  Dataset dataset = Dataset::Open(dataset_dir, Verify::kOnRead, options.threads);
  lock->Share();
  return {std::move(lock), std::move(dataset)};
}

// What the calibration's thresholds depend on: the calibration dataset (its manifest lists the
// checksum of every file, the scene hash and the simulator revision), the program that benches it
// (the methods' code and every option default: its own bytes, so any rebuild that changes them
// invalidates the cache) and the bench settings a user can set (BenchSettingsJson).
std::string CalibrationKey(const std::string& dataset_dir, const BenchOptions& bench) {
  std::string program;
  try {
    program = ChecksumOfFile("/proc/self/exe");
  } catch (const InputError&) {
    return "";  // the program cannot be identified: never reuse a cached result
  }
  nlohmann::json key = {{"dataset", ChecksumOfFile(dataset_dir + "/manifest.json")},
                        {"program", program},
                        {"version", HOILCD_VERSION},
                        {"bench", BenchSettingsJson(bench)}};
  return ChecksumOf(key.dump());
}

// The thresholds cached under `key` in `path`, or nothing (absent, unreadable, another key).
std::optional<std::map<std::string, double>> ReadCachedThresholds(const std::string& path, const std::string& key) {
  std::error_code ec;
  if (key.empty() || !std::filesystem::exists(path, ec)) return std::nullopt;
  const nlohmann::json doc = ParseJsonOrDiscarded(ReadFileBytes(path));
  if (doc.is_discarded() || !doc.is_object() || doc.value("key", "") != key || !doc.contains("thresholds") ||
      !doc["thresholds"].is_object()) {
    return std::nullopt;
  }
  std::map<std::string, double> thresholds;
  for (const auto& [name, value] : doc["thresholds"].items()) {
    if (value.is_number()) {
      thresholds[name] = value.get<double>();
    } else if (value.is_null()) {
      thresholds[name] = std::nan("");  // no threshold reaches 100 % precision
    } else {
      return std::nullopt;
    }
  }
  return thresholds;
}

// What the SLAM calibration found, and how.
struct Calibration {
  std::map<std::string, double> thresholds;  // method -> threshold at 100 % precision (NaN: none)
  std::string dataset_dir;
  double seconds = 0;
  bool render_cached = false, bench_cached = false;
};

// Each method's threshold at 100 % precision on the calibration sequence (NaN: none reaches it).
// The calibration dataset is cached like any run's, and so are its thresholds (calibration.json
// beside the dataset, under CalibrationKey).
Calibration CalibrateLoopThresholds(const Scene& scene, const BenchOptions& bench, const RunOptions& options) {
  Calibration out;
  const auto start = std::chrono::steady_clock::now();
  nlohmann::json doc = scene.resolved;
  doc["seed"] = scene.seed + options.calibration_seed_offset;
  const Scene calibration = SceneFromJson(doc, scene.file + " (calibration seed)");
  const std::string folder = RunFolder(calibration, options.cache_dir);
  out.dataset_dir = folder + "/dataset";
  const std::string cache_path = folder + "/calibration.json";
  // Thresholds cached for this very manifest (complete, this scene, this simulator) need no
  // dataset: they were benched from the files it lists, so its frames are not even read.
  std::optional<std::map<std::string, double>> thresholds;
  const std::string manifest_path = out.dataset_dir + "/manifest.json";
  std::error_code ec;
  if (std::filesystem::exists(cache_path, ec) && std::filesystem::exists(manifest_path, ec)) {
    try {
      const DatasetManifest m = DatasetManifest::FromJson(ReadFileBytes(manifest_path), manifest_path);
      if (m.complete && m.scene_hash == calibration.hash && m.hoilcd_version == SimulatorVersion() &&
          m.frame_count == calibration.frames) {
        thresholds = ReadCachedThresholds(cache_path, CalibrationKey(out.dataset_dir, bench));
      }
    } catch (const InputError&) {
      // unreadable manifest: EnsureDataset below renders the calibration sequence again
    }
  }
  out.render_cached = out.bench_cached = thresholds.has_value();
  if (!thresholds) {
    double render_s = 0;
    std::vector<std::string> calibration_warnings;  // the test sequence's say the same
    // Only what the thresholds need (CalibrationOutputs): on paper_room the people's ground truth
    // alone would add 28 % to the render's CPU, the EXRs and video far more.
    const CachedDataset cached = EnsureDataset(calibration, out.dataset_dir, CalibrationOutputs(), options,
                                               &out.render_cached, &render_s, &calibration_warnings);
    const Dataset& dataset = cached.dataset;
    const std::string key = CalibrationKey(out.dataset_dir, bench);
    BenchOptions b = bench;
    b.slam = false;
    // The calibration sequence has no ground truth (CalibrationOutputs): the oracles are left
    // out, and their SLAM thresholds come from the test sequence.
    b.optional_methods = b.methods;
    const BenchResult result = RunBench(dataset, b);
    thresholds.emplace();
    nlohmann::json saved = nlohmann::json::object();
    for (const MethodRun& run : result.runs) {
      const double t = ThresholdAtFullPrecision(result.queries, run.scores, dataset.poses(), bench.protocol.radius_m);
      (*thresholds)[run.name] = t;
      saved[run.name] = std::isnan(t) ? nlohmann::json(nullptr) : nlohmann::json(t);
    }
    if (!key.empty()) {
      WriteFileAtomic(cache_path, nlohmann::json{{"key", key}, {"thresholds", saved}}.dump(2) + "\n");
    }
  }
  out.thresholds = std::move(*thresholds);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

// Deletes a cached dataset's files (by their names, as a stale one's) and its folder when that is
// left empty, unless another process holds the folder (rendering or reading it for its own run): a
// dataset that is not removed only costs disk.
void DropDataset(const std::string& dataset_dir) {
  try {
    const FolderLock lock(dataset_dir, FolderLock::IfBusy::kRefuse);
    RemoveDatasetFiles(dataset_dir);
  } catch (const InputError&) {
    return;
  }
  std::error_code ec;
  if (std::filesystem::is_empty(dataset_dir, ec)) std::filesystem::remove(dataset_dir, ec);
}

}  // namespace

RunOutcome RunScene(const Scene& scene, const BenchOptions& bench, const RunOptions& options) {
  if (const std::string problem = options.Check(); !problem.empty()) throw InputError("run", problem);
  if (bench.protocol.protocol == "runs" && scene.runs.size() < 2) {  // refused before the render, not after
    throw InputError(scene.file,
                     "has one recording run; --protocol runs needs two or more (give the scene /runs, "
                     "docs/guide/runs.md)");
  }
  RunOutcome out;
  const std::string folder = RunFolder(scene, options.cache_dir);
  out.dataset_dir = folder + "/dataset";
  out.report_dir = options.report_dir.empty() ? folder + "/report" : options.report_dir;

  BenchOptions b = bench;
  b.threads = options.threads;
  // The SLAM calibration (its own render and bench) runs beside this scene's render and bench:
  // each alone leaves cores idle (serial steps, writer hand-offs, fsyncs, ByteTrack); together
  // they fill them. Its render runs on half the threads (fewer threads contend for the cores:
  // ~0.7 s sooner on paper_room), and only the SLAM step at the end of this scene's bench waits
  // for its thresholds, so a calibration that takes longer (this scene's dataset cached, say)
  // runs beside the bench. Both are deterministic at any thread count, so the bytes are those
  // of one after the other. Its progress lines are titled "calibration ...".
  const bool calibrate = b.slam && std::isnan(b.slam_options.slam.loop_threshold);
  // With offset 0 the calibration sequence is the scene itself, in the same folder: after it.
  const bool beside = options.calibration_seed_offset != 0;
  std::atomic<bool> stop_calibration{false};  // this side failed, or the user interrupted
  RunOptions calibration_options = options;
  if (beside) {
    calibration_options.cancel = &stop_calibration;
    calibration_options.threads = std::max(1, ResolveThreadCount(options.threads) / 2);
  }
  std::future<Calibration> calibration;  // waited for even if the render or bench throws
  if (calibrate) {
    calibration = std::async(beside ? std::launch::async : std::launch::deferred, [&scene, &calibration_options, b] {
      const ProgressReporter::ThreadTitlePrefix prefix("calibration ");
      return CalibrateLoopThresholds(scene, b, calibration_options);
    });
  }
  CachedDataset cached = [&] {
    try {
      return EnsureDataset(scene, out.dataset_dir, DatasetOutputs(), options, &out.timing.render_cached,
                           &out.timing.render_s, &out.warnings);
    } catch (...) {
      stop_calibration = true;  // its render stops after its current frame, so the error is not held back
      throw;
    }
  }();
  const Dataset& dataset = cached.dataset;
  out.warnings.insert(out.warnings.end(), dataset.warnings().begin(), dataset.warnings().end());
  // The SLAM step waits for the calibration; report.json's timing then has its figures.
  const auto take_thresholds = [&](SlamRunOptions* slam) {
    if (!calibration.valid()) return;  // a fixed threshold, or SLAM off
    while (calibration.wait_for(std::chrono::milliseconds(50)) == std::future_status::timeout) {
      if (options.cancel != nullptr && options.cancel->load()) stop_calibration = true;  // Ctrl-C stops it too
    }
    const Calibration c = calibration.get();  // runs it now if deferred; rethrows its error
    slam->calibrated_threshold = c.thresholds;
    out.calibration_dir = c.dataset_dir;
    out.timing.calibration_s = c.seconds;
    out.timing.calibration_render_cached = c.render_cached;
    out.timing.calibration_bench_cached = c.bench_cached;
  };
  try {
    out.result = BenchAndWriteReport(dataset, b, &out.timing, out.report_dir, take_thresholds);
  } catch (...) {
    stop_calibration = true;  // as for a failed render
    throw;
  }
  if (!options.keep_datasets) {
    cached.lock.reset();  // read: another process's reading lock alone keeps it now
    DropDataset(out.dataset_dir);
    if (!out.calibration_dir.empty()) DropDataset(out.calibration_dir);
  }
  return out;
}

namespace fs = std::filesystem;

bool RecordedRun::Kept() const {
  const std::string path = dir + "/" + record_file;
  std::error_code ec;
  if (!fs::exists(path, ec) || !fs::exists(dir + "/report.json", ec)) return false;
  try {
    return ParseJsonOrDiscarded(ReadFileBytes(path)) == record;
  } catch (const std::exception&) {
    return false;  // unreadable: run again
  }
}

void RecordedRun::Run(const Scene& scene, const BenchOptions& bench, RunOptions options) const {
  std::error_code ec;
  fs::remove(dir + "/" + record_file, ec);
  options.report_dir = dir;
  RunScene(scene, bench, options);
  WriteFileAtomic(dir + "/" + record_file, record.dump(2) + "\n");
}

}  // namespace hoilcd
