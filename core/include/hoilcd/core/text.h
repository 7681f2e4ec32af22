// Number formatting shared by reports, sweeps and dataset files, defined once: fixed decimals
// for tables and prose.
#pragma once

#include <string>

namespace hoilcd {

// `value` with `digits` decimals ("%.*f"); "-" when it is not finite (a missing figure).
std::string Fixed(double value, int digits = 3);

}  // namespace hoilcd
