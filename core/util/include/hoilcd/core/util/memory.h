// The memory this process may allocate, and the check made before an allocation a user's input
// sizes (a thumbnail database, a frame-by-frame matrix): a request the machine cannot hold is
// refused as bad input, naming what asked for it, instead of failing deep inside an allocator.
#pragma once

#include <optional>
#include <string>

namespace hoilcd {

// Where the kernel's figures are read; tests point these at fixture folders.
struct MemoryFiles {
  std::string proc = "/proc";             // meminfo, self/cgroup
  std::string cgroup = "/sys/fs/cgroup";  // the cgroup hierarchy (v2, or v1's memory/ below it)
};

// Bytes this process may still allocate: the least of MemAvailable (/proc/meminfo) and, for its
// cgroup and every ancestor, the memory limit minus the usage (v2 memory.max - memory.current,
// v1 memory.limit_in_bytes - memory.usage_in_bytes); nothing when none of them can be read.
std::optional<double> AllocatableBytes(const MemoryFiles& files = {});

// MemAvailable of /proc/meminfo's text, in bytes; nothing when absent or unreadable.
std::optional<double> MemAvailableBytes(const std::string& meminfo);
// Room left under a cgroup memory limit: limit - usage (at least 0), or nothing when the limit is
// "max", absent, unreadable, or v1's "no limit" (a number near 2^63).
std::optional<double> CgroupMemoryRoom(const std::string& limit, const std::string& usage);

// This process's peak resident memory so far (getrusage's ru_maxrss), bytes.
double PeakResidentBytes();

// "40.0 GB", "512 MB", "3 KB" (decimal units).
std::string FormatBytes(double bytes);

// Throws InputError at `where` (the flag or parameter that sized the request) when `bytes` is
// more than AllocatableBytes(files): "<what> needs 40.0 GB; this process may allocate 6.1 GB".
// Does nothing when the available memory cannot be read.
void CheckAllocation(double bytes, const std::string& where, const std::string& what, const MemoryFiles& files = {});

}  // namespace hoilcd
