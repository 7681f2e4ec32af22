// A method's own options, held by the method's folder and nowhere else: an options struct and its
// option table, behind one type-erased interface so the runner can set them from --param, check
// them and report their resolved values without knowing the struct. A method returns a fresh
// MethodOptions holding its defaults (LoopClosureMethod::Options) and reads its values back
// through MethodContext::Own<T>().
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

class MethodOptions {
 public:
  virtual ~MethodOptions() = default;
  virtual std::vector<OptionInfo> List() const = 0;  // every field a --param may set
  // Sets one field from "FIELD=VALUE"; throws InputError on an unknown field or a value of the
  // wrong type (call FirstProblem afterwards for ranges).
  virtual void Set(const std::string& field_equals_value) = 0;
  virtual std::string FirstProblem() const = 0;  // "" when every field is in range
  virtual nlohmann::json ToJson() const = 0;     // the resolved values, as the report prints them
};

// The options struct T with the table (a view of T's fields) that --param reaches. The table must
// outlive this (tables are function-local statics).
template <typename T>
class OptionsOf final : public MethodOptions {
 public:
  explicit OptionsOf(const OptionTable<T>& table) : table_(table) { table_.FillDefaults(&value_); }
  std::vector<OptionInfo> List() const override { return table_.List(); }
  void Set(const std::string& field_equals_value) override { table_.Set(field_equals_value, &value_); }
  std::string FirstProblem() const override { return table_.FirstProblem(value_); }
  nlohmann::json ToJson() const override { return table_.ToJson(value_); }
  const T& value() const { return value_; }

 private:
  const OptionTable<T>& table_;
  T value_;
};

// The T a method's options hold; HOILCD_CHECK when they hold another type (API misuse).
template <typename T>
const T& OptionsValue(const MethodOptions* options) {
  const auto* typed = dynamic_cast<const OptionsOf<T>*>(options);
  HOILCD_CHECK_MSG(typed != nullptr, "a method read options of a type it did not declare");
  return typed->value();
}

}  // namespace hoilcd
