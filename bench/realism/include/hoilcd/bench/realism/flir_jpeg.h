// Reading FLIR radiometric JPEGs, the format of most handheld thermal cameras: the JPEG's APP1
// "FLIR" segments carry an FFF record whose raw 16-bit thermal image and camera info (Planck
// constants, emissivity, reflected temperature) give each pixel's apparent temperature.
#pragma once

#include <optional>
#include <string>

#include <opencv2/core.hpp>

namespace hoilcd {

// What the camera-info record says about turning raw values into temperatures. The atmosphere is
// not modelled (transmission 1: handheld shots at a few metres).
struct FlirCalibration {
  double emissivity = 1;                    // of the object, as set on the camera
  double reflected_temperature_k = 293.15;  // reflected apparent temperature, K
  // FLIR's Planck constants: a black body at T [K] reads raw = R1 / (R2 (exp(B / T) - F)) - O.
  double planck_r1 = 0, planck_b = 0, planck_f = 1, planck_o = 0, planck_r2 = 1;
  // The apparent temperature of a pixel reading `raw`, °C; NaN when `raw` lies outside the
  // Planck curve (no temperature reads it).
  double TemperatureC(double raw) const;
};

// The apparent temperatures (CV_32F, °C) of the FLIR radiometric JPEG `bytes`, read from `path`;
// nullopt when `bytes` is a JPEG without FLIR APP1 segments or no JPEG. InputError(path, what was
// expected) for a missing chunk, a truncated or inconsistent FFF record, a frame of implausible
// size, or a raw value without a temperature.
std::optional<cv::Mat> ReadFlirTemperatures(const std::string& path, const std::string& bytes);

}  // namespace hoilcd
