// The CPUs this process may use: its affinity mask (taskset, a container's cpuset) capped by a
// cgroup CPU quota (a container's --cpus, a Slurm or Kubernetes CPU limit). `--threads 0` means
// this many, not the machine's cores, so a job on a shared node does not oversubscribe it.
#pragma once

#include <optional>
#include <string>

namespace hoilcd {

// At least 1.
int AvailableCpus();

// The CPU limit of a cgroup quota file's text: cgroup v2 cpu.max ("QUOTA PERIOD" or "max PERIOD")
// or cgroup v1 cfs_quota_us and cfs_period_us joined by a space; quota / period rounded up, or
// nothing when unlimited or unreadable.
std::optional<int> CpuQuotaLimit(const std::string& quota_and_period);

}  // namespace hoilcd
