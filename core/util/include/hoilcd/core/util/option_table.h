// Option tables: every field of an options struct registered once -- JSON name, member, unit,
// default, range, one-line description -- and that one table fills the defaults, reads a JSON
// object (unknown keys are problems), checks every value into a ProblemCollector at its JSON
// pointer, sets one field from "NAME=VALUE" text (--param) and lists itself for docs and --help.
// (The idea of COLMAP's OptionManager; the schema test compares the tables with the scene schema.)
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

// A numeric range: each end absent (unbounded), inclusive or exclusive. Non-finite values are
// outside every range, except NaN where OrNaN() says it stands for "not set".
struct OptionRange {
  struct Bound {
    double value = 0;
    bool exclusive = false;
  };
  std::optional<Bound> min, max;
  bool nan_allowed = false;

  static OptionRange Any() { return {}; }
  static OptionRange Closed(double lo, double hi) { return Any().AtLeast(lo).AtMost(hi); }  // [lo, hi]
  OptionRange AtLeast(double lo) const { return With(&OptionRange::min, {lo, false}); }     // >= lo
  OptionRange Above(double lo) const { return With(&OptionRange::min, {lo, true}); }        // > lo
  OptionRange AtMost(double hi) const { return With(&OptionRange::max, {hi, false}); }      // <= hi
  OptionRange Below(double hi) const { return With(&OptionRange::max, {hi, true}); }        // < hi
  OptionRange OrNaN() const {                                                               // or NaN (not set)
    OptionRange out = *this;
    out.nan_allowed = true;
    return out;
  }

  bool Contains(double value) const;  // false for infinities, and for NaN unless OrNaN()
  // "in (0, 10] px", "at least 1", "a finite number" (unit appended when not empty; "or NaN").
  std::string ToString(const std::string& unit = "") const;

 private:
  OptionRange With(std::optional<Bound> OptionRange::*end, Bound bound) const {
    OptionRange out = *this;
    out.*end = bound;
    return out;
  }
};

// One registered field, as listed (docs, --help) and compared with the scene schema.
struct OptionInfo {
  enum class Kind { kNumber, kInteger, kBoolean, kString, kExternal };
  std::string name;  // JSON path below the table's object: "vibration/enabled"
  Kind kind = Kind::kNumber;
  std::string default_json;          // the default as JSON text ("0.5", "true", "\"veryfast\"")
  std::string unit;                  // "" when none
  OptionRange range;                 // numbers and integers
  std::vector<std::string> choices;  // strings: the accepted values (empty: any string)
  std::string description;           // one line
  bool code_only = false;            // set by code, never read from JSON (see CodeOnly)
  bool optional = false;             // may be left out of a document, default and all (see Optional)
};

// The type-independent machinery; use OptionTable<T> below.
class OptionTableBase {
 public:
  struct Field;
  enum class Storage { kDouble, kInt, kUint64 };  // the C++ type of a number's member
  OptionTableBase();
  ~OptionTableBase();
  OptionTableBase(const OptionTableBase& other);
  OptionTableBase& operator=(const OptionTableBase& other);

  std::vector<OptionInfo> List() const;

 protected:
  using Locate = std::function<void*(void*)>;  // the struct -> one of its members
  void AddNumber(const char* name, Locate at, Storage storage, double default_value, const char* unit,
                 OptionRange range, const char* description);
  void AddBool(const char* name, Locate at, bool default_value, const char* description);
  // String members; enums go through to_text / from_text (choices: the accepted texts).
  void AddString(const char* name, std::function<std::string(const void*)> get,
                 std::function<void(void*, const std::string&)> set, std::string default_value,
                 std::vector<std::string> choices, const char* description);
  void AddNested(const char* name, Locate at, const OptionTableBase& table);
  void AddFlattened(Locate at, const OptionTableBase& table);
  void AddExternal(const char* name, const char* description);
  void AddRule(const char* field, std::function<std::string(const void*)> rule);
  void MarkLastCodeOnly();
  void MarkLastOptional();
  void KeepOnly(const std::vector<std::string>& names);
  void RenameField(const std::string& from, const std::string& to);
  void ChangeDefault(const std::string& name, double default_value);

