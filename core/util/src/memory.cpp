#include "hoilcd/core/util/memory.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>

#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

// v1 writes its "no limit" as the largest page-aligned int64; anything this large is no limit.
constexpr double kNoLimitBytes = 1e18;

std::string ReadSmallFile(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::optional<double> ParseBytes(const std::string& text) {
  std::istringstream in(text);
  double value = 0;
  if (!(in >> value) || !(value >= 0)) return std::nullopt;
  return value;
}

// The tightest room under the memory limits of this process's cgroup and its ancestors.
// Hand-written, as cpus.cpp reads the CPU quota: no library at hand reads cgroup limits.
std::optional<double> CgroupRoom(const MemoryFiles& files) {
  std::optional<double> room;
  auto tighten = [&](std::optional<double> r) {
    if (r && (!room || *r < *room)) room = r;
  };
  std::istringstream cgroups(ReadSmallFile(files.proc + "/self/cgroup"));
  for (std::string line; std::getline(cgroups, line);) {
    const size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    std::string path = line.substr(second + 1);
    const bool v2 = line.compare(0, first, "0") == 0 && controllers.empty();
    bool v1_memory = false;
    std::istringstream names(controllers);
    for (std::string name; std::getline(names, name, ',');) v1_memory |= name == "memory";
    if (!v2 && !v1_memory) continue;
    for (;;) {  // the cgroup and every ancestor
      const std::string dir = v2 ? files.cgroup + path : files.cgroup + "/memory" + path;
      if (v2) {
        tighten(CgroupMemoryRoom(ReadSmallFile(dir + "/memory.max"), ReadSmallFile(dir + "/memory.current")));
      } else {
        tighten(CgroupMemoryRoom(ReadSmallFile(dir + "/memory.limit_in_bytes"),
                                 ReadSmallFile(dir + "/memory.usage_in_bytes")));
      }
      if (path.empty() || path == "/") break;
      path = path.substr(0, path.find_last_of('/'));
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

}  // namespace hoilcd
