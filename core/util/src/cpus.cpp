#include "hoilcd/core/util/cpus.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <thread>

#include <sched.h>

#include "hoilcd/core/util/cgroup.h"

namespace hoilcd {
namespace {

// The CPU affinity of the calling thread (0: unknown).
int AffinityCpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return 0;
  return CPU_COUNT(&set);
}

// The tightest quota on this process's cgroup or its ancestors.
std::optional<int> CgroupCpuLimit() {
  std::optional<int> limit;
  auto tighten = [&](std::optional<int> l) {
    if (l && (!limit || *l < *limit)) limit = l;
  };
  for (const CgroupMembership& m : ParseCgroupMemberships(ReadSmallFile("/proc/self/cgroup"))) {
    if (!m.v2 && !m.Has("cpu")) continue;
    for (const std::string& path : CgroupAndAncestors(m.path)) {
      if (m.v2) {
        tighten(CpuQuotaLimit(ReadSmallFile("/sys/fs/cgroup" + path + "/cpu.max")));
      } else {
        for (const std::string root : {"/sys/fs/cgroup/cpu,cpuacct", "/sys/fs/cgroup/cpu"}) {
          tighten(CpuQuotaLimit(ReadSmallFile(root + path + "/cpu.cfs_quota_us") + " " +
                                ReadSmallFile(root + path + "/cpu.cfs_period_us")));
        }
      }
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
