#include "hoilcd/core/util/text.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace hoilcd {

std::string Fixed(double value, int digits) {
  if (!std::isfinite(value)) return kMissingFigure;
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, value);
  return buffer;
}

std::string ShortestDouble(double value) {
  std::array<char, 32> buffer;
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

std::string CsvNumber(double value, int significant_digits) {
  if (!std::isfinite(value)) return "";
  if (significant_digits <= 0) return ShortestDouble(value);
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.*g", significant_digits, value);
  return buffer;
}

}  // namespace hoilcd
