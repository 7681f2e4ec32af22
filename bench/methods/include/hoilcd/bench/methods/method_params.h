// --param NAME=VALUE for the bench: NAME is "<method>.<field>" (a field of that method's option
// table, e.g. slcd.ransac_trials, fusion.k) or "<front end>.<field>" (a shared front end's, e.g.
// persons.threshold_c, which every method on that front end sees). Each table registers fields of
// BenchOptions once (option_table.h), so a parameter only changes the copy of the options its
// method or front end runs with.
#pragma once

#include <string>
#include <vector>

#include "hoilcd/bench/methods/bench_options.h"
#include "hoilcd/bench/methods/front_ends.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

std::string FrontEndName(FrontEnd front_end);  // "keypoints", "persons", "thumbnails"
const OptionTable<BenchOptions>& FrontEndParams(FrontEnd front_end);

// Tables the point-set methods and others share.
const OptionTable<RansacOptions>& RansacParams();  // ransac_trials, inlier_threshold_px
const OptionTable<MatchOptions>& MatchParams();    // vertical_tolerance

// Throws InputError("--param", ...) naming the parameter: not NAME=VALUE, unknown method or
// front end, unknown field, a value of the wrong type or out of its range.
// `methods`: the methods run (empty: DefaultMethods()); also throws for a parameter of a method
// not among them or of a front end none of them uses, which would be silently ignored.
void CheckParams(const std::vector<std::string>& params, const std::vector<std::string>& methods);

// `options` with every parameter of `scope` (a method or front end name) set through `table`;
// with a null table, `options` unchanged (parameters of a scope without one fail CheckParams).
BenchOptions WithParams(const BenchOptions& options, const std::string& scope,
                        const OptionTable<BenchOptions>* table);

// Every parameter, one line each, grouped by method and front end (for --help-params).
std::string FormatParams();

}  // namespace hoilcd
