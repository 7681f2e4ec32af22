// Shards for job arrays (`--shard I/N` of sweep and suite): the I-th of N disjoint parts of a run
// list sorted by name, every N-th run starting at I, so the parts depend on neither the thread count
// nor the machine and together cover the list once.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

// The I-th of N parts (0-based, as Slurm array task ids and Kubernetes JOB_COMPLETION_INDEX are).
struct Shard {
  int index = 0;  // which part, 0 <= index < count
  int count = 1;  // number of parts, >= 1
  // A value parsed from --shard or an output marker, not options: no table, its check is by hand.
  std::string Check() const;
  std::string Name() const;  // "I/N"
};

// Parses "I/N"; throws InputError("--shard", ...) saying what was expected.
Shard ParseShard(const std::string& text);

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
