// Summary statistics of a list of numbers, defined once for the detector, the metrics, the
// dataset inspection and the sweep summary.
#pragma once

#include <vector>

namespace hoilcd {

// Arithmetic mean (values summed in order); NaN for no values.
double Mean(const std::vector<double>& values);

// Sample standard deviation (n - 1 in the denominator) about Mean(values); 0 for one value,
// NaN for none.
double StdDev(const std::vector<double>& values);

// The q-quantile (0 <= q <= 1) by linear interpolation between order statistics (numpy's
// default); NaN for no values.
double Quantile(std::vector<double> values, double q);

// The middle value, or the mean of the two middle values (Quantile(values, 0.5) up to rounding);
// NaN for no values.
double Median(std::vector<double> values);

}  // namespace hoilcd
