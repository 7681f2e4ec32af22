#include "hoilcd/bench/realism/flir_jpeg.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>
#include <string_view>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "hoilcd/bench/realism/real_frames.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/safe_text.h"

// Hand-written: no Debian library reads FLIR's FFF record. Layout as ExifTool's FLIR.pm reads it.
namespace hoilcd {
namespace {

constexpr std::string_view kFlirMagic("FLIR\0", 5);  // opens the payload of each FLIR APP1 segment
constexpr size_t kChunkHeaderBytes = 8;              // the magic, a version byte, the chunk's index, the last index
constexpr std::string_view kFffMagic("FFF\0", 4);
constexpr size_t kFffHeaderBytes = 0x40;
constexpr size_t kEntryBytes = 0x20;  // one FFF directory entry
constexpr uint16_t kRawRecord = 0x01, kCameraInfoRecord = 0x20;
constexpr size_t kRawHeaderBytes = 0x20;    // before the image: byte-order mark, width, height
constexpr size_t kCameraInfoBytes = 0x310;  // up to the last field read, Planck R2
constexpr std::string_view kPngMagic("\x89PNG\r\n\x1a\n", 8);

std::string Number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string RecordName(uint16_t type) {
  std::ostringstream s;
  s << "FLIR record 0x" << std::hex << type;
  if (type == kRawRecord) s << " (raw thermal image)";
  if (type == kCameraInfoRecord) s << " (camera info)";
  return s.str();
}

// Integers and floats of one byte order from untrusted bytes. Callers check sizes before reading,
// so a read past the end is our bug, not the file's.
class ByteReader {
 public:
  ByteReader(std::string_view bytes, bool little_endian) : bytes_(bytes), little_endian_(little_endian) {}
  uint16_t U16(size_t at) const { return static_cast<uint16_t>(Unsigned(at, 2)); }
  uint32_t U32(size_t at) const { return Unsigned(at, 4); }
  int32_t I32(size_t at) const {
    const uint32_t u = U32(at);
    int32_t i = 0;
    std::memcpy(&i, &u, sizeof i);
    return i;
  }
  float F32(size_t at) const {
    const uint32_t u = U32(at);
    float f = 0;
    std::memcpy(&f, &u, sizeof f);
    return f;
  }

