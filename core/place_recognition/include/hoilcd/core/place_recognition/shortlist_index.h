// The shortlist of online loop closure: frames' global descriptors in a FAISS index, searched for
// the K frames most similar to a query (inner product, so normalised thumbnails compare by their
// cross-correlation), on which the point-set methods then run RANSAC instead of the whole
// database. Exact search (IndexFlatIP) or a graph of nearest neighbours (IndexHNSWFlat, Malkov &
// Yashunin 2018). Frames are added one by one as a robot adds them; every call is deterministic.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hoilcd/core/util/option_table.h"

namespace faiss {
struct Index;
}

namespace hoilcd {

// Defaults and ranges: Table() in shortlist_index.cpp.
struct ShortlistOptions {
  int k;                  // frames the shortlist keeps for RANSAC; 0 = every frame (no shortlist)
  std::string index;      // "hnsw" (approximate, fast at 100,000 frames) or "flat" (exact)
  int hnsw_neighbours;    // HNSW's M: links per node
  int hnsw_build_depth;   // HNSW's efConstruction: candidates kept while a frame is linked in
  int hnsw_search_depth;  // HNSW's efSearch: candidates kept while searching (at least k is used)

  ShortlistOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<ShortlistOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

class ShortlistIndex {
 public:
  // `dimension`: length of every descriptor (> 0).
  ShortlistIndex(int dimension, const ShortlistOptions& options);
  ~ShortlistIndex();
  ShortlistIndex(const ShortlistIndex&) = delete;
  ShortlistIndex& operator=(const ShortlistIndex&) = delete;

  // Adds frame `id` (any int, usually the frame number). descriptor.size() == dimension, finite.
  void Add(int id, const std::vector<float>& descriptor);
  // The ids of the min(k, size()) frames most similar to `descriptor` (k <= 0: all of them),
  // most similar first, equal similarities by ascending id.
  std::vector<int> Search(const std::vector<float>& descriptor, int k) const;
  int size() const { return static_cast<int>(ids_.size()); }
  int dimension() const { return dimension_; }
  // Bytes the index holds: descriptors, links and the id table (an estimate for HNSW's links).
  double MemoryBytes() const;

 private:
  int dimension_;
  ShortlistOptions options_;
  std::unique_ptr<faiss::Index> index_;
  std::vector<int> ids_;  // FAISS's sequential label -> the caller's id
};

}  // namespace hoilcd