  void FillDefaultsOf(void* options) const;
  nlohmann::json ToJsonOf(const void* options) const;
  void ReadInto(const nlohmann::json& object, const std::string& where, void* options,
                ProblemCollector* problems) const;
  void CheckOf(const void* options, const std::string& where, ProblemCollector* problems) const;
  void SetOf(const std::string& name_equals_value, void* options) const;

 private:
  struct Rule;
  std::vector<Field> fields_;
  std::vector<Rule> rules_;
};

// Fields of T, registered once (usually in a function-local static built by the module that
// owns T). Problem locations: `where` + "/" + the field's path, e.g. "scene.json: /camera" +
// "/netd_k"; with an empty `where`, just the path ("vibration/roll_sd_deg").
template <typename T>
class OptionTable : public OptionTableBase {
 public:
  OptionTable& Add(const char* name, double T::*member, double default_value, const char* unit, OptionRange range,
                   const char* description) {
    AddNumber(name, At(member), Storage::kDouble, default_value, unit, range, description);
    return *this;
  }
  OptionTable& Add(const char* name, int T::*member, int default_value, const char* unit, OptionRange range,
                   const char* description) {
    AddNumber(name, At(member), Storage::kInt, default_value, unit, range, description);
    return *this;
  }
  // An unsigned 64-bit whole number (a seed offset, say); values above 2^53 are not supported.
  OptionTable& Add(const char* name, uint64_t T::*member, uint64_t default_value, const char* unit, OptionRange range,
                   const char* description) {
    AddNumber(name, At(member), Storage::kUint64, static_cast<double>(default_value), unit, range, description);
    return *this;
  }
  OptionTable& Add(const char* name, bool T::*member, bool default_value, const char* description) {
    AddBool(name, At(member), default_value, description);
    return *this;
  }
  // A string; `choices` empty accepts any string.
  OptionTable& Add(const char* name, std::string T::*member, std::string default_value,
                   std::vector<std::string> choices, const char* description) {
    AddString(
        name, [member](const void* p) { return static_cast<const T*>(p)->*member; },
        [member](void* p, const std::string& v) { static_cast<T*>(p)->*member = v; }, std::move(default_value),
        std::move(choices), description);
    return *this;
  }
  // An enum member written as one of `choices`' texts.
  template <typename E>
  OptionTable& AddEnum(const char* name, E T::*member, E default_value, std::vector<std::pair<std::string, E>> choices,
                       const char* description) {
    std::vector<std::string> texts;
    std::string default_text;
    for (const auto& [text, value] : choices) {
      texts.push_back(text);
      if (value == default_value) default_text = text;
    }
    AddString(
        name,
        [member, choices](const void* p) {
          for (const auto& [text, value] : choices) {
            if (static_cast<const T*>(p)->*member == value) return text;
          }
          return std::string();
        },
        [member, choices](void* p, const std::string& v) {
          for (const auto& [text, value] : choices) {
            if (text == v) static_cast<T*>(p)->*member = value;
          }
        },
        default_text, texts, description);
    return *this;
  }
  // A member struct S read from the sub-object `name` with S's own table.
  template <typename S>
  OptionTable& Nest(const char* name, S T::*member, const OptionTable<S>& table) {
    AddNested(name, At(member), table);
    return *this;
  }
  // The same for an S that `at` finds in T (an entry of a map member, say).
  template <typename S>
  OptionTable& Nest(const char* name, std::function<S*(T*)> at, const OptionTable<S>& table) {
    AddNested(
        name, [at = std::move(at)](void* p) -> void* { return at(static_cast<T*>(p)); }, table);
    return *this;
  }
  // A member struct S whose fields sit in this same JSON object.
  template <typename S>
  OptionTable& Flatten(S T::*member, const OptionTable<S>& table) {
    AddFlattened(At(member), table);
    return *this;
  }
  // A key of this object that is read elsewhere (arrays, maps): accepted by Read, not touched.
  OptionTable& External(const char* name, const char* description) {
    AddExternal(name, description);
    return *this;
  }
  // Marks the field registered last as set by code (a model constant, a value taken from
  // elsewhere in the scene): listed, defaulted, checked and settable, but not a JSON key.
  OptionTable& CodeOnly() {
    MarkLastCodeOnly();
    return *this;
  }
  // Marks the field registered last as optional: a document may leave it out and stays without
  // it when its defaults are filled in (the schema gives it no default), its absence meaning the
  // table's default. A field added later this way leaves every existing resolved document, and
  // its hash, unchanged.
  OptionTable& Optional() {
    MarkLastOptional();
    return *this;
  }
  // A check beyond one field's range: `rule` returns "" or what was expected, reported at `field`.
  OptionTable& Rule(const char* field, std::function<std::string(const T&)> rule) {
    AddRule(field, [rule = std::move(rule)](const void* p) { return rule(*static_cast<const T*>(p)); });
    return *this;
  }

