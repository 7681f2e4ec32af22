// The folder `hoilcd realism -o DIR` writes: realism.json and realism.md (RealismComparison), and
// per statistic a PNG of both sides' histograms overlaid (histograms/<key>.png), every view and the
// views that are not blank side by side. And the synthetic side alone as an inspect section, in
// `hoilcd inspect` and every bench report.
#pragma once

#include <string>

#include <opencv2/core.hpp>

#include "hoilcd/bench/realism/realism.h"
#include "hoilcd/bench/report/inspect.h"

namespace hoilcd {

// InputError unless DIR may hold the realism output (output_folder.h: new, empty, or an earlier
// realism output, recognised by its realism.json); call it before the work.
void CheckRealismFolder(const std::string& dir);

// The histograms of one statistic, real and synthetic overlaid as densities, every view on the
// left and views that are not blank on the right. 8-bit BGR.
cv::Mat RealismHistogram(const StatisticRow& row);

// DIR/realism.json, DIR/realism.md, DIR/histograms/<key>.png; DIR created, checked as
// CheckRealismFolder does.
void WriteRealismFolder(const RealismComparison& comparison, const std::string& dir);

// "frame_statistics": the synthetic side of `hoilcd realism` on the frames inspect samples
// (SampledViewFrames): per statistic its median over every view and over views that are not
// blank, the blank share and the static pairs' temporal noise. Needs the radiometric or the
// thermal output.
InspectSection FrameStatisticsSection(const Dataset& dataset, int threads);

}  // namespace hoilcd
