#include "hoilcd/core/util/option_table.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "hoilcd/core/util/json_reader.h"

namespace hoilcd {

using nlohmann::json;

struct OptionTableBase::Field {
  enum class Kind { kNumber, kInteger, kBoolean, kString, kExternal, kNested };
  Kind kind = Kind::kNumber;
  Storage storage = Storage::kDouble;  // numbers and integers
  std::string name;
  std::string unit, description;
  OptionRange range;
  double default_number = 0;
  bool default_bool = false;
  std::string default_string;
  std::vector<std::string> choices;
  Locate at;  // numbers, integers, booleans, nested tables
  std::function<std::string(const void*)> get_string;
  std::function<void(void*, const std::string&)> set_string;
  std::shared_ptr<const OptionTableBase> nested;
  bool code_only = false;
  bool optional = false;
};

struct OptionTableBase::Rule {
  std::string field;
  std::function<std::string(const void*)> check;
};

namespace {

std::string Number(double value) {
  // Whole numbers up to 2^53 in full ("9007199254740992", not "9.007199255e+15").
  if (value == std::floor(value) && std::fabs(value) <= 9007199254740992.0) {
    return std::to_string(static_cast<long long>(value));
  }
  std::ostringstream out;
  out << std::setprecision(10) << value;
  return out.str();
}

std::string Join(const std::string& where, const std::string& name) {
  return where.empty() ? name : where + "/" + name;
}

std::string JoinChoices(const std::vector<std::string>& choices) {
  std::string out;
  for (const std::string& c : choices) out += (out.empty() ? "" : ", ") + c;
  return out;
}

void* Mutable(const void* p) { return const_cast<void*>(p); }  // Locate serves reads and writes

constexpr double kMaxExactInteger = 9007199254740992.0;  // 2^53: every whole number below is a double

// A number field's value, whatever the member's type.
double LoadNumber(const OptionTableBase::Field& f, const void* options) {
  const void* p = f.at(Mutable(options));
  switch (f.storage) {
    case OptionTableBase::Storage::kDouble:
      return *static_cast<const double*>(p);
    case OptionTableBase::Storage::kInt:
      return *static_cast<const int*>(p);
    case OptionTableBase::Storage::kUint64:
      return static_cast<double>(*static_cast<const uint64_t*>(p));
  }
  return 0;
}

void StoreNumber(const OptionTableBase::Field& f, void* options, double value) {
  void* p = f.at(options);
  switch (f.storage) {
    case OptionTableBase::Storage::kDouble:
      *static_cast<double*>(p) = value;
      break;
    case OptionTableBase::Storage::kInt:
      *static_cast<int*>(p) = static_cast<int>(value);
      break;
    case OptionTableBase::Storage::kUint64:
      *static_cast<uint64_t*>(p) = static_cast<uint64_t>(value);
      break;
  }
}

}  // namespace

bool OptionRange::Contains(double value) const {
  if (std::isnan(value)) return nan_allowed;
  if (!std::isfinite(value)) return false;
  if (min && (min->exclusive ? !(value > min->value) : !(value >= min->value))) return false;
  if (max && (max->exclusive ? !(value < max->value) : !(value <= max->value))) return false;
  return true;
}

std::string OptionRange::ToString(const std::string& unit) const {
  std::string text;
  if (min && max) {
    text = std::string("in ") + (min->exclusive ? "(" : "[") + Number(min->value) + ", " + Number(max->value) +
           (max->exclusive ? ")" : "]");
  } else if (min) {
    text = (min->exclusive ? "above " : "at least ") + Number(min->value);
  } else if (max) {
    text = (max->exclusive ? "below " : "at most ") + Number(max->value);
  } else {
    return "a finite number" + (unit.empty() ? "" : " (" + unit + ")") + (nan_allowed ? " or NaN" : "");
  }
  return (unit.empty() ? text : text + " " + unit) + (nan_allowed ? " or NaN" : "");
}

OptionTableBase::OptionTableBase() = default;
OptionTableBase::~OptionTableBase() = default;
OptionTableBase::OptionTableBase(const OptionTableBase& other) = default;
OptionTableBase& OptionTableBase::operator=(const OptionTableBase& other) = default;

void OptionTableBase::AddNumber(const char* name, Locate at, Storage storage, double default_value, const char* unit,
                                OptionRange range, const char* description) {
  Field f;
  f.kind = storage == Storage::kDouble ? Field::Kind::kNumber : Field::Kind::kInteger;
  f.storage = storage;
  f.name = name;
  f.at = std::move(at);
  f.default_number = default_value;
  f.unit = unit;
  f.range = range;
  f.description = description;
  HOILCD_CHECK_MSG(range.Contains(default_value), name << ": default " << default_value << " outside its range");
  fields_.push_back(std::move(f));
}

void OptionTableBase::AddBool(const char* name, Locate at, bool default_value, const char* description) {
  Field f;
  f.kind = Field::Kind::kBoolean;
  f.name = name;
  f.at = std::move(at);
  f.default_bool = default_value;
  f.description = description;
  fields_.push_back(std::move(f));
}

void OptionTableBase::AddString(const char* name, std::function<std::string(const void*)> get,
                                std::function<void(void*, const std::string&)> set, std::string default_value,
                                std::vector<std::string> choices, const char* description) {
  Field f;
  f.kind = Field::Kind::kString;
  f.name = name;
  f.get_string = std::move(get);
  f.set_string = std::move(set);
  f.default_string = std::move(default_value);
  f.choices = std::move(choices);
  f.description = description;
  HOILCD_CHECK_MSG(f.choices.empty() || std::count(f.choices.begin(), f.choices.end(), f.default_string) == 1,
                   name << ": default '" << f.default_string << "' is not one of its choices");
  fields_.push_back(std::move(f));
}

void OptionTableBase::AddNested(const char* name, Locate at, const OptionTableBase& table) {
  Field f;
  f.kind = Field::Kind::kNested;
  f.name = name;
  f.at = std::move(at);
  f.nested = std::make_shared<const OptionTableBase>(table);
  fields_.push_back(std::move(f));
}

void OptionTableBase::AddFlattened(Locate at, const OptionTableBase& table) {
  for (Field f : table.fields_) {
    if (f.at) f.at = [outer = at, inner = f.at](void* p) { return inner(outer(p)); };
    if (f.get_string) {
      f.get_string = [outer = at, inner = f.get_string](const void* p) { return inner(outer(Mutable(p))); };
      f.set_string = [outer = at, inner = f.set_string](void* p, const std::string& v) { inner(outer(p), v); };
    }
    fields_.push_back(std::move(f));
  }
  for (Rule r : table.rules_) {
    r.check = [outer = at, inner = r.check](const void* p) { return inner(outer(Mutable(p))); };
    rules_.push_back(std::move(r));
  }
}

void OptionTableBase::AddExternal(const char* name, const char* description) {
  Field f;
  f.kind = Field::Kind::kExternal;
  f.name = name;
  f.description = description;
  fields_.push_back(std::move(f));
}

void OptionTableBase::AddRule(const char* field, std::function<std::string(const void*)> rule) {
  rules_.push_back({field, std::move(rule)});
}

void OptionTableBase::MarkLastCodeOnly() {
  HOILCD_CHECK(!fields_.empty() && fields_.back().kind != Field::Kind::kNested);
  fields_.back().code_only = true;
}

void OptionTableBase::MarkLastOptional() {
  HOILCD_CHECK(!fields_.empty() && fields_.back().kind != Field::Kind::kNested);
  fields_.back().optional = true;
}

void OptionTableBase::KeepOnly(const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    HOILCD_CHECK_MSG(std::count_if(fields_.begin(), fields_.end(), [&](const Field& f) { return f.name == name; }) == 1,
                     "no field '" << name << "' to keep");
  }
  const auto dropped = [&](const std::string& name) { return std::count(names.begin(), names.end(), name) == 0; };
  fields_.erase(std::remove_if(fields_.begin(), fields_.end(), [&](const Field& f) { return dropped(f.name); }),
                fields_.end());
  rules_.erase(std::remove_if(rules_.begin(), rules_.end(), [&](const Rule& r) { return dropped(r.field); }),
               rules_.end());
}

