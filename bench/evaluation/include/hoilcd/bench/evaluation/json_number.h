// The one JSON-number helper of the report files: JSON has no NaN or infinity, so a missing
// figure is written as null.
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>

namespace hoilcd {

// `value` as a JSON number, or null when it is not finite.
inline nlohmann::json JsonNumber(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace hoilcd
