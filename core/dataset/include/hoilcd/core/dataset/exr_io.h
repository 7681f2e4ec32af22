// Multi-channel OpenEXR frames (T, T_true, Z, id, class) for the dataset folder: encoded in memory
// (for atomic writes and checksums) and read back as float images.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

// Named single-channel images of equal size.
using ExrChannels = std::vector<std::pair<std::string, cv::Mat>>;

// OpenEXR's lossless compressions (benchmarks/exr_png_bench.cpp measures them).
enum class ExrCompression { kNone, kRle, kZips, kZip, kPiz };

struct ExrWriteOptions {
  // The dataset's: RLE encodes a frame 4x faster than ZIP level 1 at 2.2x its size (docs/SPEC.md).
  ExrCompression compression = ExrCompression::kRle;
  int zip_level = 4;  // zlib level 1-9, for kZip and kZips (4: OpenEXR's default)
  // kRle: false lays the blocks out by hand (OpenEXR's own header, the same bytes, ~4x faster);
  // true has OpenEXR encode the pixels too (tests and exr_png_bench compare the two).
  bool openexr_rle = false;
};

// Encodes channels as an EXR in memory. The pixel type follows each image's type: CV_32F ->
// FLOAT, CV_16F -> HALF, CV_32S -> UINT holding the int32's bits (-1 is 4294967295).
std::string EncodeExr(const ExrChannels& channels, const ExrWriteOptions& options = {});

// A frame's channels as the dataset stores them (docs/SPEC.md): T and T_true float32 (°C), Z half
// (m), id and class uint (CV_32S images; -1, "nothing", is stored as 4294967295).
ExrChannels FrameExrChannels(const cv::Mat& temperature_c, const cv::Mat& ideal_c, const cv::Mat& depth_m,
                             const cv::Mat& instance, const cv::Mat& class_id);

// Reads every channel of an EXR frame of exactly `size` (the dataset's intrinsics) as CV_32F
// (UINT channels as the int32 EncodeExr wrote, so -1 reads back as -1);
// any other data window, or more channels than a frame can have, is an InputError naming the file
// (a crafted header cannot make the reader allocate more than one frame's channels).
ExrChannels ReadExr(const std::string& path, cv::Size size);
// The same for an EXR file's bytes already in memory; errors name `path`. With `only`, just those
// channels, in that order (a missing one is an InputError naming it): the others are not converted,
// which halves the time of a reader that needs two of a frame's five.
ExrChannels DecodeExr(const std::string& bytes, const std::string& path, cv::Size size,
                      const std::vector<std::string>& only = {});

// Frame `frame`'s EXR in a dataset folder (exr/NNNNNN.exr, read through Dataset::ReadFile), at the
// manifest's frame size; InputError naming the missing output when the dataset was rendered
// without EXRs.
ExrChannels ReadDatasetExr(const Dataset& dataset, int frame, const std::vector<std::string>& only = {});
// The path of that frame's EXR (DIR/exr/NNNNNN.exr), for messages.
std::string DatasetExrPath(const Dataset& dataset, int frame);
// The channel `name` of `channels`; InputError naming `path` and the channel when it is absent.
const cv::Mat& ExrChannel(const ExrChannels& channels, const std::string& name, const std::string& path);

}  // namespace hoilcd
