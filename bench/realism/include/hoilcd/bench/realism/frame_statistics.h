// The statistics of one thermal frame that tell a rendered room from a real one (issue 43), the
// same on both sides of `hoilcd realism` and in every inspect and bench report. Each frame is
// stretched from its 1st to its 99th percentile onto 0..255. Which size each statistic sees:
// - corners, strong edges and entropy: the stretched frame resized (INTER_AREA) to 256x192, as are
//   the temperature percentiles, the wall residual and the temporal noise. Corner counts and edge
//   shares depend on the pixel count, and the wall residual's 15-px window on the pixel scale, so
//   one size keeps cameras comparable; upsampling a small frame adds no corners of its own.
// - the spectrum slope: the same resized frame when the camera's frame is at least 256x192 (the
//   reduction averages, as pixels do); a smaller frame's at its native size, because upsampling
//   removes power near 1/4 cycles per output pixel and steepens the slope (FLIR E40, 160x120:
//   -2.89 native, -3.55 upsampled; docs/results/2026-12-07-spectrum-slope.md, section 2).
// - the flat-region noise (flat_noise.h): always at native size, on the temperatures (grey levels
//   for an 8-bit frame), not stretched: noise correlation is a property of the camera's pixels.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace hoilcd {

// The image and temperature statistics are taken on a frame of this size, whatever the camera's
// (the spectrum slope and flat-region noise of a smaller frame excepted, see above).
constexpr int kStatisticsWidthPx = 256;
constexpr int kStatisticsHeightPx = 192;
// A view is blank when its radiometric p95 - p5 is below this.
constexpr double kBlankViewSpreadK = 2.0;
// Wall residual: pixels within this of the frame's median temperature, minus their 15x15 median.
constexpr double kWallBandK = 1.5;
constexpr int kWallMedianWindowPx = 15;
// A view is wall-dominated when at least this share of its pixels is within kWallBandK of its
// median: mostly wall, floor or ceiling, the views whose residual shows the walls' own detail.
constexpr double kWallDominatedShare = 0.8;

// One frame's statistics. Temperature figures are NaN for a frame without temperatures (8-bit).
struct FrameStatistics {
  double shi_tomasi_corners =
      NAN;                    // goodFeaturesToTrack: 1000 max, quality 0.01, distance 4, block 3, 4-px border masked
  double slcd_corners = NAN;  // the SLCD detector with its default KeypointOptions
  double fast_corners = NAN;  // cv::FAST, threshold 10, non-maximum suppression
  double strong_edge_fraction = NAN;  // share of pixels whose Sobel 3x3 magnitude / 8 exceeds 8 grey levels
  double entropy_bits = NAN;          // Shannon entropy of the 256-bin histogram
  double spectrum_slope = NAN;        // log power vs log frequency, 1/64 to 1/4 cycles/px (SpectrumFrame)
  double flat_noise_k = NAN;          // MeasureFlatNoise's std on the native temperatures, K; NaN for 8-bit frames
  double flat_noise_lag1 = NAN;       // MeasureFlatNoise's lag-1 correlation at native size (8-bit frames too)
  int width_px = 0, height_px = 0;    // the frame's native size, as the camera gave it
  bool radiometric = false;           // the frame held temperatures
  double p1_c = NAN, p5_c = NAN, p50_c = NAN, p95_c = NAN, p99_c = NAN;  // temperature percentiles, °C
  double spread_k = NAN;                                                 // p95 - p5
  double wall_residual_k = NAN;  // std of T - median15(T) over pixels within kWallBandK of the median
  double wall_share = NAN;       // share of pixels within kWallBandK of the median
  bool wall_dominated = false;   // wall_share >= kWallDominatedShare
  bool blank = false;            // radiometric and spread_k < kBlankViewSpreadK
};

// `frame` (one channel: CV_32F or CV_64F temperatures, or CV_8U/CV_16U grey levels) stretched from
// its 1st to its 99th percentile onto 0..255 (clamped) and resized (INTER_AREA) to 256x192, CV_8U.
// A frame whose p99 equals its p1 comes out black.
cv::Mat StretchedFrame(const cv::Mat& frame);
// The same stretch at the frame's native size, CV_8U.
cv::Mat NativeStretchedFrame(const cv::Mat& frame);
// Whether resizing a frame of `size` to 256x192 would upsample it (narrower or shorter).
bool SmallerThanStatisticsSize(cv::Size size);
// The frame SpectrumSlope is measured on: NativeStretchedFrame for a frame smaller than 256x192 in
// either dimension, StretchedFrame for any other.
cv::Mat SpectrumFrame(const cv::Mat& frame);
// Temperatures (CV_32F °C, any size) resized the same way, CV_32F.
cv::Mat ResizedTemperatures(const cv::Mat& temperature_c);

// The statistics of an 8-bit stretched frame (StretchedFrame's output).
int ShiTomasiCorners(const cv::Mat& stretched_u8);
int SlcdCorners(const cv::Mat& stretched_u8);
int FastCorners(const cv::Mat& stretched_u8);
double StrongEdgeFraction(const cv::Mat& stretched_u8);
double EntropyBits(const cv::Mat& stretched_u8);
// Mean subtracted, |DFT|^2 averaged over rings 1/256 cycles/px wide, a least-squares line through
// (ln f, ln power) of the rings from 1/64 to 1/4 cycles/px; NaN for a flat frame. Any size: the
// frequencies are in cycles per pixel along each axis, rings no frequency falls in are left out.
double SpectrumSlope(const cv::Mat& stretched_u8);

// 15x15 median of CV_32F temperatures, borders replicated, exact on the values quantised to 0.01 K
// (Huang's sliding histogram: OpenCV's medianBlur takes only 8-bit images for windows over 5).
cv::Mat MedianFilter15(const cv::Mat& temperature_c);
// The std of T - MedianFilter15(T) over pixels within kWallBandK of T's median; NaN under 100 such
// pixels. `share`, when given, receives the share of such pixels.
double WallResidualK(const cv::Mat& temperature_c, double* share = nullptr);

// Every statistic of a frame at its native size (the sizes each sees: the header's comment):
// temperatures (CV_32F °C; radiometric) or grey levels (CV_8U or CV_16U without a temperature scale).
FrameStatistics MeasureTemperatureFrame(const cv::Mat& temperature_c);
FrameStatistics MeasureGreyFrame(const cv::Mat& grey);

// Temporal noise between two temperature frames of a static view, K: the frames resized to
// 256x192, 1.4826 x the median absolute deviation of their difference / sqrt(2) (robust to the
// few pixels where something moved).
double TemporalNoiseK(const cv::Mat& first_c, const cv::Mat& second_c);

// A statistic by name, for tables and histograms.
struct StatisticInfo {
  std::string key;    // JSON key, with its unit
  std::string label;  // for people
  std::string unit;   // "", "K", "°C", "bits"
  bool needs_temperature = false;
  double (*value)(const FrameStatistics&) = nullptr;
};
// Every per-frame statistic, in report order.
const std::vector<StatisticInfo>& FrameStatisticList();

}  // namespace hoilcd