void OptionTableBase::RenameField(const std::string& from, const std::string& to) {
  const auto field = std::find_if(fields_.begin(), fields_.end(), [&](const Field& f) { return f.name == from; });
  HOILCD_CHECK_MSG(field != fields_.end(), "no field '" << from << "' to rename");
  HOILCD_CHECK_MSG(std::none_of(fields_.begin(), fields_.end(), [&](const Field& f) { return f.name == to; }),
                   "a field '" << to << "' already exists");
  field->name = to;
  for (Rule& r : rules_) {
    if (r.field == from) r.field = to;
  }
}

void OptionTableBase::ChangeDefault(const std::string& name, double default_value) {
  const auto field = std::find_if(fields_.begin(), fields_.end(), [&](const Field& f) { return f.name == name; });
  HOILCD_CHECK_MSG(
      field != fields_.end() && (field->kind == Field::Kind::kNumber || field->kind == Field::Kind::kInteger),
      "no number field '" << name << "'");
  HOILCD_CHECK_MSG(field->range.Contains(default_value), name << ": default " << default_value << " outside its range");
  HOILCD_CHECK_MSG(field->kind == Field::Kind::kNumber || default_value == std::floor(default_value),
                   name << ": default " << default_value << " is not a whole number");
  field->default_number = default_value;
}

