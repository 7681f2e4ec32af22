// --param NAME=VALUE for the bench: NAME is "<method>.<field>" (a field of that method's own
// options, method_options.h, e.g. slcd.ransac_trials, fusion.k) or "<front end>.<field>" (a shared
// front end's field of BenchOptions, e.g. persons.threshold_c, which every method on that front
// end sees). Every table is a view of its struct's own (option_table.h), so each default and
// range is registered once, and a parameter only changes the method or front end it names.
#pragma once

#include <string>
#include <vector>

#include "hoilcd/bench/methods/bench_options.h"
#include "hoilcd/bench/methods/front_ends.h"
#include "hoilcd/bench/methods/loop_closure_method.h"
#include "hoilcd/bench/methods/method_options.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

std::string FrontEndName(FrontEnd front_end);  // "keypoints", "persons", "thumbnails", "ideal-keypoints", ...
FrontEnd FrontEndOf(const std::string& name);  // HOILCD_CHECK on a name that is not a --param scope
// The --param scope whose values a front end reads: the ideal keypoints take the keypoints' (the
// same detector on another image); the true persons have none (returned as themselves).
FrontEnd ParamScope(FrontEnd front_end);
// The --param table of keypoints, persons or thumbnails (HOILCD_CHECK on another).
const OptionTable<BenchOptions>& FrontEndParams(FrontEnd front_end);

// Views that several methods' options share.
const OptionTable<RansacOptions>& RansacParams();  // ransac_trials, inlier_threshold_px
const OptionTable<MatchOptions>& MatchParams();    // vertical_tolerance

// Throws InputError("--param", ...) naming the parameter: not NAME=VALUE, unknown method or
// front end, unknown field, a value of the wrong type or out of its range.
// `methods`: the methods run (empty: DefaultMethods()); also throws for a parameter of a method
// not among them or of a front end none of them uses, which would be silently ignored.
void CheckParams(const std::vector<std::string>& params, const std::vector<std::string>& methods);

// `options` with every parameter of the front end's ParamScope set (after CheckParams).
BenchOptions WithFrontEndParams(const BenchOptions& options, FrontEnd front_end);

// `method`'s own options with every parameter "<method>.<field>" of `params` set, checked; null
// for a method without options. Throws InputError naming a bad parameter.
std::unique_ptr<MethodOptions> OptionsWithParams(const LoopClosureMethod& method,
                                                 const std::vector<std::string>& params);

// Every parameter, one line each, grouped by method and front end (for --help-params).
std::string FormatParams();

}  // namespace hoilcd
