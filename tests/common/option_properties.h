// Properties every options struct X with an option table has (X::Table(), X(), X::Check()):
// constructed, it holds each registered default and is valid; a value just outside any bounded
// field's range is the first problem Check() names, at that field.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

template <typename X>
void ExpectConstructedHoldsTheTableDefaults() {
  const X options;
  const nlohmann::json values = X::Table().ToJson(options);
  int compared = 0;
  for (const OptionInfo& info : X::Table().List()) {
    if (info.kind == OptionInfo::Kind::kExternal) continue;
    // As text: a NaN default (not set) is JSON null on both sides.
    EXPECT_EQ(values.at(nlohmann::json::json_pointer("/" + info.name)).dump(),
              nlohmann::json::parse(info.default_json).dump())
        << info.name;
    ++compared;
  }
  EXPECT_GT(compared, 0);
  EXPECT_EQ(options.Check(), "");
}

// Each bound of every number field, crossed by the least step (1 for whole numbers), in turn on a
// default X: Check() must report that field first. Returns how many bounds were crossed.
template <typename X>
int ExpectEveryBoundCrossedIsNamedByCheck() {
  int crossed = 0;
  for (const OptionInfo& info : X::Table().List()) {
    if (info.kind != OptionInfo::Kind::kNumber && info.kind != OptionInfo::Kind::kInteger) continue;
    const bool whole = info.kind == OptionInfo::Kind::kInteger;
    for (const auto& [bound, below] : {std::pair{info.range.min, true}, std::pair{info.range.max, false}}) {
      if (!bound) continue;
      double value = bound->value;
      if (!bound->exclusive) {
        value = whole ? value + (below ? -1 : 1) : std::nextafter(value, below ? -INFINITY : INFINITY);
      }
      char text[64];
      std::snprintf(text, sizeof(text), whole ? "%.0f" : "%.17g", value);
      X options;
      try {
        X::Table().Set(info.name + "=" + text, &options);
      } catch (const InputError&) {
        continue;  // the member's type cannot hold it (an unsigned field below 0)
      }
      EXPECT_EQ(options.Check().rfind(info.name + ": must be", 0), 0u)
          << info.name << "=" << text << " gave '" << options.Check() << "'";
      ++crossed;
    }
  }
  return crossed;
}

}  // namespace hoilcd
