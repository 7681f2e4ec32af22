// The loop-closure methods a user can name with --methods: the paper's SLCD, DLCD and their
// fusion, and the beyond-the-paper variants reported beside them. Names are validated here.
#pragma once

#include <string>
#include <vector>

namespace hoilcd {

struct MethodInfo {
  std::string name;         // as given to --methods
  std::string description;  // one line for the report
  bool from_paper = false;  // one of the paper's Table 1 methods
};

// Every method hoilcd knows, in report order.
const std::vector<MethodInfo>& MethodCatalog();
const MethodInfo& FindMethod(const std::string& name);  // HOILCD_CHECK on unknown names

// "slcd,dlcd,fusion" -> names, validated; "paper" = the paper's three, "all" = every method.
// Throws InputError("--methods", ...) naming the unknown method and the known ones.
std::vector<std::string> ParseMethodList(const std::string& csv);

// The default of `hoilcd bench` and `hoilcd run`: the paper's methods plus the extras.
std::vector<std::string> DefaultMethods();

}  // namespace hoilcd
