// Rendered frames against real ones (`hoilcd realism`): the per-frame statistics of a set of frames
// (a dataset's, or a folder of real frames), and per statistic the distance between two sets
// (Wasserstein-1 and the ratio of medians), over every view and over the views that are not blank.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/realism/frame_statistics.h"
#include "hoilcd/bench/realism/real_frames.h"
#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

// The frames of one side and their statistics.
struct FrameSet {
  std::string name;                         // "synthetic" or "real"
  std::string source;                       // the dataset folder or the real frames' folder
  std::vector<std::string> frames;          // a dataset's frame indices or the real files' names
  std::vector<FrameStatistics> statistics;  // parallel to frames
  std::vector<double> temporal_noise_k;     // one per static pair of consecutive frames
  std::vector<std::string> skipped;         // real folder: entries that are no frame file
  int Radiometric() const;
  int Blank() const;
};

// A dataset frame pair is static when the true camera moved less than this between them.
constexpr double kStaticMoveM = 0.002;
constexpr double kStaticTurnRad = 0.02 * M_PI / 180.0;

// Every `stride`-th frame from frame 0.
std::vector<int> StridedFrames(int frame_count, int stride);
// Whether frames `frame` and `frame` + 1 see a static view (kStaticMoveM, kStaticTurnRad).
bool IsStaticPair(const std::vector<PoseRecord>& poses, int frame);

// The synthetic side: `frames` of the dataset, from its radiometric output (temperature
// statistics) or else its 8-bit thermal output; temporal noise over each of them whose next frame
// is a static pair. On `threads` threads (0: every core); the same at any count.
FrameSet MeasureDatasetFrames(const Dataset& dataset, const std::vector<int>& frames, int threads);

// The real side: every frame file of `dir` (ListRealFrames), read with `options` (FLIR radiometric
// JPEGs with the calibration they carry, ReadRealFrame). With `static_sequence`, the folder is one
// static view in name order: temporal noise over each pair of consecutive radiometric frames of
// one size.
FrameSet MeasureRealFrames(const std::string& dir, const RealFrameOptions& options, bool static_sequence, int threads);

// W1 distance between two empirical distributions (the area between their CDFs); NaN if either is empty.
double Wasserstein1(std::vector<double> a, std::vector<double> b);

// One statistic's values on both sides and their distance.
struct SideSummary {
  int count = 0;
  double median = NAN, p25 = NAN, p75 = NAN;
};
struct StatisticComparison {
  SideSummary synthetic, real;
  double median_ratio = NAN;  // synthetic median / real median
  double wasserstein1 = NAN;
};
struct StatisticRow {
  std::string key, label, unit;
  std::vector<double> synthetic, real;  // every frame's (or pair's) value, NaN left out
  std::vector<double> synthetic_not_blank, real_not_blank;
  StatisticComparison all, not_blank;
};

struct RealismComparison {
  FrameSet synthetic, real;
  std::vector<StatisticRow> rows;  // FrameStatisticList() then temporal noise
  nlohmann::json ToJson() const;   // everything, per-frame values included
  std::string ToMarkdown() const;  // realism.md
};

// Every statistic of both sides. `real` may be empty (inspect and the bench report give the
// synthetic side alone): its summaries then count 0 and the distances are NaN.
RealismComparison CompareFrameSets(FrameSet synthetic, FrameSet real);

}  // namespace hoilcd
