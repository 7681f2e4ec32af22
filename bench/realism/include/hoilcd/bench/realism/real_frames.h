// Reading a folder of real thermal frames for `hoilcd realism`: 16-bit radiometric PNG or TIFF
// (with the camera's stated scale and offset), 32-bit float TIFF and .npy arrays of temperatures
// (°C or K), FLIR radiometric JPEGs (temperatures, flir_jpeg.h), and 8-bit PNG or other JPEG
// (grey levels only: no temperature statistics for those).
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace hoilcd {

// How raw values become temperatures. Defaults and ranges: Check() in real_frames.cpp. FLIR
// radiometric JPEGs carry their own calibration and ignore these.
struct RealFrameOptions {
  // 16-bit integer frames (PNG, TIFF, .npy uint16): T[°C] = value * scale + offset_c. NaN (the
  // default) refuses 16-bit frames, since a 16-bit file alone does not say its unit; hoilcd's own
  // centikelvin radiometric frames are scale 0.01, offset -273.15.
  double scale = NAN;     // K per count
  double offset_c = NAN;  // °C at count 0
  // Float frames (.npy float32/float64, 32-bit float TIFF): "c", "k", or "auto" (median above
  // kKelvinAboveC: kelvin, else °C).
  std::string float_unit = "auto";
  // "" when valid, else the first problem, naming the flag.
  std::string Check() const;
};

// Float frames whose median is above this are in kelvin (room scenes are 0-60 °C, 273-333 K).
constexpr double kKelvinAboveC = 150.0;
// Temperatures a thermal camera's frame may hold, °C; beyond them the scale or unit is wrong.
constexpr double kMinPlausibleC = -100.0, kMaxPlausibleC = 1000.0;
// The largest real frame file read, bytes.
constexpr uint64_t kMaxRealFrameBytes = uint64_t{1} << 28;

struct RealFrame {
  std::string file;  // name within the folder
  bool radiometric = false;
  cv::Mat image;  // CV_32F °C when radiometric, else CV_8U grey
};

// The frame in `path` by its extension (.png, .tif, .tiff, .npy, .jpg, .jpeg, any case); a JPEG
// with FLIR APP1 segments is radiometric, any other 8-bit grey. InputError(path, what was
// expected) for an unreadable file, a wrong dtype, shape or channel count, a 16-bit frame without
// a scale, a malformed FLIR record, or temperatures outside kMinPlausibleC..kMaxPlausibleC.
RealFrame ReadRealFrame(const std::string& path, const RealFrameOptions& options);

// InputError(path, ...) unless a frame of rows x cols px is 16 to kMaxImageSidePx px a side.
void CheckRealFrameSize(int rows, int cols, const std::string& path);

// Whether a file name has one of the extensions ReadRealFrame reads.
bool IsRealFrameFile(const std::string& name);

// The frame files of `dir` (not its subfolders), sorted by name, and the names of the other
// entries it skipped. InputError(dir, ...) when it is missing, no folder, or holds no frame file.
std::vector<std::string> ListRealFrames(const std::string& dir, std::vector<std::string>* skipped);

}  // namespace hoilcd
