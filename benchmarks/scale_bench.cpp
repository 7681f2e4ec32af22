// scale_bench: online SLCD against database size. A dataset's frames (rendered here from
// scenes/paper_room.json unless --dataset names one) give SLCD's keypoints and the thumbnails; a
// database of each size is replayed from them (frame i is source frame i mod N, its keypoints moved
// by up to half a pixel and its thumbnail by a little noise, both keyed by i, so no two entries are
// identical), then queries are timed as `hoilcd bench --online` runs them: a FAISS shortlist of K
// (shortlist_index.h), then MNN + RANSAC against those K (retrieval_index.h). Prints one line per
// size: insertion and query p50 / p99 in ms, the index's size and the process's peak memory.
// Not a Google Benchmark: each size is one long measurement, and the peaks are what it reports.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "hoilcd/bench/methods/bench_options.h"
#include "hoilcd/bench/methods/front_ends.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/place_recognition/retrieval_index.h"
#include "hoilcd/core/place_recognition/shortlist_index.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/memory.h"
#include "hoilcd/core/util/random.h"
#include "hoilcd/core/util/stats.h"
#include "hoilcd/sim/assets/data_dir.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/scene/scene.h"

namespace hoilcd {
namespace {

using Clock = std::chrono::steady_clock;

double MsSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

struct Args {
  std::string dataset;  // empty: render paper_room into a temporary folder
  std::vector<int> sizes = {1000, 10000, 100000};
  int queries = 1000;  // timed per size
  ShortlistOptions shortlist;
  int threads = 0;
};

Args Parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw InputError(flag, "expected a value");
      return argv[++i];
    };
    if (flag == "--dataset") {
      a.dataset = value();
    } else if (flag == "--sizes") {
      a.sizes.clear();
      std::string list = value();
      for (size_t p = 0; p <= list.size();) {
        const size_t comma = std::min(list.find(',', p), list.size());
        a.sizes.push_back(std::stoi(list.substr(p, comma - p)));
        p = comma + 1;
      }
    } else if (flag == "--queries") {
      a.queries = std::stoi(value());
    } else if (flag == "--k") {
      a.shortlist.k = std::stoi(value());
    } else if (flag == "--index") {
      a.shortlist.index = value();
    } else if (flag == "--threads") {
      a.threads = std::stoi(value());
    } else {
      throw InputError(flag,
                       "unknown flag (scale_bench [--dataset DIR] [--sizes 1000,10000,100000] "
                       "[--queries N] [--k K] [--index hnsw|flat] [--threads N])");
    }
  }
  if (const std::string problem = a.shortlist.Check(); !problem.empty()) throw InputError("--k/--index", problem);
  for (int s : a.sizes) {
    if (s < 1) throw InputError("--sizes", "sizes must be at least 1");
  }
  if (a.queries < 1) throw InputError("--queries", "must be at least 1");
  return a;
}

// Source frame `source`'s keypoints and thumbnail, replayed as entry `key`.
void Replay(const FrontEndOutput& source_features, int source, uint64_t key, std::vector<Point2>* points,
            std::vector<float>* descriptor) {
  Rng rng(HashCombine(HashString("scale_bench.replay"), key));
  *points = source_features.keypoints[source];
  for (Point2& p : *points) {
    p.x += static_cast<float>(rng.Uniform(-0.5, 0.5));
    p.y += static_cast<float>(rng.Uniform(-0.5, 0.5));
  }
  *descriptor = source_features.thumbnails.descriptor(source);
  double norm = 0;
  for (float& v : *descriptor) {
    v += static_cast<float>(0.01 * (rng.Uniform() - 0.5));
    norm += static_cast<double>(v) * v;
  }
  for (float& v : *descriptor) v = static_cast<float>(v / std::sqrt(std::max(norm, 1e-30)));
}

