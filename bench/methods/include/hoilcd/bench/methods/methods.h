// The method names a user can give with --methods: every registered LoopClosureMethod
// (loop_closure_method.h), "paper" for the paper's and "all" for every one. Names are validated here.
#pragma once

#include <string>
#include <vector>

#include "hoilcd/bench/methods/loop_closure_method.h"

namespace hoilcd {

// The registered method called `name`; HOILCD_CHECK on unknown names.
const LoopClosureMethod& FindMethod(const std::string& name);

// Whether a method of that name is registered.
bool IsMethod(const std::string& name);

// "slcd,dlcd,fusion" -> names, validated; "paper" = the paper's three, "all" = every method.
// Throws InputError("--methods", ...) naming the unknown method and the known ones. With
// `from_groups`, also the names that only "all" or "paper" brought in (BenchOptions::optional_methods).
std::vector<std::string> ParseMethodList(const std::string& csv, std::vector<std::string>* from_groups = nullptr);

// The default of `hoilcd bench` and `hoilcd run`: every registered method, in report order.
std::vector<std::string> DefaultMethods();

}  // namespace hoilcd
