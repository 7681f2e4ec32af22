#include "hoilcd/bench/methods/methods.h"

#include <algorithm>
#include <sstream>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

bool IsMethod(const std::string& name) {
  const auto& methods = RegisteredMethods();
  return std::any_of(methods.begin(), methods.end(), [&](const auto& m) { return m->Name() == name; });
}

std::vector<std::string> DefaultMethods() {
  std::vector<std::string> out;
  for (const auto& m : RegisteredMethods()) out.push_back(m->Name());
  return out;
}

std::vector<std::string> ParseMethodList(const std::string& csv, std::vector<std::string>* from_groups) {
  std::vector<std::string> out, named;
  std::stringstream ss(csv);
  std::string name;
  auto add = [&](const std::string& n) {
    if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
  };
  while (std::getline(ss, name, ',')) {
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    if (name.empty()) continue;
    if (name == "all") {
      for (const auto& m : RegisteredMethods()) add(m->Name());
      continue;
    }
    if (name == "paper") {
      for (const auto& m : RegisteredMethods())
        if (m->FromPaper()) add(m->Name());
      continue;
    }
    if (!IsMethod(name)) {
      std::string known;
      for (const auto& m : RegisteredMethods()) known += (known.empty() ? "" : ", ") + m->Name();
      throw InputError("--methods", "unknown method '" + name + "' (known: " + known + ", paper, all)");
    }
    add(name);
    named.push_back(name);
  }
  if (out.empty()) throw InputError("--methods", "at least one method name");
  if (from_groups != nullptr) {
    from_groups->clear();
    for (const std::string& m : out)
      if (std::find(named.begin(), named.end(), m) == named.end()) from_groups->push_back(m);
  }
  return out;
}

}  // namespace hoilcd
