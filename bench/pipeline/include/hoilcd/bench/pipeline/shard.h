// Shards of sweep and suite (`--shard I/N`, parsed by core/util/shard.h): the I-th of N disjoint
// parts of a run list sorted by name, every N-th run starting at I, so the parts depend on neither
// the thread count nor the machine and together cover the list once.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/shard.h"  // Shard and its parser, shared with render

namespace hoilcd {

// The shard's runs: sorted_runs[k] for k % count == index (round robin over the sorted list).
template <typename Run>
std::vector<Run> ShardOf(const std::vector<Run>& sorted_runs, const Shard& shard) {
  HOILCD_CHECK_MSG(shard.Check().empty(), shard.Check());
  std::vector<Run> out;
  for (size_t k = static_cast<size_t>(shard.index); k < sorted_runs.size(); k += static_cast<size_t>(shard.count)) {
    out.push_back(sorted_runs[k]);
  }
  return out;
}

}  // namespace hoilcd
