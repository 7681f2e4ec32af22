// Shards for job arrays (`--shard I/N` of render, sweep and suite): the I-th of N disjoint parts of
// a piece of work. The syntax is parsed once, here; each command says how it splits its work
// (render: contiguous frame ranges, ContiguousPart; sweep and suite: a round robin over their runs).
#pragma once

#include <string>

namespace hoilcd {

// The I-th of N parts (0-based, as Slurm array task ids and Kubernetes JOB_COMPLETION_INDEX are).
struct Shard {
  int index = 0;  // which part, 0 <= index < count
  int count = 1;  // number of parts, >= 1
  // A value parsed from --shard or an output marker, not options: no table, its check is by hand.
  std::string Check() const;
  std::string Name() const;  // "I/N"
  bool operator==(const Shard& o) const { return index == o.index && count == o.count; }
  bool operator!=(const Shard& o) const { return !(*this == o); }
};

// Parses "I/N"; throws InputError("--shard", ...) saying what was expected.
Shard ParseShard(const std::string& text);

// [begin, end) of the shard's contiguous part of `total` items: [I*total/N, (I+1)*total/N), so the
// parts tile [0, total) in order and differ in size by at most one.
struct IndexRange {
  int begin = 0;
  int end = 0;
  bool operator==(const IndexRange& o) const { return begin == o.begin && end == o.end; }
};
IndexRange ContiguousPart(const Shard& shard, int total);

}  // namespace hoilcd
