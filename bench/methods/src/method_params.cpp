#include "hoilcd/bench/methods/method_params.h"

#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

constexpr FrontEnd kFrontEnds[] = {FrontEnd::kKeypoints, FrontEnd::kPersons, FrontEnd::kThumbnails};

// The table that owns `scope`, or null when the scope is a method without parameters; throws
// for a scope that is neither a method nor a front end.
const OptionTable<BenchOptions>* TableOf(const std::string& scope, const std::string& param) {
  for (FrontEnd f : kFrontEnds)
    if (FrontEndName(f) == scope) return &FrontEndParams(f);
  if (IsMethod(scope)) return FindMethod(scope).Params();
  std::string known;
  for (const auto& m : RegisteredMethods()) known += (known.empty() ? "" : ", ") + m->Name();
  for (FrontEnd f : kFrontEnds) known += ", " + FrontEndName(f);
  throw InputError("--param", "'" + param + "': expected NAME=VALUE with NAME = <method or front end>.<field>, "
                              "the method or front end one of: " + known);
}

// Splits "scope.field=value" at the first dot before the '='.
bool SplitParam(const std::string& param, std::string* scope, std::string* rest) {
  const size_t eq = param.find('=');
  const size_t dot = param.find('.');
  if (eq == std::string::npos || dot == std::string::npos || dot > eq || dot == 0) return false;
  *scope = param.substr(0, dot);
  *rest = param.substr(dot + 1);
  return true;
}

BenchOptions Apply(const BenchOptions& options, const std::string& param, const std::string& rest,
                   const OptionTable<BenchOptions>& table) {
  BenchOptions out = options;
  try {
    table.Set(rest, &out);
  } catch (const InputError& e) {
    throw InputError("--param", "'" + param + "': expected " + e.problems().front().message);
  }
  return out;
}

}  // namespace

std::string FrontEndName(FrontEnd front_end) {
  switch (front_end) {
    case FrontEnd::kKeypoints: return "keypoints";
    case FrontEnd::kPersons: return "persons";
    case FrontEnd::kThumbnails: return "thumbnails";
  }
  return "";
}

// The --param tables are views of the options' own tables (Only, Rename): each default and range
// is registered once, beside its struct.
const OptionTable<RansacOptions>& RansacParams() {
  static const OptionTable<RansacOptions> table =
      RansacOptions::Table().Only({"trials", "inlier_threshold_px"}).Rename("trials", "ransac_trials");
  return table;
}

const OptionTable<MatchOptions>& MatchParams() {
  static const OptionTable<MatchOptions> table = MatchOptions::Table().Only({"vertical_tolerance"});
  return table;
}

const OptionTable<BenchOptions>& FrontEndParams(FrontEnd front_end) {
  static const OptionTable<BenchOptions> tables[] = {
      OptionTable<BenchOptions>().Flatten(
          &BenchOptions::keypoints,
          KeypointOptions::Table().Only({"detector", "max_keypoints", "gftt_quality", "gftt_min_eigenvalue"})),
      OptionTable<BenchOptions>().Flatten(
          &BenchOptions::detector,
          PersonDetectorOptions::Table().Only({"threshold_c", "head_min_c", "min_area_px", "min_height_px"})),
      OptionTable<BenchOptions>().Flatten(&BenchOptions::thumbnail, ThumbnailOptions::Table()),
  };
  return tables[static_cast<int>(front_end)];
}

void CheckParams(const std::vector<std::string>& params, const std::vector<std::string>& methods) {
  const std::vector<std::string> run = methods.empty() ? DefaultMethods() : methods;
  std::string run_list;
  for (const std::string& m : run) run_list += (run_list.empty() ? "" : ", ") + m;
  for (const std::string& param : params) {
    std::string scope, rest;
    if (!SplitParam(param, &scope, &rest)) {
      throw InputError("--param", "'" + param + "': expected NAME=VALUE with NAME = <method or front end>.<field>, "
                                  "e.g. slcd.ransac_trials=50");
    }
    const OptionTable<BenchOptions>* table = TableOf(scope, param);
    if (table == nullptr) throw InputError("--param", "'" + param + "': method " + scope + " has no parameters");
    const BenchOptions set = Apply(BenchOptions{}, param, rest, *table);
    ProblemCollector problems;
    table->Check(set, "", &problems);
    if (!problems.empty()) {
      throw InputError("--param", "'" + param + "': " + problems.problems().front().ToString());
    }
    bool used = false;
    for (const std::string& m : run) {
      if (m == scope) used = true;
      for (FrontEnd f : FindMethod(m).FrontEnds()) used |= FrontEndName(f) == scope;
    }
    if (!used) {
      throw InputError("--param", "'" + param + "': " + (IsMethod(scope) ? "method " : "front end ") + scope +
                                      (IsMethod(scope) ? " is not run" : " is used by none of the methods run") +
                                      " (methods: " + run_list + "); add it to --methods or drop the parameter");
    }
  }
}

BenchOptions WithParams(const BenchOptions& options, const std::string& scope,
                        const OptionTable<BenchOptions>* table) {
  BenchOptions out = options;
  if (table == nullptr) return out;
  for (const std::string& param : options.params) {
    std::string s, rest;
    if (SplitParam(param, &s, &rest) && s == scope) out = Apply(out, param, rest, *table);
  }
  return out;
}

std::string FormatParams() {
  std::string out;
  for (const auto& m : RegisteredMethods()) {
    if (m->Params() == nullptr) continue;
    out += m->Name() + ".\n" + FormatOptionList(m->Params()->List());
  }
  for (FrontEnd f : kFrontEnds) out += FrontEndName(f) + ". (every method on this front end)\n" + FormatOptionList(FrontEndParams(f).List());
  return out;
}

}  // namespace hoilcd
