#include "hoilcd/core/util/memory.h"

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <sstream>

#include <sys/resource.h>

#include "hoilcd/core/util/cgroup.h"
#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

// v1 writes its "no limit" as the largest page-aligned int64; anything this large is no limit.
constexpr double kNoLimitBytes = 1e18;

std::optional<double> ParseBytes(const std::string& text) {
  std::istringstream in(text);
  double value = 0;
  if (!(in >> value) || !(value >= 0)) return std::nullopt;
  return value;
}

// The tightest room under the memory limits of this process's cgroup and its ancestors.
std::optional<double> CgroupRoom(const MemoryFiles& files) {
  std::optional<double> room;
  auto tighten = [&](std::optional<double> r) {
    if (r && (!room || *r < *room)) room = r;
  };
  for (const CgroupMembership& m : ParseCgroupMemberships(ReadSmallFile(files.proc + "/self/cgroup"))) {
    if (!m.v2 && !m.Has("memory")) continue;
    for (const std::string& path : CgroupAndAncestors(m.path)) {
      const std::string dir = m.v2 ? files.cgroup + path : files.cgroup + "/memory" + path;
      if (m.v2) {
        tighten(CgroupMemoryRoom(ReadSmallFile(dir + "/memory.max"), ReadSmallFile(dir + "/memory.current")));
      } else {
        tighten(CgroupMemoryRoom(ReadSmallFile(dir + "/memory.limit_in_bytes"),
                                 ReadSmallFile(dir + "/memory.usage_in_bytes")));
      }
    }
  }
  return room;
}

}  // namespace

std::optional<double> MemAvailableBytes(const std::string& meminfo) {
  std::istringstream lines(meminfo);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream in(line);
    std::string key, unit;
    double value = 0;
    if (!(in >> key >> value) || key != "MemAvailable:" || !(value >= 0)) continue;
    in >> unit;
    return unit == "kB" ? value * 1024 : value;
  }
  return std::nullopt;
}

std::optional<double> CgroupMemoryRoom(const std::string& limit, const std::string& usage) {
  const std::optional<double> limit_bytes = ParseBytes(limit);
  if (!limit_bytes || *limit_bytes >= kNoLimitBytes) return std::nullopt;  // "max", absent, v1's none
  return std::max(0.0, *limit_bytes - ParseBytes(usage).value_or(0.0));
}

std::optional<double> AllocatableBytes(const MemoryFiles& files) {
  std::optional<double> bytes = MemAvailableBytes(ReadSmallFile(files.proc + "/meminfo"));
  if (const std::optional<double> room = CgroupRoom(files); room && (!bytes || *room < *bytes)) bytes = room;
  return bytes;
}

std::string FormatBytes(double bytes) {
  static const char* const kUnits[] = {"bytes", "KB", "MB", "GB", "TB", "PB", "EB"};
  int unit = 0;
  while (bytes >= 1000 && unit + 1 < static_cast<int>(std::size(kUnits))) bytes /= 1000, ++unit;
  char text[64];
  std::snprintf(text, sizeof text, unit > 0 && bytes < 100 ? "%.1f %s" : "%.0f %s", bytes, kUnits[unit]);
  return text;
}

void CheckAllocation(double bytes, const std::string& where, const std::string& what, const MemoryFiles& files) {
  const std::optional<double> available = AllocatableBytes(files);
  if (!available || bytes <= *available) return;
  throw InputError(where, what + " needs " + FormatBytes(bytes) + "; this process may allocate " +
                              FormatBytes(*available) + " (MemAvailable and the cgroup's memory limit)");
}

double PeakResidentBytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return 1024.0 * static_cast<double>(usage.ru_maxrss);  // Linux gives kilobytes
}

}  // namespace hoilcd
