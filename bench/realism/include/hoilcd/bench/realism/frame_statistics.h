// The statistics of one thermal frame that tell a rendered room from a real one (issue 43), the
// same on both sides of `hoilcd realism` and in every inspect and bench report: corner counts,
// strong edges, entropy and the spectrum's slope of the frame stretched from its 1st to its 99th
// percentile onto 0..255 and resized to 256x192, and, for radiometric frames, temperature
// percentiles, the wall high-pass residual and whether the view is blank.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace hoilcd {

// Every statistic is taken on a frame of this size, whatever the camera's.
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
  double spectrum_slope = NAN;        // log power vs log frequency, 1/64 to 1/4 cycles/px
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
// Temperatures (CV_32F °C, any size) resized the same way, CV_32F.
cv::Mat ResizedTemperatures(const cv::Mat& temperature_c);

// The statistics of an 8-bit stretched frame (StretchedFrame's output).
int ShiTomasiCorners(const cv::Mat& stretched_u8);
int SlcdCorners(const cv::Mat& stretched_u8);
int FastCorners(const cv::Mat& stretched_u8);
double StrongEdgeFraction(const cv::Mat& stretched_u8);
double EntropyBits(const cv::Mat& stretched_u8);
// Mean subtracted, |DFT|^2 averaged over rings 1/256 cycles/px wide, a least-squares line through
// (ln f, ln power) of the rings from 1/64 to 1/4 cycles/px; NaN for a flat frame.
double SpectrumSlope(const cv::Mat& stretched_u8);

// 15x15 median of CV_32F temperatures, borders replicated, exact on the values quantised to 0.01 K
// (Huang's sliding histogram: OpenCV's medianBlur takes only 8-bit images for windows over 5).
cv::Mat MedianFilter15(const cv::Mat& temperature_c);
// The std of T - MedianFilter15(T) over pixels within kWallBandK of T's median; NaN under 100 such
// pixels. `share`, when given, receives the share of such pixels.
double WallResidualK(const cv::Mat& temperature_c, double* share = nullptr);

// Every statistic of a frame: temperatures (CV_32F °C, any size; radiometric) or grey levels
// (CV_8U or CV_16U without a temperature scale).
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