void MeasureSize(const FrontEndOutput& features, int sources, int size, const Args& args, const MatchOptions& match,
                 const RansacOptions& ransac) {
  ShortlistIndex shortlist(static_cast<int>(features.thumbnails.descriptor(0).size()), args.shortlist);
  RetrievalIndex points;
  std::vector<double> insert_ms;
  std::vector<Point2> p;
  std::vector<float> d;
  for (int i = 0; i < size; ++i) {
    Replay(features, i % sources, static_cast<uint64_t>(i), &p, &d);
    const auto t = Clock::now();
    points.Add(p);
    shortlist.Add(i, d);
    insert_ms.push_back(MsSince(t));
  }
  std::vector<double> search_ms, ransac_ms, query_ms;
  for (int q = 0; q < args.queries; ++q) {
    // Queries spread over the source frames, each a fresh replay (keys past the database's).
    const int source = static_cast<int>(static_cast<int64_t>(q) * sources / args.queries);
    Replay(features, source, static_cast<uint64_t>(size) + q, &p, &d);
    points.Add(p);  // the query's points, scored against database entries by frame id
    const auto t = Clock::now();
    std::vector<int> listed = shortlist.Search(d, args.shortlist.k);
    const double s = MsSince(t);
    std::sort(listed.begin(), listed.end());
    const auto t_ransac = Clock::now();
    points.ScoreDatabases({size + q}, {listed}, match, ransac, 1, args.threads);
    const double r = MsSince(t_ransac);
    search_ms.push_back(s), ransac_ms.push_back(r), query_ms.push_back(s + r);
  }
  std::printf(
      "size %7d: insert p50 %.3f p99 %.3f ms | query p50 %.2f p99 %.2f ms (search p50 %.2f, RANSAC p50 "
      "%.2f) | index %s | peak memory %s\n",
      size, Quantile(insert_ms, 0.5), Quantile(insert_ms, 0.99), Quantile(query_ms, 0.5), Quantile(query_ms, 0.99),
      Quantile(search_ms, 0.5), Quantile(ransac_ms, 0.5), FormatBytes(shortlist.MemoryBytes()).c_str(),
      FormatBytes(PeakResidentBytes()).c_str());
  std::fflush(stdout);
}

int Main(int argc, char** argv) {
  const Args args = Parse(argc, argv);
  std::string dir = args.dataset;
  std::filesystem::path temp;
  if (dir.empty()) {
    temp = std::filesystem::temp_directory_path() / ("scale_bench_" + std::to_string(::getpid()));
    SequenceOptions render;
    render.output_dir = temp.string();
    render.threads = args.threads;
    render.outputs = "thermal";
    std::printf("rendering scenes/paper_room.json into %s\n", render.output_dir.c_str());
    RenderSequence(LoadScene(DataDir() + "/scenes/paper_room.json", {}), render);
    dir = render.output_dir;
  }
  const Dataset dataset = Dataset::Open(dir, Verify::kOnRead, args.threads);
  const BenchOptions bench;
  FrontEndOptions front;
  front.keypoints = bench.keypoints;
  front.thumbnail = bench.thumbnail;
  front.threads = args.threads;
  FrontEndOutput features = RunFrontEnds(dataset, {FrontEnd::kKeypoints, FrontEnd::kThumbnails}, front);
  features.keypoint_index = RetrievalIndex();  // the replayed databases hold their own
  if (!temp.empty()) std::filesystem::remove_all(temp);
  double points = 0;
  for (const auto& k : features.keypoints) points += static_cast<double>(k.size());
  const int sources = dataset.num_frames();
  MatchOptions match;
  match.image_height_px = dataset.manifest().intrinsics.height;
  const RansacOptions ransac;
  std::printf("replaying %d frames of %s (%.0f keypoints a frame), K = %d (%s), %d queries a size\n", sources,
              dir.c_str(), points / std::max(1, sources), args.shortlist.k, args.shortlist.index.c_str(), args.queries);
  for (int size : args.sizes) MeasureSize(features, sources, size, args, match, ransac);
  return 0;
}

}  // namespace
}  // namespace hoilcd

int main(int argc, char** argv) {
  try {
    return hoilcd::Main(argc, argv);
  } catch (const hoilcd::InputError& e) {
    std::fprintf(stderr, "scale_bench: %s\n", e.what());
    return 2;
  }
}
