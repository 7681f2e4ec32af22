#include "hoilcd/bench/methods/method_params.h"

#include <algorithm>
#include <iterator>

#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

// The front ends with a --param scope of their own (the oracles' options are their models').
constexpr FrontEnd kFrontEnds[] = {FrontEnd::kKeypoints, FrontEnd::kPersons, FrontEnd::kThumbnails};

bool HasScope(FrontEnd front_end) {
  return std::find(std::begin(kFrontEnds), std::end(kFrontEnds), front_end) != std::end(kFrontEnds);
}

// Throws for a scope that is neither a method nor a front end, naming the known ones.
void CheckScope(const std::string& scope, const std::string& param) {
  for (FrontEnd f : kFrontEnds)
    if (FrontEndName(f) == scope) return;
  if (IsMethod(scope)) return;
  std::string known;
  for (const auto& m : RegisteredMethods()) known += (known.empty() ? "" : ", ") + m->Name();
  for (FrontEnd f : kFrontEnds) known += ", " + FrontEndName(f);
  throw InputError("--param", "'" + param +
                                  "': expected NAME=VALUE with NAME = <method or front end>.<field>, "
                                  "the method or front end one of: " +
                                  known);
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

// Runs `set` (one table's Set) with its InputError reworded to name the whole parameter.
template <typename SetFn>
void SetNamingParam(const std::string& param, const SetFn& set) {
  try {
    set();
  } catch (const InputError& e) {
    throw InputError("--param", "'" + param + "': expected " + e.problems().front().message);
  }
}

void ThrowIfProblem(const std::string& param, const std::string& problem) {
  if (!problem.empty()) throw InputError("--param", "'" + param + "': " + problem);
}

}  // namespace

FrontEnd FrontEndOf(const std::string& name) {
  for (FrontEnd f : kFrontEnds)
    if (FrontEndName(f) == name) return f;
  HOILCD_CHECK_MSG(false, "no front end called " << name);
  std::abort();
}

std::string FrontEndName(FrontEnd front_end) {
  switch (front_end) {
    case FrontEnd::kKeypoints:
      return "keypoints";
    case FrontEnd::kPersons:
      return "persons";
    case FrontEnd::kThumbnails:
      return "thumbnails";
    case FrontEnd::kIdealKeypoints:
      return "ideal-keypoints";
    case FrontEnd::kTruePersons:
      return "true-persons";
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

FrontEnd ParamScope(FrontEnd front_end) {
  return front_end == FrontEnd::kIdealKeypoints ? FrontEnd::kKeypoints : front_end;
}

const OptionTable<BenchOptions>& FrontEndParams(FrontEnd front_end) {
  HOILCD_CHECK_MSG(HasScope(front_end), FrontEndName(front_end) << " has no --param scope");
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
      throw InputError("--param", "'" + param +
                                      "': expected NAME=VALUE with NAME = <method or front end>.<field>, "
                                      "e.g. slcd.ransac_trials=50");
    }
    CheckScope(scope, param);
    if (IsMethod(scope)) {
      OptionsWithParams(FindMethod(scope), {param});
    } else {
      const OptionTable<BenchOptions>& table = FrontEndParams(FrontEndOf(scope));
      BenchOptions set;
      SetNamingParam(param, [&] { table.Set(rest, &set); });
      ThrowIfProblem(param, table.FirstProblem(set));
    }
    bool used = false;
    for (const std::string& m : run) {
      if (m == scope) used = true;
      for (FrontEnd f : FindMethod(m).FrontEnds()) used |= FrontEndName(ParamScope(f)) == scope;
    }
    if (!used) {
      throw InputError("--param", "'" + param + "': " + (IsMethod(scope) ? "method " : "front end ") + scope +
                                      (IsMethod(scope) ? " is not run" : " is used by none of the methods run") +
                                      " (methods: " + run_list + "); add it to --methods or drop the parameter");
    }
  }
}

BenchOptions WithFrontEndParams(const BenchOptions& options, FrontEnd front_end_in) {
  const FrontEnd front_end = ParamScope(front_end_in);
  if (!HasScope(front_end)) return options;
  BenchOptions out = options;
  for (const std::string& param : options.params) {
    std::string scope, rest;
    if (SplitParam(param, &scope, &rest) && scope == FrontEndName(front_end)) {
      SetNamingParam(param, [&] { FrontEndParams(front_end).Set(rest, &out); });
    }
  }
  return out;
}

std::unique_ptr<MethodOptions> OptionsWithParams(const LoopClosureMethod& method,
                                                 const std::vector<std::string>& params) {
  std::unique_ptr<MethodOptions> own = method.Options();
  for (const std::string& param : params) {
    std::string scope, rest;
    if (!SplitParam(param, &scope, &rest) || scope != method.Name()) continue;
    if (own == nullptr) throw InputError("--param", "'" + param + "': method " + scope + " has no parameters");
    SetNamingParam(param, [&] { own->Set(rest); });
    ThrowIfProblem(param, own->FirstProblem());
  }
  return own;
}

std::string FormatParams() {
  std::string out;
  for (const auto& m : RegisteredMethods()) {
    if (const std::unique_ptr<MethodOptions> own = m->Options())
      out += m->Name() + ".\n" + FormatOptionList(own->List());
  }
  for (FrontEnd f : kFrontEnds)
    out += FrontEndName(f) + ". (every method on this front end)\n" + FormatOptionList(FrontEndParams(f).List());
  return out;
}

}  // namespace hoilcd
