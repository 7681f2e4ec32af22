#include "hoilcd/bench/realism/real_frames.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>
#include <utility>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "hoilcd/bench/evaluation/npy.h"
#include "hoilcd/bench/realism/flir_jpeg.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/safe_text.h"
#include "hoilcd/core/util/sizes.h"

namespace hoilcd {
namespace {

constexpr const char* kScaleHint =
    "give the camera's --scale and --offset (T[°C] = value * scale + offset; centikelvin: --scale 0.01 "
    "--offset -273.15)";

std::string Lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::string Extension(const std::string& name) { return Lower(std::filesystem::path(name).extension().string()); }

std::string Number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// Refuses a frame whose temperatures a camera cannot have seen: a wrong scale, offset or unit.
void CheckPlausible(const cv::Mat& temperature_c, const std::string& path, const std::string& how) {
  double lo = 0, hi = 0;
  cv::minMaxLoc(temperature_c, &lo, &hi);
  if (!(lo >= kMinPlausibleC && hi <= kMaxPlausibleC)) {
    throw InputError(path, "temperatures " + Number(lo) + " to " + Number(hi) + " °C (" + how + "): expected " +
                               Number(kMinPlausibleC) + " to " + Number(kMaxPlausibleC) +
                               " °C; is the scale, offset or unit right?");
  }
}

cv::Mat FromCounts(const cv::Mat& counts, const std::string& path, const RealFrameOptions& o) {
  if (std::isnan(o.scale) || std::isnan(o.offset_c)) {
    throw InputError(path, "a 16-bit frame holds counts, not temperatures: " + std::string(kScaleHint));
  }
  cv::Mat t;
  counts.convertTo(t, CV_32F, o.scale, o.offset_c);
  CheckPlausible(t, path, "scale " + Number(o.scale) + ", offset " + Number(o.offset_c));
  return t;
}

cv::Mat FromFloat(const cv::Mat& values, const std::string& path, const RealFrameOptions& o) {
  cv::Mat t;
  values.convertTo(t, CV_32F);
  for (int y = 0; y < t.rows; ++y) {
    for (int x = 0; x < t.cols; ++x) {
      if (!std::isfinite(t.at<float>(y, x))) {
        throw InputError(path, "element [" + std::to_string(y) + ", " + std::to_string(x) +
                                   "] is not finite: expected a temperature at every pixel");
      }
    }
  }
  std::string unit = o.float_unit;
  if (unit == "auto") {
    std::vector<float> v(t.begin<float>(), t.end<float>());
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    unit = v[v.size() / 2] > kKelvinAboveC ? "k" : "c";
  }
  if (unit == "k") t -= 273.15;
  CheckPlausible(t, path, unit == "k" ? "read as kelvin" : "read as °C");
  return t;
}

RealFrame ReadImage(const std::string& path, const std::string& bytes, const RealFrameOptions& o) {
  if (bytes.empty()) throw InputError(path, "is empty: expected a PNG, TIFF or JPEG image");
  const std::vector<uchar> buffer(bytes.begin(), bytes.end());
  cv::Mat image;
  try {
    image = cv::imdecode(buffer, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {  // a decoder's assertion on a malformed file
    throw InputError(path, "cannot decode (" + SafeText(e.err) + "): expected a PNG, TIFF or JPEG image");
  }
  if (image.empty()) throw InputError(path, "cannot decode: expected a PNG, TIFF or JPEG image");
  CheckRealFrameSize(image.rows, image.cols, path);
  RealFrame f;
  const int depth = image.depth();
  if (image.channels() != 1 && !(depth == CV_8U && (image.channels() == 3 || image.channels() == 4))) {
    throw InputError(path, std::to_string(image.channels()) + " channels of " +
                               (depth == CV_16U ? "16-bit" : "non-8-bit") +
                               " values: expected one channel (a radiometric frame) or 8-bit grey");
  }
  if (depth == CV_16U || depth == CV_16S) {
    f.radiometric = true;
    f.image = FromCounts(image, path, o);
  } else if (depth == CV_32F || depth == CV_64F) {
    f.radiometric = true;
    f.image = FromFloat(image, path, o);
  } else if (depth == CV_8U) {
    if (image.channels() == 1) {
      f.image = image;
    } else {
      cv::cvtColor(image, f.image, image.channels() == 3 ? cv::COLOR_BGR2GRAY : cv::COLOR_BGRA2GRAY);
    }
  } else {
    throw InputError(path, "pixel type " + std::to_string(depth) +
                               ": expected 8-bit grey, 16-bit counts or 32-bit float temperatures");
  }
  return f;
}

RealFrame ReadNpy(const std::string& path, const std::string& bytes, const RealFrameOptions& o) {
  const NpyHeader h = ParseNpyHeader(bytes, path);
  if (h.fortran_order != "False") {
    throw InputError(path, "fortran_order " + SafeText(h.fortran_order) + ": expected False (a C-order array)");
  }
  struct Dtype {
    const char* descr;
    int type;
    size_t bytes;
  };
  static const Dtype kDtypes[] = {
      {"<f4", CV_32F, 4}, {"<f8", CV_64F, 8}, {"<u2", CV_16U, 2}, {"<i2", CV_16S, 2}, {"|u1", CV_8U, 1}};
  const Dtype* dtype = nullptr;
  for (const Dtype& d : kDtypes) {
    if (h.descr == d.descr) dtype = &d;
  }
  if (dtype == nullptr) {
    throw InputError(path, "dtype " + SafeText(h.descr_as_written) +
                               ": expected float32 or float64 temperatures ('<f4', '<f8'), uint16 or int16 counts "
                               "('<u2', '<i2') or uint8 grey ('|u1')");
  }
  const bool one_channel = h.shape.size() == 3 && h.shape[2] == 1;
  if (!(h.shape.size() == 2 || one_channel)) {
    throw InputError(path, "shape " + SafeText(h.shape_as_written) + ": expected (height, width) of one frame");
  }
  CheckRealFrameSize(static_cast<int>(std::min<int64_t>(h.shape[0], kMaxImageSidePx + 1)),
                     static_cast<int>(std::min<int64_t>(h.shape[1], kMaxImageSidePx + 1)), path);
  const int rows = static_cast<int>(h.shape[0]), cols = static_cast<int>(h.shape[1]);
  const size_t body = static_cast<size_t>(rows) * static_cast<size_t>(cols) * dtype->bytes;
  if (bytes.size() - h.data_start != body) {
    throw InputError(path, "holds " + std::to_string(bytes.size() - h.data_start) + " data bytes: expected " +
                               std::to_string(body) + " for shape " + SafeText(h.shape_as_written) + " of " +
                               SafeText(h.descr_as_written));
  }
  cv::Mat values(rows, cols, dtype->type);
  std::memcpy(values.data, bytes.data() + h.data_start, body);  // little-endian host (x86-64, arm64)
  RealFrame f;
  if (dtype->type == CV_8U) {
    f.image = values;
  } else {
    f.radiometric = true;
    f.image = dtype->type == CV_32F || dtype->type == CV_64F ? FromFloat(values, path, o) : FromCounts(values, path, o);
  }
  return f;
}

// A .jpg or .jpeg: a FLIR radiometric JPEG's temperatures, any other JPEG's grey levels.
RealFrame ReadJpeg(const std::string& path, const std::string& bytes, const RealFrameOptions& o) {
  std::optional<cv::Mat> temperature_c = ReadFlirTemperatures(path, bytes);
  if (!temperature_c) return ReadImage(path, bytes, o);
  CheckPlausible(*temperature_c, path, "FLIR radiometric JPEG, with the file's emissivity and reflected temperature");
  RealFrame f;
  f.radiometric = true;
  f.image = std::move(*temperature_c);
  return f;
}

}  // namespace

void CheckRealFrameSize(int rows, int cols, const std::string& path) {
  if (rows < 16 || cols < 16 || rows > kMaxImageSidePx || cols > kMaxImageSidePx) {
    throw InputError(path, "frame of " + std::to_string(cols) + "x" + std::to_string(rows) + " px: expected 16 to " +
                               std::to_string(kMaxImageSidePx) + " px a side");
  }
}

std::string RealFrameOptions::Check() const {
  if (std::isnan(scale) != std::isnan(offset_c)) return "--scale and --offset: give both or neither";
  if (!std::isnan(scale) && !(std::isfinite(scale) && scale > 0 && scale <= 1)) {
    return "--scale " + Number(scale) + ": expected kelvin per count in (0, 1] (centikelvin: 0.01)";
  }
  if (!std::isnan(offset_c) && !(std::isfinite(offset_c) && std::fabs(offset_c) <= 1000)) {
    return "--offset " + Number(offset_c) + ": expected °C at count 0, within -1000..1000 (kelvin counts: -273.15)";
  }
  if (float_unit != "auto" && float_unit != "c" && float_unit != "k") {
    return "--float-unit " + SafeText(float_unit) + ": expected auto, c or k";
  }
  return "";
}

bool IsRealFrameFile(const std::string& name) {
  const std::string e = Extension(name);
  return e == ".png" || e == ".tif" || e == ".tiff" || e == ".npy" || e == ".jpg" || e == ".jpeg";
}

RealFrame ReadRealFrame(const std::string& path, const RealFrameOptions& options) {
  const std::string bytes = ReadFileBytes(path, kMaxRealFrameBytes);
  const std::string extension = Extension(path);
  RealFrame f = extension == ".npy"                           ? ReadNpy(path, bytes, options)
                : extension == ".jpg" || extension == ".jpeg" ? ReadJpeg(path, bytes, options)
                                                              : ReadImage(path, bytes, options);
  f.file = std::filesystem::path(path).filename().string();
  return f;
}

std::vector<std::string> ListRealFrames(const std::string& dir, std::vector<std::string>* skipped) {
  std::error_code ec;
  if (!std::filesystem::exists(dir, ec))
    throw InputError(dir, "no such folder: expected a folder of real thermal frames");
  if (!std::filesystem::is_directory(dir, ec))
    throw InputError(dir, "is a file: expected a folder of real thermal frames");
  std::vector<std::string> frames;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file(ec) && IsRealFrameFile(name)) {
      frames.push_back(name);
    } else if (skipped != nullptr) {
      skipped->push_back(name);
    }
  }
  if (ec) throw InputError(dir, "cannot list the folder: " + ec.message());
  if (frames.empty()) {
    throw InputError(
        dir, "holds no frame: expected .png or .tif/.tiff (16-bit radiometric or 8-bit), .npy, or .jpg/.jpeg files");
  }
  std::sort(frames.begin(), frames.end());
  if (skipped != nullptr) std::sort(skipped->begin(), skipped->end());
  return frames;
}

}  // namespace hoilcd
