// The steps of a bench run that the offline runner (runner.cpp) and the online one (online.cpp)
// share: which methods run and in what order, what the dataset must hold for them, their front
// ends with their --param values, and one scoring pass of every method over a labelling.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/evaluation/evaluate.h"
#include "hoilcd/bench/methods/bench_options.h"
#include "hoilcd/bench/methods/front_ends.h"
#include "hoilcd/bench/methods/loop_closure_method.h"
#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

// The methods to score: the asked ones and, before each, the methods it combines (Inputs()).
std::vector<const LoopClosureMethod*> ScoringOrder(const std::vector<std::string>& asked);

// Keeps the methods `why_not` has nothing against: why_not(method, named) returns "" to keep it,
// else why it cannot run; for a method named on the command line (not brought in by "all",
// "paper" or the default) it throws its InputError instead. Returns "<method>: not run, <why>" per
// method left out; InputError on --methods when none is kept ("no method can run <context>: ...").
std::vector<std::string> KeepMethods(BenchOptions* options, const std::string& context,
                                     const std::function<std::string(const std::string&, bool)>& why_not);

// The methods the dataset lacks the ground truth for: a named one is an InputError naming the
// output and the method; an optional one (from "all", "paper" or the default) is left out of
// options->methods, with a line in the returned notes.
std::vector<std::string> LeaveOutUnavailable(const Dataset& dataset, BenchOptions* options);

std::set<FrontEnd> NeededFrontEnds(const std::vector<const LoopClosureMethod*>& order);

// Before any work: the sizes the front ends' options ask of this dataset fit its image and this
// machine's memory (a thumbnail no larger than the frame; its database within reach).
void CheckFrontEndSizes(const Dataset& dataset, const BenchOptions& options, const std::set<FrontEnd>& needed);

// The front ends in `needed`, once each, with their --param values.
FrontEndOutput RunFrontEndsWithParams(const Dataset& dataset, const BenchOptions& options,
                                      const std::set<FrontEnd>& needed);

// The methods in scoring order with their own options (--param values set), resolved once.
struct ResolvedMethods {
  std::vector<const LoopClosureMethod*> order;
  std::vector<std::unique_ptr<MethodOptions>> own;  // parallel to order; null: none
  std::map<std::string, nlohmann::json> resolved;   // each method's own options as it runs (for the report)
};
ResolvedMethods ResolveMethods(const BenchOptions& options, std::vector<const LoopClosureMethod*> order);

// Every method's scores of `labelling`'s queries, inputs before the methods that combine them;
// methods that share a pass (PassKey) are scored together when the first of them comes up.
std::map<std::string, MethodScores> ScoreMethods(const Dataset& dataset, const BenchOptions& options,
                                                 const ResolvedMethods& methods, const Labelling& labelling,
                                                 const FrontEndOutput& front_ends);

}  // namespace hoilcd
