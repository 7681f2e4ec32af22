#include "hoilcd/core/place_recognition/shortlist_index.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <faiss/IndexFlat.h>
#include <faiss/IndexHNSW.h>
#include <omp.h>

#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

// FAISS parallelises over the queries of a call with OpenMP; hoilcd adds and searches one frame at
// a time, so a team of threads only costs its wake-up (about a scheduler slice, ~10 ms, on a busy
// machine) and a visited table per thread. While it lives, this thread's FAISS calls run alone.
class OneOpenMpThread {
 public:
  OneOpenMpThread() : before_(omp_get_max_threads()) { omp_set_num_threads(1); }
  ~OneOpenMpThread() { omp_set_num_threads(before_); }
  OneOpenMpThread(const OneOpenMpThread&) = delete;
  OneOpenMpThread& operator=(const OneOpenMpThread&) = delete;

 private:
  int before_;
};

}  // namespace

ShortlistOptions::ShortlistOptions() { Table().FillDefaults(this); }

const OptionTable<ShortlistOptions>& ShortlistOptions::Table() {
  using O = ShortlistOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("k", &O::k, 50, "frames", R::Closed(0, 100000),
               "frames the global-descriptor shortlist hands to RANSAC; 0 = every frame (no shortlist)")
          .Add("index", &O::index, "hnsw", {"hnsw", "flat"},
               "the shortlist's FAISS index: hnsw (approximate nearest neighbours) or flat (exact)")
          .Add("hnsw_neighbours", &O::hnsw_neighbours, 32, "", R::Closed(4, 256), "HNSW links per frame (M)")
          .Add("hnsw_build_depth", &O::hnsw_build_depth, 64, "", R::Closed(4, 4096),
               "HNSW candidates kept while a frame is linked in (efConstruction)")
          .Add("hnsw_search_depth", &O::hnsw_search_depth, 128, "", R::Closed(1, 100000),
               "HNSW candidates kept while searching (efSearch; at least k)");
  return table;
}

std::string ShortlistOptions::Check() const { return Table().FirstProblem(*this); }

ShortlistIndex::ShortlistIndex(int dimension, const ShortlistOptions& options)
    : dimension_(dimension), options_(options) {
  HOILCD_CHECK_MSG(dimension > 0, "a shortlist index needs descriptors of at least one value");
  HOILCD_CHECK_MSG(options.Check().empty(), options.Check());
  if (options.index == "flat") {
    index_ = std::make_unique<faiss::IndexFlatIP>(dimension);
  } else {
    auto hnsw = std::make_unique<faiss::IndexHNSWFlat>(dimension, options.hnsw_neighbours, faiss::METRIC_INNER_PRODUCT);
    hnsw->hnsw.efConstruction = options.hnsw_build_depth;
    hnsw->hnsw.efSearch = options.hnsw_search_depth;
    index_ = std::move(hnsw);
  }
}

ShortlistIndex::~ShortlistIndex() = default;

void ShortlistIndex::Add(int id, const std::vector<float>& descriptor) {
  HOILCD_CHECK_MSG(static_cast<int>(descriptor.size()) == dimension_,
                   "descriptor of " << descriptor.size() << " values, the index holds " << dimension_);
  for (float v : descriptor) HOILCD_CHECK_MSG(std::isfinite(v), "descriptor values must be finite");
  // One vector per call on this thread alone: the graph depends only on the order of the calls.
  const OneOpenMpThread alone;
  index_->add(1, descriptor.data());
  ids_.push_back(id);
}

std::vector<int> ShortlistIndex::Search(const std::vector<float>& descriptor, int k) const {
  HOILCD_CHECK_MSG(static_cast<int>(descriptor.size()) == dimension_,
                   "descriptor of " << descriptor.size() << " values, the index holds " << dimension_);
  const int n = size();
  const int want = (k <= 0 || k > n) ? n : k;
  if (want == 0) return {};
  const faiss::Index* searched = index_.get();
  // Every frame: the exact vectors HNSW stores, since a graph search need not reach them all.
  if (want == n) {
    if (const auto* hnsw = dynamic_cast<const faiss::IndexHNSW*>(index_.get())) searched = hnsw->storage;
  }
  const OneOpenMpThread alone;
  std::vector<float> similarity(want);
  std::vector<faiss::Index::idx_t> labels(want, -1);
  if (const auto* hnsw = dynamic_cast<const faiss::IndexHNSW*>(searched)) {
    faiss::SearchParametersHNSW params;
    params.efSearch = std::max(options_.hnsw_search_depth, want);
    hnsw->search(1, descriptor.data(), want, similarity.data(), labels.data(), &params);
  } else {
    searched->search(1, descriptor.data(), want, similarity.data(), labels.data());
  }
  std::vector<std::pair<float, int>> found;  // (similarity, id)
  for (int i = 0; i < want; ++i) {
    if (labels[i] >= 0 && labels[i] < n) found.emplace_back(similarity[i], ids_[labels[i]]);
  }
  std::sort(found.begin(), found.end(),
            [](const auto& a, const auto& b) { return a.first != b.first ? a.first > b.first : a.second < b.second; });
  std::vector<int> out;
  out.reserve(found.size());
  for (const auto& f : found) out.push_back(f.second);
  return out;
}

double ShortlistIndex::MemoryBytes() const {
  double bytes = static_cast<double>(size()) * (dimension_ * sizeof(float) + sizeof(int));
  if (options_.index == "hnsw") {
    // Level 0 holds 2M links per frame, the levels above about one more (level l holds M^-l of the
    // frames, M links each); plus an offset and a level per frame.
    bytes += static_cast<double>(size()) *
             ((2.0 * options_.hnsw_neighbours + 1) * sizeof(faiss::HNSW::storage_idx_t) + sizeof(size_t) + sizeof(int));
  }
  return bytes;
}

}  // namespace hoilcd
