// The JSON-number helpers of the report files: JSON has no NaN or infinity, so a missing figure
// is written as null and read back as NaN.
#pragma once

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

namespace hoilcd {

// `value` as a JSON number, or null when it is not finite.
inline nlohmann::json JsonNumber(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

// object[key] when it is a number, else NaN (a figure left out or written as null).
inline double JsonNumberOrNan(const nlohmann::json& object, const std::string& key) {
  const auto it = object.find(key);
  return it != object.end() && it->is_number() ? it->get<double>() : NAN;
}

}  // namespace hoilcd