 private:
  uint32_t Unsigned(size_t at, size_t width) const {
    HOILCD_CHECK(at <= bytes_.size() && width <= bytes_.size() - at);
    uint32_t v = 0;
    for (size_t i = 0; i < width; ++i) {
      const uint32_t byte = static_cast<uint8_t>(bytes_[at + i]);
      v |= byte << (8 * (little_endian_ ? i : width - 1 - i));
    }
    return v;
  }
  std::string_view bytes_;
  bool little_endian_;
};

// FLIR records open with the uint16 2 in their own byte order (ExifTool's RawDataByteOrder).
bool LittleEndianRecord(std::string_view record) { return record.size() >= 2 && record[0] == 2 && record[1] == 0; }

// The FFF data: the payloads of the JPEG's APP1 "FLIR" segments joined in chunk order; nullopt for
// a JPEG without them or no JPEG.
std::optional<std::string> FlirData(const std::string& path, std::string_view jpeg) {
  const auto byte = [&](size_t at) { return static_cast<uint8_t>(jpeg[at]); };
  if (jpeg.size() < 4 || byte(0) != 0xFF || byte(1) != 0xD8) return std::nullopt;
  std::map<int, std::string_view> chunks;
  int last = -1;
  size_t at = 2;
  while (at + 4 <= jpeg.size() && byte(at) == 0xFF) {
    const uint8_t marker = byte(at + 1);
    if (marker == 0xFF) {  // fill byte
      ++at;
      continue;
    }
    if (marker == 0xDA || marker == 0xD9) break;                 // start of scan or end of image: the metadata is over
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {  // markers without a length
      at += 2;
      continue;
    }
    const size_t length = ByteReader(jpeg, false).U16(at + 2);
    const bool flir = marker == 0xE1 && jpeg.substr(at + 4, kFlirMagic.size()) == kFlirMagic;
    if (length < 2 || length > jpeg.size() - at - 2) {
      if (!flir && chunks.empty()) break;  // a broken JPEG without FLIR data: the image decoder judges it
      throw InputError(path, "JPEG segment at byte " + std::to_string(at) + " of " + std::to_string(length) +
                                 " bytes runs past the end of the file (" + std::to_string(jpeg.size()) +
                                 " bytes): expected whole FLIR APP1 segments");
    }
    if (flir) {
      const std::string_view payload = jpeg.substr(at + 4, length - 2);
      if (payload.size() < kChunkHeaderBytes) {
        throw InputError(path, "FLIR APP1 segment at byte " + std::to_string(at) + " holds " +
                                   std::to_string(payload.size()) + " bytes: expected at least " +
                                   std::to_string(kChunkHeaderBytes) + " (its chunk header)");
      }
      const int index = static_cast<uint8_t>(payload[6]), last_index = static_cast<uint8_t>(payload[7]);
      if (last != -1 && last_index != last) {
        throw InputError(path, "FLIR APP1 chunks give " + std::to_string(last) + " and " + std::to_string(last_index) +
                                   " as the last chunk's index: expected one FFF record");
      }
      last = last_index;
      if (index > last) {
        throw InputError(path, "FLIR APP1 chunk " + std::to_string(index) + " of 0.." + std::to_string(last) +
                                   ": expected an index up to the last");
      }
      if (!chunks.emplace(index, payload.substr(kChunkHeaderBytes)).second) {
        throw InputError(path, "FLIR APP1 chunk " + std::to_string(index) + " appears twice: expected each once");
      }
    }
    at += 2 + length;
  }
  if (chunks.empty()) return std::nullopt;
  std::string fff;
  for (int i = 0; i <= last; ++i) {
    const auto chunk = chunks.find(i);
    if (chunk == chunks.end()) {
      throw InputError(path, "FLIR APP1 chunk " + std::to_string(i) + " of 0.." + std::to_string(last) +
                                 " is missing: expected every chunk of the FFF record");
    }
    fff.append(chunk->second);
  }
  return fff;
}

struct FffRecords {
  std::string_view raw, camera_info;
};

// The raw-image and camera-info records of the FFF data, each bounds-checked.
FffRecords FindRecords(const std::string& path, std::string_view fff) {
  if (fff.size() < kFffHeaderBytes) {
    throw InputError(path, "FLIR FFF data is " + std::to_string(fff.size()) + " bytes: expected at least " +
                               std::to_string(kFffHeaderBytes) + " (its header)");
  }
  if (fff.substr(0, kFffMagic.size()) != kFffMagic) {
    throw InputError(path, "FLIR APP1 data does not open with \"FFF\\0\": expected an FFF record");
  }
  // The header's byte order is the one in which its version reads 100 to 199.
  const auto known = [](uint32_t version) { return version >= 100 && version < 200; };
  const bool little_endian = !known(ByteReader(fff, false).U32(0x14));
  const ByteReader header(fff, little_endian);
  if (!known(header.U32(0x14))) {
    throw InputError(path,
                     "FLIR FFF version " + std::to_string(ByteReader(fff, false).U32(0x14)) + ": expected 100 to 199");
  }
  const uint64_t directory = header.U32(0x18), entries = header.U32(0x1c);
  if (directory + entries * kEntryBytes > fff.size()) {
    throw InputError(path, "FLIR FFF directory of " + std::to_string(entries) + " entries at byte " +
                               std::to_string(directory) + " runs past the end of the FFF data (" +
                               std::to_string(fff.size()) + " bytes)");
  }
  FffRecords records;
  for (uint64_t e = 0; e < entries; ++e) {
    const size_t entry = directory + e * kEntryBytes;
    const uint16_t type = header.U16(entry);
    const uint64_t offset = header.U32(entry + 0x0c), length = header.U32(entry + 0x10);
    if (type == 0 || length == 0) continue;  // a free entry
    if (offset + length > fff.size()) {
      throw InputError(path, RecordName(type) + " at byte " + std::to_string(offset) + ", " + std::to_string(length) +
                                 " bytes, runs past the end of the FFF data (" + std::to_string(fff.size()) +
                                 " bytes)");
    }
    std::string_view* slot = type == kRawRecord          ? &records.raw
                             : type == kCameraInfoRecord ? &records.camera_info
                                                         : nullptr;
    if (slot != nullptr && slot->empty()) *slot = fff.substr(offset, length);
  }
  for (const uint16_t type : {kRawRecord, kCameraInfoRecord}) {
    if ((type == kRawRecord ? records.raw : records.camera_info).empty()) {
      throw InputError(path, "no " + RecordName(type) + ": expected one in the FFF directory");
    }
  }
  return records;
}

// The 16-bit PNG a raw record holds, its values in the record's byte order.
cv::Mat DecodePng(const std::string& path, std::string_view png, int rows, int cols, bool little_endian) {
  const std::string what = RecordName(kRawRecord);
  if (png.size() < 24 || png.substr(12, 4) != "IHDR") {
    throw InputError(path, what + " holds a PNG without its IHDR header: expected a 16-bit grey PNG");
  }
  const ByteReader ihdr(png, false);
  if (ihdr.U32(16) != static_cast<uint32_t>(cols) || ihdr.U32(20) != static_cast<uint32_t>(rows)) {
    throw InputError(path, what + " holds a PNG of " + std::to_string(ihdr.U32(16)) + "x" +
                               std::to_string(ihdr.U32(20)) + " px: expected the record's " + std::to_string(cols) +
                               "x" + std::to_string(rows));
  }
  const std::vector<uchar> buffer(png.begin(), png.end());
  cv::Mat raw;
  try {
    raw = cv::imdecode(buffer, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {  // a decoder's assertion on a malformed PNG
    throw InputError(path,
                     what + " holds a PNG that OpenCV refuses (" + SafeText(e.err) + "): expected a 16-bit grey PNG");
  }
  if (raw.type() != CV_16UC1 || raw.rows != rows || raw.cols != cols) {
    throw InputError(path, what + " holds a PNG that does not decode to " + std::to_string(cols) + "x" +
                               std::to_string(rows) + " px of one 16-bit channel: expected a 16-bit grey PNG");
  }
  // FLIR writes the PNG's values in the record's byte order, not PNG's big-endian one (ExifTool:
  // "most FLIR cameras using the PNG format seem to write the 16-bit raw image data in the wrong
  // byte order"); a big-endian record (the ThermaCAM EX320's) holds them the PNG way.
  if (little_endian) {
    for (auto it = raw.begin<uint16_t>(); it != raw.end<uint16_t>(); ++it) {
      *it = static_cast<uint16_t>((*it >> 8) | (*it << 8));
    }
  }
  return raw;
}

// The raw 16-bit thermal image of record 0x1: a PNG, or the values themselves.
cv::Mat RawImage(const std::string& path, std::string_view record) {
  const std::string what = RecordName(kRawRecord);
  if (record.size() < kRawHeaderBytes) {
    throw InputError(path, what + " is " + std::to_string(record.size()) + " bytes: expected at least " +
                               std::to_string(kRawHeaderBytes));
  }
  const bool little_endian = LittleEndianRecord(record);
  const ByteReader header(record, little_endian);
  const int cols = header.U16(2), rows = header.U16(4);
  CheckRealFrameSize(rows, cols, path);
  const std::string_view data = record.substr(kRawHeaderBytes);
  if (data.substr(0, kPngMagic.size()) == kPngMagic) return DecodePng(path, data, rows, cols, little_endian);
  const size_t expected = static_cast<size_t>(rows) * static_cast<size_t>(cols) * 2;
  if (data.size() != expected) {
    throw InputError(path, what + " holds " + std::to_string(data.size()) + " bytes of 16-bit values: expected " +
                               std::to_string(cols) + " x " + std::to_string(rows) +
                               " x 2 = " + std::to_string(expected) + " (or a PNG)");
  }
  cv::Mat raw(rows, cols, CV_16U);
  const ByteReader values(data, little_endian);
  size_t at = 0;
  for (auto it = raw.begin<uint16_t>(); it != raw.end<uint16_t>(); ++it, at += 2) *it = values.U16(at);
  return raw;
}

// The calibration of record 0x20, refused when a value cannot describe a camera.
FlirCalibration ReadCalibration(const std::string& path, std::string_view record) {
  const std::string what = RecordName(kCameraInfoRecord);
  if (record.size() < kCameraInfoBytes) {
    throw InputError(path, what + " is " + std::to_string(record.size()) + " bytes: expected at least " +
                               std::to_string(kCameraInfoBytes));
  }
  const ByteReader r(record, LittleEndianRecord(record));
  FlirCalibration c;
  c.emissivity = r.F32(0x20);
  c.reflected_temperature_k = r.F32(0x28);
  c.planck_r1 = r.F32(0x58);
  c.planck_b = r.F32(0x5c);
  c.planck_f = r.F32(0x60);
  c.planck_o = r.I32(0x308);
  c.planck_r2 = r.F32(0x30c);
  if (!(c.emissivity > 0 && c.emissivity <= 1)) {
    throw InputError(path, what + ": emissivity " + Number(c.emissivity) + ": expected above 0, at most 1");
  }
  const double min_k = kMinPlausibleC + 273.15, max_k = kMaxPlausibleC + 273.15;
  if (!(c.reflected_temperature_k >= min_k && c.reflected_temperature_k <= max_k)) {
    throw InputError(path, what + ": reflected temperature " + Number(c.reflected_temperature_k) + " K: expected " +
                               Number(min_k) + " to " + Number(max_k) + " K");
  }
  if (!(c.planck_r1 > 0 && c.planck_b > 0 && c.planck_r2 > 0 && std::isfinite(c.planck_r1) &&
        std::isfinite(c.planck_b) && std::isfinite(c.planck_r2) && std::isfinite(c.planck_f))) {
    throw InputError(path, what + ": Planck R1 " + Number(c.planck_r1) + ", B " + Number(c.planck_b) + ", F " +
                               Number(c.planck_f) + ", R2 " + Number(c.planck_r2) +
                               ": expected R1, B and R2 positive and every one finite");
  }
  return c;
}

}  // namespace

double FlirCalibration::TemperatureC(double raw) const {
  const double raw_reflected =
      planck_r1 / (planck_r2 * (std::exp(planck_b / reflected_temperature_k) - planck_f)) - planck_o;
  const double raw_object = (raw - (1 - emissivity) * raw_reflected) / emissivity;
  if (!(raw_object + planck_o > 0)) return NAN;  // no radiance: beyond the curve's asymptote
  const double temperature_k = planck_b / std::log(planck_r1 / (planck_r2 * (raw_object + planck_o)) + planck_f);
  return std::isfinite(temperature_k) && temperature_k > 0 ? temperature_k - 273.15 : NAN;
}

std::optional<cv::Mat> ReadFlirTemperatures(const std::string& path, const std::string& bytes) {
  const std::optional<std::string> fff = FlirData(path, bytes);
  if (!fff) return std::nullopt;
  const FffRecords records = FindRecords(path, *fff);
  const cv::Mat raw = RawImage(path, records.raw);
  const FlirCalibration c = ReadCalibration(path, records.camera_info);
  cv::Mat temperature_c(raw.size(), CV_32F);
  for (int y = 0; y < raw.rows; ++y) {
    for (int x = 0; x < raw.cols; ++x) {
      const uint16_t value = raw.at<uint16_t>(y, x);
      const double t = c.TemperatureC(value);
      if (!std::isfinite(t)) {
        throw InputError(path, "pixel [" + std::to_string(y) + ", " + std::to_string(x) + "] reads raw value " +
                                   std::to_string(value) + ", outside the Planck curve of the file's camera info (R1 " +
                                   Number(c.planck_r1) + ", B " + Number(c.planck_b) + ", F " + Number(c.planck_f) +
                                   ", O " + Number(c.planck_o) + ", R2 " + Number(c.planck_r2) + ", emissivity " +
                                   Number(c.emissivity) + "): expected a raw value that has a temperature");
      }
      // Within float's range, so that the cast is defined; the plausibility check refuses far less.
      const double limit = std::numeric_limits<float>::max();
      temperature_c.at<float>(y, x) = static_cast<float>(std::clamp(t, -limit, limit));
    }
  }
  return temperature_c;
}

}  // namespace hoilcd
