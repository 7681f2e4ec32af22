#include "hoilcd/core/util/option_table.h"

#include <cmath>
#include <cstdint>
#include <limits>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace hoilcd {
namespace {

using nlohmann::json;

struct Inner {
  double sd_m = -1;
  bool enabled = false;
};

struct Flat {
  int samples = -1;
};

struct Example {
  enum class Mode { kFast, kSlow };
  double gain = -1;
  double offset_k = -1;
  double reference_c = -1;
  int count = -1;
  bool on = false;
  std::string preset;
  Mode mode = Mode::kSlow;
  Inner inner;
  Flat flat;
};

const OptionTable<Inner>& InnerTable() {
  static const OptionTable<Inner> table =
      OptionTable<Inner>()
          .Add("sd_m", &Inner::sd_m, 0.1, "m", OptionRange::Closed(0, 1), "standard deviation")
          .Add("enabled", &Inner::enabled, true, "switch");
  return table;
}

const OptionTable<Flat>& FlatTable() {
  static const OptionTable<Flat> table =
      OptionTable<Flat>().Add("samples", &Flat::samples, 2, "", OptionRange::Closed(1, 8), "samples per axis");
  return table;
}

const OptionTable<Example>& ExampleTable() {
  static const OptionTable<Example> table =
      OptionTable<Example>()
          .Add("gain", &Example::gain, 0.5, "", OptionRange().Above(0).AtMost(10), "gain")
          .Add("offset_k", &Example::offset_k, 0, "K", OptionRange::Any(), "offset")
          .Add("count", &Example::count, 3, "", OptionRange().AtLeast(1).Below(100), "count")
          .Add("on", &Example::on, true, "switch")
          .Add("reference_c", &Example::reference_c, 25, "°C", OptionRange::Closed(-50, 150), "model constant")
          .CodeOnly()
          .Add("preset", &Example::preset, "fast", {"fast", "slow"}, "preset")
          .AddEnum("mode", &Example::mode, Example::Mode::kFast,
                   {{"fast", Example::Mode::kFast}, {"slow", Example::Mode::kSlow}}, "mode")
          .Nest("inner", &Example::inner, InnerTable())
          .Flatten(&Example::flat, FlatTable())
          .External("waypoints", "read elsewhere")
          .Rule("offset_k", [](const Example& e) { return e.offset_k > e.gain ? "at most gain" : ""; });
  return table;
}

Example Defaults() {
  Example e;
  ExampleTable().FillDefaults(&e);
  return e;
}

std::vector<std::string> Wheres(const ProblemCollector& problems) {
  std::vector<std::string> out;
  for (const Problem& p : problems.problems()) out.push_back(p.where);
  return out;
}

TEST(OptionTable, FillDefaultsSetsEveryRegisteredFieldIncludingNestedFlattenedAndEnums) {
  const Example e = Defaults();
  EXPECT_EQ(e.gain, 0.5);
  EXPECT_EQ(e.offset_k, 0);
  EXPECT_EQ(e.count, 3);
  EXPECT_TRUE(e.on);
  EXPECT_EQ(e.preset, "fast");
  EXPECT_EQ(e.mode, Example::Mode::kFast);
  EXPECT_EQ(e.inner.sd_m, 0.1);
  EXPECT_TRUE(e.inner.enabled);
  EXPECT_EQ(e.flat.samples, 2);
  EXPECT_EQ(ExampleTable().FirstProblem(e), "");
}

TEST(OptionTable, ReadSetsPresentFieldsAndKeepsAbsentOnes) {
  Example e = Defaults();
  ProblemCollector problems;
  ExampleTable().Read(json::parse(R"({"gain": 2, "mode": "slow", "inner": {"sd_m": 0.5},
                                      "samples": 4, "waypoints": [[0, 0]]})"),
                      "f.json: /x", &e, &problems);
  EXPECT_TRUE(problems.empty());
  EXPECT_EQ(e.gain, 2);
  EXPECT_EQ(e.mode, Example::Mode::kSlow);
  EXPECT_EQ(e.inner.sd_m, 0.5);
  EXPECT_TRUE(e.inner.enabled);
  EXPECT_EQ(e.flat.samples, 4);
  EXPECT_EQ(e.count, 3);
}