void OptionTableBase::FillDefaultsOf(void* options) const {
  for (const Field& f : fields_) {
    switch (f.kind) {
      case Field::Kind::kNumber:
      case Field::Kind::kInteger:
        StoreNumber(f, options, f.default_number);
        break;
      case Field::Kind::kBoolean:
        *static_cast<bool*>(f.at(options)) = f.default_bool;
        break;
      case Field::Kind::kString:
        f.set_string(options, f.default_string);
        break;
      case Field::Kind::kExternal:
        break;
      case Field::Kind::kNested:
        f.nested->FillDefaultsOf(f.at(options));
        break;
    }
  }
}

json OptionTableBase::ToJsonOf(const void* options) const {
  json out = json::object();
  for (const Field& f : fields_) {
    switch (f.kind) {
      case Field::Kind::kNumber:
        out[f.name] = LoadNumber(f, options);
        break;
      case Field::Kind::kInteger:
        if (f.storage == Storage::kUint64) {
          out[f.name] = *static_cast<const uint64_t*>(f.at(Mutable(options)));
        } else {
          out[f.name] = *static_cast<const int*>(f.at(Mutable(options)));
        }
        break;
      case Field::Kind::kBoolean:
        out[f.name] = *static_cast<const bool*>(f.at(Mutable(options)));
        break;
      case Field::Kind::kString:
        out[f.name] = f.get_string(options);
        break;
      case Field::Kind::kExternal:
        break;
      case Field::Kind::kNested:
        out[f.name] = f.nested->ToJsonOf(f.at(Mutable(options)));
        break;
    }
  }
  return out;
}

void OptionTableBase::ReadInto(const json& object, const std::string& where, void* options,
                               ProblemCollector* problems) const {
  if (!object.is_object()) {
    problems->Add(where, "expected an object");
    return;
  }
  for (const auto& [key, value] : object.items()) {
    const std::string at = Join(where, JsonPointerToken(key));
    const auto field = std::find_if(fields_.begin(), fields_.end(),
                                    [&key = key](const Field& f) { return f.name == key && !f.code_only; });
    if (field == fields_.end()) {
      std::vector<std::string> names;
      for (const Field& f : fields_) {
        if (!f.code_only) names.push_back(f.name);
      }
      problems->Add(at, "unknown key '" + key + "' (expected one of: " + JoinChoices(names) + ")");
      continue;
    }
    const Field& f = *field;
    switch (f.kind) {
      case Field::Kind::kNumber:
        if (value.is_number()) {
          *static_cast<double*>(f.at(options)) = value.get<double>();
        } else {
          problems->Add(at, "expected a number");
        }
        break;
      case Field::Kind::kInteger: {
        // Compared as integers: through a double, 2^53 + 1 would pass as 2^53.
        const bool wide = f.storage == Storage::kUint64;
        const int64_t lowest = wide ? 0 : std::numeric_limits<int>::min();
        const int64_t highest = wide ? static_cast<int64_t>(kMaxExactInteger) : std::numeric_limits<int>::max();
        const bool in_range =
            value.is_number_unsigned()
                ? value.get<uint64_t>() <= static_cast<uint64_t>(highest)
                : value.is_number_integer() && value.get<int64_t>() >= lowest && value.get<int64_t>() <= highest;
        if (in_range) {
          StoreNumber(f, options, value.get<double>());
        } else {
          problems->Add(at, wide ? "expected a whole number, 0 or more" : "expected a whole number");
        }
        break;
      }
      case Field::Kind::kBoolean:
        if (value.is_boolean()) {
          *static_cast<bool*>(f.at(options)) = value.get<bool>();
        } else {
          problems->Add(at, "expected true or false");
        }
        break;
      case Field::Kind::kString:
        if (!value.is_string()) {
          problems->Add(at, "expected a string");
        } else if (!f.choices.empty() &&
                   std::count(f.choices.begin(), f.choices.end(), value.get<std::string>()) == 0) {
          problems->Add(at, "expected one of: " + JoinChoices(f.choices));
        } else {
          f.set_string(options, value.get<std::string>());
        }
        break;
      case Field::Kind::kExternal:
        break;
      case Field::Kind::kNested:
        f.nested->ReadInto(value, at, f.at(options), problems);
        break;
    }
  }
}

