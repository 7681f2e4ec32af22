#include "hoilcd/core/util/cgroup.h"

#include <algorithm>
#include <fstream>
#include <sstream>

namespace hoilcd {

bool CgroupMembership::Has(const std::string& controller) const {
  return std::find(controllers.begin(), controllers.end(), controller) != controllers.end();
}

std::vector<CgroupMembership> ParseCgroupMemberships(const std::string& text) {
  std::vector<CgroupMembership> out;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    const size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    CgroupMembership m;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    m.v2 = line.compare(0, first, "0") == 0 && controllers.empty();
    std::istringstream names(controllers);
    for (std::string name; std::getline(names, name, ',');) m.controllers.push_back(name);
    m.path = line.substr(second + 1);
    out.push_back(m);
  }
  return out;
}

std::vector<std::string> CgroupAndAncestors(std::string path) {
  std::vector<std::string> out;
  for (;;) {
    out.push_back(path);
    if (path.empty() || path == "/") return out;
    path = path.substr(0, path.find_last_of('/'));
  }
}

std::string ReadSmallFile(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace hoilcd
