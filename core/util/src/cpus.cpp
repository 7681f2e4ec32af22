#include "hoilcd/core/util/cpus.h"

#include <sched.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>

namespace hoilcd {
namespace {

std::string ReadSmallFile(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The CPU affinity of the calling thread (0: unknown).
int AffinityCpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return 0;
  return CPU_COUNT(&set);
}

// The tightest quota on this process's cgroup or its ancestors. Hand-written: neither the
// standard library nor TBB reads cgroup quotas.
std::optional<int> CgroupCpuLimit() {
  std::optional<int> limit;
  auto tighten = [&](std::optional<int> l) {
    if (l && (!limit || *l < *limit)) limit = l;
  };
  std::istringstream cgroups(ReadSmallFile("/proc/self/cgroup"));
  for (std::string line; std::getline(cgroups, line);) {
    const size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    std::string path = line.substr(second + 1);
    const bool v2 = line.compare(0, first, "0") == 0 && controllers.empty();
    const bool v1_cpu = controllers.find("cpu") != std::string::npos && controllers.find("cpuset") == std::string::npos;
    if (!v2 && !v1_cpu) continue;
    for (;;) {  // the cgroup and every ancestor
      if (v2) {
        tighten(CpuQuotaLimit(ReadSmallFile("/sys/fs/cgroup" + path + "/cpu.max")));
      } else {
        for (const std::string root : {"/sys/fs/cgroup/cpu,cpuacct", "/sys/fs/cgroup/cpu"}) {
          tighten(CpuQuotaLimit(ReadSmallFile(root + path + "/cpu.cfs_quota_us") + " " +
                                ReadSmallFile(root + path + "/cpu.cfs_period_us")));
        }
      }
      if (path.empty() || path == "/") break;
      path = path.substr(0, path.find_last_of('/'));
    }
  }
  return limit;
}

}  // namespace

std::optional<int> CpuQuotaLimit(const std::string& quota_and_period) {
  std::istringstream in(quota_and_period);
  std::string quota_text;
  double period = 0;
  if (!(in >> quota_text >> period) || quota_text == "max" || !(period > 0)) return std::nullopt;
  double quota = 0;
  try {
    quota = std::stod(quota_text);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (!(quota > 0)) return std::nullopt;  // v1 writes -1 for no quota
  return std::max(1, static_cast<int>(std::ceil(quota / period - 1e-9)));
}

int AvailableCpus() {
  int cpus = AffinityCpus();
  if (cpus <= 0) cpus = static_cast<int>(std::thread::hardware_concurrency());
  if (const std::optional<int> quota = CgroupCpuLimit()) cpus = cpus > 0 ? std::min(cpus, *quota) : *quota;
  return std::max(1, cpus);
}

}  // namespace hoilcd
