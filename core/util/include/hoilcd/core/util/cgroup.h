// The cgroups this process belongs to (/proc/self/cgroup, v1 and v2) and the chain from a cgroup up
// to its hierarchy's root: where the CPU quota (cpus.h) and the memory limit (memory.h) are read.
// Hand-written: no library at hand reads cgroup limits.
#pragma once

#include <string>
#include <vector>

namespace hoilcd {

// One line of /proc/self/cgroup: "ID:CONTROLLERS:PATH".
struct CgroupMembership {
  bool v2 = false;                       // the unified hierarchy ("0::PATH")
  std::vector<std::string> controllers;  // v1: the hierarchy's controllers ("cpu", "cpuacct", ...)
  std::string path;                      // the cgroup below the hierarchy's root ("/user.slice/job")

  bool Has(const std::string& controller) const;
};

// The memberships in the text of /proc/self/cgroup; malformed lines are skipped.
std::vector<CgroupMembership> ParseCgroupMemberships(const std::string& text);

// `path` and each of its ancestors, nearest first: "/a/b" -> "/a/b", "/a", "".
std::vector<std::string> CgroupAndAncestors(std::string path);

// A small kernel file's text; "" when it cannot be read.
std::string ReadSmallFile(const std::string& path);

}  // namespace hoilcd