TEST(OptionTable, ReadReportsUnknownKeysAndWrongTypesAtTheirJsonPointer) {
  Example e = Defaults();
  ProblemCollector problems;
  ExampleTable().Read(json::parse(R"({"gian": 2, "count": 2.5, "on": 1, "preset": "medium",
                                      "inner": {"sd": 1, "enabled": "yes"}, "gain": "x"})"),
                      "f.json: /x", &e, &problems);
  const std::vector<std::string> wheres = Wheres(problems);
  const std::vector<std::string> expected = {"f.json: /x/count",         "f.json: /x/gain",     "f.json: /x/gian",
                                             "f.json: /x/inner/enabled", "f.json: /x/inner/sd", "f.json: /x/on",
                                             "f.json: /x/preset"};
  std::vector<std::string> sorted = wheres;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, expected);
  bool unknown_named = false;
  for (const Problem& p : problems.problems()) {
    if (p.where == "f.json: /x/gian") {
      unknown_named = p.message.find("unknown key 'gian'") == 0 && p.message.find("gain") != std::string::npos;
    }
  }
  EXPECT_TRUE(unknown_named);
  ProblemCollector not_object;
  ExampleTable().Read(json::array(), "f.json: /x", &e, &not_object);
  EXPECT_EQ(Wheres(not_object), std::vector<std::string>{"f.json: /x"});
}

TEST(OptionTable, CheckReportsEveryValueOutsideItsRangeAtItsPointerWithRangeAndUnit) {
  Example e = Defaults();
  e.gain = 0;          // exclusive minimum
  e.count = 100;       // exclusive maximum
  e.inner.sd_m = 1.5;  // nested
  e.flat.samples = 0;  // flattened
  ProblemCollector problems;
  ExampleTable().Check(e, "f.json: /x", &problems);
  ASSERT_EQ(problems.problems().size(), 4u);
  EXPECT_EQ(problems.problems()[0].ToString(), "f.json: /x/gain: must be in (0, 10] (got 0)");
  EXPECT_EQ(problems.problems()[1].ToString(), "f.json: /x/count: must be in [1, 100) (got 100)");
  EXPECT_EQ(problems.problems()[2].ToString(), "f.json: /x/inner/sd_m: must be in [0, 1] m (got 1.5)");
  EXPECT_EQ(problems.problems()[3].ToString(), "f.json: /x/samples: must be in [1, 8] (got 0)");
}

TEST(OptionTable, BoundsAreInclusiveOrExclusiveAsRegistered) {
  Example e = Defaults();
  e.gain = 10;  // inclusive maximum
  e.count = 1;  // inclusive minimum
  EXPECT_EQ(ExampleTable().FirstProblem(e), "");
  e.gain = 1e-12;
  EXPECT_EQ(ExampleTable().FirstProblem(e), "");
}

TEST(OptionTable, NonFiniteValuesFailEvenAnUnboundedRange) {
  Example e = Defaults();
  e.offset_k = std::nan("");
  EXPECT_EQ(ExampleTable().FirstProblem(e), "offset_k: must be a finite number (K) (got nan)");
}

TEST(OptionTable, CodeOnlyFieldsAreDefaultedCheckedAndSettableButNotReadFromJson) {
  Example e = Defaults();
  EXPECT_EQ(e.reference_c, 25);
  ProblemCollector problems;
  ExampleTable().Read(json::parse(R"({"reference_c": 30})"), "f.json: /x", &e, &problems);
  ASSERT_EQ(problems.problems().size(), 1u);
  EXPECT_EQ(problems.problems()[0].message.rfind("unknown key 'reference_c'", 0), 0u);
  EXPECT_EQ(problems.problems()[0].message.find("reference_c", 20), std::string::npos) << "not offered as expected";
  EXPECT_EQ(e.reference_c, 25);
  ExampleTable().Set("reference_c=200", &e);
  EXPECT_EQ(ExampleTable().FirstProblem(e), "reference_c: must be in [-50, 150] °C (got 200)");
  EXPECT_TRUE(ExampleTable().List()[4].code_only);
}

