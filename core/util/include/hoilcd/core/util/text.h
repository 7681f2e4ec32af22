// Number formatting shared by reports, sweeps and dataset files, defined once: fixed decimals
// for tables and prose, the shortest exact text for files, CSV fields.
#pragma once

#include <string>

namespace hoilcd {

// What every table and report shows for a missing figure.
inline constexpr char kMissingFigure[] = "-";

// `value` with `digits` decimals ("%.*f"); kMissingFigure when it is not finite.
std::string Fixed(double value, int digits = 3);

// The shortest decimal text that reads back as exactly the same double (std::to_chars).
std::string ShortestDouble(double value);

// A CSV field: "" when `value` is not finite (a missing figure), else ShortestDouble(value), or
// with significant_digits > 0 that many significant digits ("%.*g").
std::string CsvNumber(double value, int significant_digits = 0);

}  // namespace hoilcd
