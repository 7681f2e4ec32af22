// Physical constants shared by the simulator and the dataset format.
#pragma once

namespace hoilcd {

constexpr double kZeroCelsiusK = 273.15;  // 0 °C in kelvin

}  // namespace hoilcd