TEST(OptionTable, OptionalFieldsAreListedAsSuchAndReadLikeAnyOther) {
  struct Trigger {
    double delta_k;
  };
  const OptionTable<Trigger> table =
      OptionTable<Trigger>()
          .Add("delta_k", &Trigger::delta_k, 0.0, "K", OptionRange::Closed(0, 20), "trigger")
          .Optional();
  ASSERT_EQ(table.List().size(), 1u);
  EXPECT_TRUE(table.List()[0].optional);
  EXPECT_FALSE(ExampleTable().List()[0].optional);
  Trigger t{};
  table.FillDefaults(&t);
  EXPECT_EQ(t.delta_k, 0.0);
  ProblemCollector problems;
  table.Read(json::parse(R"({"delta_k": 1.5})"), "f.json: /x", &t, &problems);
  EXPECT_TRUE(problems.empty());
  EXPECT_EQ(t.delta_k, 1.5);
}

TEST(OptionTable, RulesAreReportedAtTheirField) {
  Example e = Defaults();
  e.offset_k = 1;
  EXPECT_EQ(ExampleTable().FirstProblem(e), "offset_k: at most gain");
}

TEST(OptionTable, SetParsesNameEqualsValueForEveryKindAndNestedNames) {
  Example e = Defaults();
  ExampleTable().Set("gain=7.5", &e);
  ExampleTable().Set("count=42", &e);
  ExampleTable().Set("on=false", &e);
  ExampleTable().Set("mode=slow", &e);
  ExampleTable().Set("inner.sd_m=0.25", &e);
  ExampleTable().Set("inner/enabled=false", &e);
  ExampleTable().Set("samples=5", &e);
  EXPECT_EQ(e.gain, 7.5);
  EXPECT_EQ(e.count, 42);
  EXPECT_FALSE(e.on);
  EXPECT_EQ(e.mode, Example::Mode::kSlow);
  EXPECT_EQ(e.inner.sd_m, 0.25);
  EXPECT_FALSE(e.inner.enabled);
  EXPECT_EQ(e.flat.samples, 5);
}

