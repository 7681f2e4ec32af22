#include "hoilcd/core/text.h"

#include <cmath>
#include <cstdio>

namespace hoilcd {

std::string Fixed(double value, int digits) {
  if (!std::isfinite(value)) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, value);
  return buffer;
}

}  // namespace hoilcd