void OptionTableBase::CheckOf(const void* options, const std::string& where, ProblemCollector* problems) const {
  // The location is joined only for a problem: some callers check options once per pair.
  for (const Field& f : fields_) {
    switch (f.kind) {
      case Field::Kind::kNumber:
      case Field::Kind::kInteger: {
        const double value = LoadNumber(f, options);
        if (!f.range.Contains(value)) {
          problems->Add(Join(where, f.name), "must be " + f.range.ToString(f.unit) + " (got " + Number(value) + ")");
        }
        break;
      }
      case Field::Kind::kString: {
        if (f.choices.empty()) break;
        const std::string value = f.get_string(options);
        if (std::count(f.choices.begin(), f.choices.end(), value) == 0) {
          problems->Add(Join(where, f.name), "must be one of: " + JoinChoices(f.choices) + " (got '" + value + "')");
        }
        break;
      }
      case Field::Kind::kBoolean:
      case Field::Kind::kExternal:
        break;
      case Field::Kind::kNested:
        f.nested->CheckOf(f.at(Mutable(options)), Join(where, f.name), problems);
        break;
    }
  }
  for (const Rule& r : rules_) {
    if (std::string message = r.check(options); !message.empty()) problems->Add(Join(where, r.field), message);
  }
}

void OptionTableBase::SetOf(const std::string& name_equals_value, void* options) const {
  const size_t eq = name_equals_value.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError(name_equals_value, "NAME=VALUE");
  std::string name = name_equals_value.substr(0, eq);
  const std::string text = name_equals_value.substr(eq + 1);
  std::replace(name.begin(), name.end(), '.', '/');
  const OptionTableBase* table = this;
  void* target = options;
  for (;;) {
    const size_t slash = name.find('/');
    const std::string key = name.substr(0, slash);
    const auto field = std::find_if(table->fields_.begin(), table->fields_.end(),
                                    [&](const Field& f) { return f.name == key && f.kind != Field::Kind::kExternal; });
    if (field == table->fields_.end()) {
      std::string names;
      for (const OptionInfo& info : List()) {
        if (info.kind != OptionInfo::Kind::kExternal) names += (names.empty() ? "" : ", ") + info.name;
      }
      throw InputError(name_equals_value, "an option name (one of: " + names + ")");
    }
    const Field& f = *field;
    if (f.kind == Field::Kind::kNested) {
      if (slash == std::string::npos)
        throw InputError(name_equals_value, "a field of '" + key + "' (e.g. " + key + "/...)");
      table = f.nested.get();
      target = f.at(target);
      name = name.substr(slash + 1);
      continue;
    }
    if (slash != std::string::npos)
      throw InputError(name_equals_value, "no field after '" + key + "' (it is a value, not a group)");
    char* end = nullptr;
    switch (f.kind) {
      case Field::Kind::kNumber: {
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || !std::isfinite(value)) throw InputError(name_equals_value, "a number");
        StoreNumber(f, target, value);
        return;
      }
      case Field::Kind::kInteger: {
        const bool wide = f.storage == Storage::kUint64;
        const long long value = std::strtoll(text.c_str(), &end, 10);
        const long long lowest = wide ? 0 : std::numeric_limits<int>::min();
        const long long highest = wide ? static_cast<long long>(kMaxExactInteger) : std::numeric_limits<int>::max();
        if (text.empty() || *end != '\0' || value < lowest || value > highest) {
          throw InputError(name_equals_value, wide ? "a whole number, 0 or more" : "a whole number");
        }
        StoreNumber(f, target, static_cast<double>(value));
        return;
      }
      case Field::Kind::kBoolean:
        if (text != "true" && text != "false") throw InputError(name_equals_value, "true or false");
        *static_cast<bool*>(f.at(target)) = text == "true";
        return;
      case Field::Kind::kString:
        if (!f.choices.empty() && std::count(f.choices.begin(), f.choices.end(), text) == 0) {
          throw InputError(name_equals_value, "one of: " + JoinChoices(f.choices));
        }
        f.set_string(target, text);
        return;
      case Field::Kind::kExternal:
      case Field::Kind::kNested:
        return;  // excluded above
    }
  }
}