TEST(OptionTable, SetRejectsUnknownNamesAndBadValuesNamingTheText) {
  Example e = Defaults();
  auto message = [&](const std::string& text) {
    try {
      ExampleTable().Set(text, &e);
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("gian=1").rfind("gian=1: an option name (one of: gain, offset_k", 0), 0u) << message("gian=1");
  EXPECT_EQ(message("gain=fast"), "gain=fast: a number");
  EXPECT_EQ(message("gain=1e999"), "gain=1e999: a number");
  EXPECT_EQ(message("count=2.5"), "count=2.5: a whole number");
  EXPECT_EQ(message("on=yes"), "on=yes: true or false");
  EXPECT_EQ(message("mode=medium"), "mode=medium: one of: fast, slow");
  EXPECT_EQ(message("inner=1"), "inner=1: a field of 'inner' (e.g. inner/...)");
  EXPECT_EQ(message("gain.x=1"), "gain.x=1: no field after 'gain' (it is a value, not a group)");
  EXPECT_EQ(message("gain"), "gain: NAME=VALUE");  // every message is what was expected
  EXPECT_EQ(message("=1"), "=1: NAME=VALUE");
  EXPECT_EQ(message("waypoints=1").rfind("waypoints=1: an option name", 0), 0u);
}

TEST(OptionTable, ListGivesEveryFieldWithDefaultUnitRangeAndDescription) {
  const std::vector<OptionInfo> list = ExampleTable().List();
  std::vector<std::string> names;
  for (const OptionInfo& o : list) names.push_back(o.name);
  EXPECT_EQ(names, (std::vector<std::string>{"gain", "offset_k", "count", "on", "reference_c", "preset", "mode",
                                             "inner/sd_m", "inner/enabled", "samples", "waypoints"}));
  EXPECT_EQ(list[0].default_json, "0.5");
  EXPECT_TRUE(list[0].range.min->exclusive);
  EXPECT_FALSE(list[0].range.max->exclusive);
  EXPECT_EQ(list[2].kind, OptionInfo::Kind::kInteger);
  EXPECT_EQ(list[6].default_json, "\"fast\"");
  EXPECT_EQ(list[6].choices, (std::vector<std::string>{"fast", "slow"}));
  EXPECT_EQ(list[7].unit, "m");
  EXPECT_EQ(list[10].kind, OptionInfo::Kind::kExternal);
  const std::string text = FormatOptionList(list);
  EXPECT_NE(text.find("inner/sd_m"), std::string::npos);
  EXPECT_NE(text.find("in [0, 1] m"), std::string::npos);
  EXPECT_NE(text.find("standard deviation"), std::string::npos);
}

TEST(OptionTable, OnlyKeepsTheNamedFieldsWithTheirDefaultsRangesAndRules) {
  const OptionTable<Example> some = ExampleTable().Only({"offset_k", "gain"});
  std::vector<std::string> names;
  for (const OptionInfo& o : some.List()) names.push_back(o.name);
  EXPECT_EQ(names, (std::vector<std::string>{"gain", "offset_k"}));  // the table's order
  Example e;
  some.FillDefaults(&e);
  EXPECT_EQ(e.gain, 0.5);
  EXPECT_EQ(e.count, -1) << "a field left out is not touched";
  e.gain = 11;
  EXPECT_EQ(some.FirstProblem(e), "gain: must be in (0, 10] (got 11)");
  e.gain = 0.5;
  e.offset_k = 1;
  EXPECT_EQ(some.FirstProblem(e), "offset_k: at most gain");
  EXPECT_EQ(ExampleTable().Only({"gain"}).FirstProblem(e), "") << "a rule at a field left out is left out";
  EXPECT_THROW(some.Set("count=2", &e), InputError);
  EXPECT_THROW(ExampleTable().Only({"gian"}), std::logic_error);
}

TEST(OptionTable, AppendJoinsTwoViewsOfOneStruct) {
  const OptionTable<Example> joined = ExampleTable().Only({"count"}).Append(ExampleTable().Only({"gain"}));
  std::vector<std::string> names;
  for (const OptionInfo& o : joined.List()) names.push_back(o.name);
  EXPECT_EQ(names, (std::vector<std::string>{"count", "gain"}));
  Example e = Defaults();
  joined.Set("gain=3", &e);
  EXPECT_EQ(e.gain, 3);
}

TEST(OptionTable, ToJsonGivesEveryValueAsReadReadsItAndListsDefaults) {
  Example e = Defaults();
  const json values = ExampleTable().ToJson(e);
  EXPECT_EQ(values, json::parse(R"({"gain": 0.5, "offset_k": 0.0, "count": 3, "on": true, "reference_c": 25.0,
                                    "preset": "fast", "mode": "fast", "inner": {"sd_m": 0.1, "enabled": true},
                                    "samples": 2})"));
  for (const OptionInfo& o : ExampleTable().List()) {
    if (o.kind != OptionInfo::Kind::kExternal) {
      EXPECT_EQ(values.at(json::json_pointer("/" + o.name)), json::parse(o.default_json)) << o.name;
    }
  }
  Example read;
  ProblemCollector problems;
  json without_code_only = values;
  without_code_only.erase("reference_c");
  ExampleTable().Read(without_code_only, "", &read, &problems);
  EXPECT_TRUE(problems.empty());
  json read_back = ExampleTable().ToJson(read);
  EXPECT_EQ(read_back["reference_c"], -1.0) << "code-only: not read";
  read_back.erase("reference_c");
  EXPECT_EQ(read_back, without_code_only);
}

TEST(OptionTable, RenameGivesAFieldAndItsRulesAnotherNameOnly) {
  const OptionTable<Example> renamed = ExampleTable().Only({"gain", "offset_k"}).Rename("offset_k", "bias_k");
  Example e = Defaults();
  renamed.Set("bias_k=0.25", &e);
  EXPECT_EQ(e.offset_k, 0.25);
  e.offset_k = 1;
  EXPECT_EQ(renamed.FirstProblem(e), "bias_k: at most gain");
  EXPECT_EQ(renamed.List()[1].default_json, "0.0");
  EXPECT_THROW(renamed.Set("offset_k=0", &e), InputError);
  EXPECT_THROW(ExampleTable().Rename("gain", "count"), std::logic_error);
}

TEST(OptionTable, WithDefaultChangesOneDefaultInsideItsRange) {
  const OptionTable<Example> other = ExampleTable().WithDefault("gain", 2).WithDefault("count", 7);
  Example e;
  other.FillDefaults(&e);
  EXPECT_EQ(e.gain, 2);
  EXPECT_EQ(e.count, 7);
  EXPECT_EQ(e.offset_k, 0);
  EXPECT_EQ(Defaults().gain, 0.5) << "the original table keeps its own";
  EXPECT_THROW(ExampleTable().WithDefault("gain", 20), std::logic_error);
  EXPECT_THROW(ExampleTable().WithDefault("count", 2.5), std::logic_error);
  EXPECT_THROW(ExampleTable().WithDefault("preset", 1), std::logic_error);
}

TEST(OptionTable, Uint64FieldsAreDefaultedReadSetAndChecked) {
  struct Seeded {
    uint64_t offset = 0;
  };
  const OptionTable<Seeded> table = OptionTable<Seeded>().Add("offset", &Seeded::offset, uint64_t{1000}, "",
                                                              OptionRange::Any().AtLeast(0), "seed offset");
  Seeded s;
  table.FillDefaults(&s);
  EXPECT_EQ(s.offset, 1000u);
  EXPECT_EQ(table.List()[0].default_json, "1000");
  EXPECT_EQ(table.List()[0].kind, OptionInfo::Kind::kInteger);
  table.Set("offset=4294967296", &s);
  EXPECT_EQ(s.offset, 4294967296u);
  EXPECT_EQ(table.FirstProblem(s), "");
  EXPECT_THROW(table.Set("offset=-1", &s), InputError);
  ProblemCollector problems;
  table.Read(json::parse(R"({"offset": -3})"), "f.json", &s, &problems);
  EXPECT_EQ(Wheres(problems), std::vector<std::string>{"f.json/offset"});
  table.Read(json::parse(R"({"offset": 7})"), "f.json", &s, &problems);
  EXPECT_EQ(s.offset, 7u);
}

TEST(OptionTable, OrNaNAcceptsNaNAsNotSetButNoInfinity) {
  struct Threshold {
    double t = 0;
  };
  const OptionTable<Threshold> table = OptionTable<Threshold>().Add(
      "t", &Threshold::t, std::nan(""), "", OptionRange::Any().OrNaN(), "threshold; NaN: calibrated");
  Threshold x;
  table.FillDefaults(&x);
  EXPECT_TRUE(std::isnan(x.t));
  EXPECT_EQ(table.FirstProblem(x), "");
  x.t = std::numeric_limits<double>::infinity();
  EXPECT_EQ(table.FirstProblem(x), "t: must be a finite number or NaN (got inf)");
  EXPECT_EQ(OptionRange::Any().AtLeast(0).OrNaN().ToString("m"), "at least 0 m or NaN");
}

TEST(OptionTable, RegisteringADefaultOutsideItsRangeIsAnApiMisuse) {
  struct Bad {
    double x = 0;
  };
  EXPECT_THROW(OptionTable<Bad>().Add("x", &Bad::x, 5, "", OptionRange::Closed(0, 1), "x"), std::logic_error);
}

}  // namespace
}  // namespace hoilcd