  // A copy holding only the fields `names` (in this table's order) and the rules reported at them:
  // the fields of T that another interface exposes (a --param table, say), their defaults and
  // ranges still registered once, here. A name this table does not have is an API misuse.
  OptionTable Only(const std::vector<std::string>& names) const {
    OptionTable out = *this;
    out.KeepOnly(names);
    return out;
  }
  // A copy in which field `from` (and the rules reported at it) is called `to`.
  OptionTable Rename(const std::string& from, const std::string& to) const {
    OptionTable out = *this;
    out.RenameField(from, to);
    return out;
  }
  // A copy in which number field `name` defaults to `default_value` (inside its range): the
  // default of T's field where T is part of a larger whole with its own (a bench's scoring
  // filter, say), stated once by that whole's table.
  OptionTable WithDefault(const std::string& name, double default_value) const {
    OptionTable out = *this;
    out.ChangeDefault(name, default_value);
    return out;
  }

  // Appends every field and rule of `other`, another table of T (fields from two views of T).
  OptionTable& Append(const OptionTable<T>& other) {
    AddFlattened([](void* p) { return p; }, other);
    return *this;
  }

  void FillDefaults(T* options) const { FillDefaultsOf(options); }
  // Every registered field's value as Read reads it (nested tables as objects; External keys
  // left out; code-only fields included): for reports, and for tests against List()'s defaults.
  // (A template only so that this header needs no more than json_fwd.hpp.)
  template <typename Json = nlohmann::json>
  Json ToJson(const T& options) const {
    return ToJsonOf(&options);
  }
  // Sets every field present in `object` (a JSON object); absent fields keep their value. Wrong
  // types, unknown keys and values outside a string's choices are problems at their pointer.
  void Read(const nlohmann::json& object, const std::string& where, T* options, ProblemCollector* problems) const {
    ReadInto(object, where, options, problems);
  }
  // Every value outside its range and every broken rule, each at its pointer.
  void Check(const T& options, const std::string& where, ProblemCollector* problems) const {
    CheckOf(&options, where, problems);
  }
  // "" when valid, else the first problem ("path: must be ..."): for HOILCD_CHECKs of callers.
  std::string FirstProblem(const T& options) const {
    ProblemCollector problems;
    Check(options, "", &problems);
    return problems.empty() ? "" : problems.problems().front().ToString();
  }
  // Sets one field from "NAME=VALUE" (NAME a field path with '/' or '.'); throws InputError
  // naming the text on an unknown name or a value of the wrong type. Call Check afterwards.
  void Set(const std::string& name_equals_value, T* options) const { SetOf(name_equals_value, options); }

 private:
  template <typename M>
  static Locate At(M T::*member) {
    return [member](void* p) -> void* { return &(static_cast<T*>(p)->*member); };
  }
};

// The table as aligned text, one field a line: name, default, unit, range, description.
std::string FormatOptionList(const std::vector<OptionInfo>& options);
// The accepted values of a field in words: "in (0, 10] px", "one of: a, b", "true or false";
// "" for a string that takes any text.
std::string OptionRangeText(const OptionInfo& option);
// The table as a Markdown table (field, default, accepted values, description); fields set only by
// code are left out. The generated reference docs/guide/scenes.md is made of these.
std::string FormatOptionTableMarkdown(const std::vector<OptionInfo>& options);

}  // namespace hoilcd