std::vector<OptionInfo> OptionTableBase::List() const {
  std::vector<OptionInfo> out;
  for (const Field& f : fields_) {
    if (f.kind == Field::Kind::kNested) {
      for (OptionInfo info : f.nested->List()) {
        info.name = f.name + "/" + info.name;
        out.push_back(std::move(info));
      }
      continue;
    }
    OptionInfo info;
    info.name = f.name;
    info.unit = f.unit;
    info.description = f.description;
    info.code_only = f.code_only;
    info.optional = f.optional;
    switch (f.kind) {
      case Field::Kind::kNumber:
        info.kind = OptionInfo::Kind::kNumber;
        info.default_json = json(f.default_number).dump();
        info.range = f.range;
        break;
      case Field::Kind::kInteger:
        info.kind = OptionInfo::Kind::kInteger;
        info.default_json = json(static_cast<long long>(f.default_number)).dump();
        info.range = f.range;
        break;
      case Field::Kind::kBoolean:
        info.kind = OptionInfo::Kind::kBoolean;
        info.default_json = f.default_bool ? "true" : "false";
        break;
      case Field::Kind::kString:
        info.kind = OptionInfo::Kind::kString;
        info.default_json = json(f.default_string).dump();
        info.choices = f.choices;
        break;
      case Field::Kind::kExternal:
      case Field::Kind::kNested:
        info.kind = OptionInfo::Kind::kExternal;
        break;
    }
    out.push_back(std::move(info));
  }
  return out;
}

std::string OptionRangeText(const OptionInfo& o) {
  if (o.kind == OptionInfo::Kind::kNumber || o.kind == OptionInfo::Kind::kInteger) return o.range.ToString(o.unit);
  if (!o.choices.empty()) return "one of: " + JoinChoices(o.choices);
  if (o.kind == OptionInfo::Kind::kBoolean) return "true or false";
  if (o.kind == OptionInfo::Kind::kExternal) return "(see the description)";
  return "";  // a string without choices
}

std::string FormatOptionList(const std::vector<OptionInfo>& options) {
  size_t name_width = 0, default_width = 0;
  for (const OptionInfo& o : options) {
    name_width = std::max(name_width, o.name.size());
    default_width = std::max(default_width, o.default_json.size());
  }
  std::ostringstream out;
  for (const OptionInfo& o : options) {
    out << std::left << std::setw(static_cast<int>(name_width)) << o.name << "  "
        << std::setw(static_cast<int>(default_width)) << o.default_json << "  " << OptionRangeText(o) << "  "
        << o.description << "\n";
  }
  return out.str();
}

std::string FormatOptionTableMarkdown(const std::vector<OptionInfo>& options) {
  const auto cell = [](std::string text) {
    for (size_t at = text.find('|'); at != std::string::npos; at = text.find('|', at + 2)) text.replace(at, 1, "\\|");
    return text;
  };
  std::ostringstream out;
  out << "| field | default | accepted | description |\n|---|---|---|---|\n";
  for (const OptionInfo& o : options) {
    if (o.code_only) continue;
    const bool shown = o.kind != OptionInfo::Kind::kExternal && !o.default_json.empty();
    const std::string default_text = shown ? "`" + o.default_json + "`" : "";
    const std::string accepted = OptionRangeText(o);
    out << "| `" << o.name << "` | " << cell(default_text) << " | " << cell(accepted.empty() ? "any text" : accepted)
        << " | " << cell(o.description) << " |\n";
  }
  return out.str();
}

}  // namespace hoilcd
