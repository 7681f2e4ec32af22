#include "hoilcd/core/util/shard.h"

#include <cstdint>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

std::string Shard::Check() const {
  if (count < 1) return "the number of shards must be at least 1";
  if (index < 0 || index >= count) return "the shard index must be in 0.." + std::to_string(count - 1);
  return "";
}

std::string Shard::Name() const { return std::to_string(index) + "/" + std::to_string(count); }

Shard ParseShard(const std::string& text) {
  const size_t slash = text.find('/');
  auto parse = [&](const std::string& part) {
    const size_t b = part.find_first_not_of(" \t");
    const std::string t = b == std::string::npos ? "" : part.substr(b, part.find_last_not_of(" \t") - b + 1);
    if (t.empty() || t.find_first_not_of("0123456789") != std::string::npos || t.size() > 9) {
      throw InputError("--shard", "expected I/N with whole numbers, 0 <= I < N (e.g. 0/4), but got '" + text + "'");
    }
    return std::stoi(t);
  };
  if (slash == std::string::npos) parse("");
  Shard shard;
  shard.index = parse(text.substr(0, slash));
  shard.count = parse(text.substr(slash + 1));
  if (const std::string problem = shard.Check(); !problem.empty())
    throw InputError("--shard", problem + " (got '" + text + "')");
  return shard;
}

IndexRange ContiguousPart(const Shard& shard, int total) {
  HOILCD_CHECK_MSG(shard.Check().empty() && total >= 0, shard.Check());
  auto bound = [&](int i) { return static_cast<int>(static_cast<int64_t>(i) * total / shard.count); };
  return {bound(shard.index), bound(shard.index + 1)};
}

}  // namespace hoilcd
