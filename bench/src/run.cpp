#include "hoilcd/bench/run.h"

#include <cctype>
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

RunOutcome RunScene(const Scene& scene, const BenchOptions& bench, const RunOptions& options) {
  if (const std::string problem = options.Check(); !problem.empty()) throw InputError("run", problem);
  RunOutcome out;
  const std::string folder = RunFolder(scene, options.cache_dir);
  out.dataset_dir = folder + "/dataset";
  out.report_dir = options.report_dir.empty() ? folder + "/report" : options.report_dir;

  // Reuse the cached dataset only when it is complete, intact, of this very scene and rendered
  // by this simulator. One rendered by another simulator (or with an unreadable manifest) is
  // stale: its files are deleted by their exact names and it is rendered anew. Anything else in
  // the folder is the user's: it is kept, and named in an error.
  bool cached = false;
  std::error_code ec;
  const std::string manifest_path = out.dataset_dir + "/manifest.json";
  if (std::filesystem::exists(manifest_path, ec)) {
    std::string version;
    try {
      version = DatasetManifest::FromJson(ReadFileBytes(manifest_path), manifest_path).hoilcd_version;
    } catch (const InputError&) {
    }
    if (version != SimulatorVersion()) {
      const std::vector<std::string> left = RemoveDatasetFiles(out.dataset_dir);
      if (!left.empty()) {
        throw InputError(out.dataset_dir, "held a stale cached dataset (now deleted) beside files hoilcd did not "
                                          "write (" + JoinFileList(left) + "); move them away and run again");
      }
    } else {
      try {
        const Dataset existing = Dataset::Open(out.dataset_dir, /*verify_checksums=*/true);
        cached = existing.manifest().scene_hash == scene.hash && existing.num_frames() == scene.frames;
      } catch (const InputError&) {
        cached = false;  // partial or damaged: RenderSequence resumes or re-renders what is bad
      }
    }
  }
  if (!cached) {
    SequenceOptions render;
    render.output_dir = out.dataset_dir;
    render.threads = options.threads;
    render.cancel = options.cancel;
    out.timing.render_s = RenderSequence(scene, render).seconds;
  }
  out.timing.render_cached = cached;
  const Dataset dataset = Dataset::Open(out.dataset_dir, /*verify_checksums=*/!cached);
  out.warnings = dataset.warnings();
  BenchOptions b = bench;
  b.threads = options.threads;
  out.result = RunBench(dataset, b);
  out.timing.bench_s = out.result.seconds;
  WriteReport(out.result, dataset, b, out.timing, out.report_dir);
  return out;
}

}  // namespace hoilcd
