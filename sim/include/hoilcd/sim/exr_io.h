// Multi-channel float32 OpenEXR frames (T, T_true, Z, id, class) for the dataset folder.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "hoilcd/core/dataset.h"

namespace hoilcd {

// Named single-channel CV_32F images of equal size.
using ExrChannels = std::vector<std::pair<std::string, cv::Mat>>;

// Encodes channels as a ZIP-compressed float32 EXR in memory (for atomic writes and checksums).
std::string EncodeExr(const ExrChannels& channels);

// Reads every channel of an EXR frame of exactly `size` (the dataset's intrinsics) as CV_32F;
// any other data window, or more channels than a frame can have, is an InputError naming the file
// (a crafted header cannot make the reader allocate more than one frame's channels).
ExrChannels ReadExr(const std::string& path, cv::Size size);

// Frame `frame`'s EXR in a dataset folder (exr/NNNNNN.exr), at the manifest's frame size.
ExrChannels ReadDatasetExr(const Dataset& dataset, int frame);

}  // namespace hoilcd
