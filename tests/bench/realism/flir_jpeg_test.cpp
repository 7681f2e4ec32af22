#include "hoilcd/bench/realism/flir_jpeg.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "hoilcd/bench/realism/real_frames.h"
#include "hoilcd/core/util/file_io.h"
#include "input_error_of.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

using test::InputErrorOf;
using test::TestDir;

// Linear_load's own camera info (tests/data/flir/README.md), for the synthetic files.
FlirCalibration LinearLoadCalibration() {
  FlirCalibration c;
  c.emissivity = 0.96f;
  c.reflected_temperature_k = 293.15f;
  c.planck_r1 = 14861.5595703125;
  c.planck_b = 1395.5999755859375;
  c.planck_f = 1.0;
  c.planck_o = -992;
  c.planck_r2 = 0.03233606740832329;
  return c;
}

// The raw value a pixel of an object at temperature_k with emissivity e reads (FlirCalibration's
// Planck curve, the reflection the rest), rounded as the camera stores it.
uint16_t RawOf(const FlirCalibration& c, double temperature_k) {
  const auto black_body = [&](double t_k) {
    return c.planck_r1 / (c.planck_r2 * (std::exp(c.planck_b / t_k) - c.planck_f)) - c.planck_o;
  };
  const double raw =
      c.emissivity * black_body(temperature_k) + (1 - c.emissivity) * black_body(c.reflected_temperature_k);
  return static_cast<uint16_t>(std::lround(raw));
}

// `value`'s `width` bytes at `at` of `bytes`, in one byte order; grows `bytes` as needed.
void Put(std::string* bytes, size_t at, uint64_t value, int width, bool little_endian) {
  if (bytes->size() < at + width) bytes->resize(at + width, '\0');
  for (int i = 0; i < width; ++i) {
    (*bytes)[at + (little_endian ? i : width - 1 - i)] = static_cast<char>((value >> (8 * i)) & 0xff);
  }
}

void PutFloat(std::string* bytes, size_t at, double value, bool little_endian) {
  const float f = static_cast<float>(value);
  uint32_t u = 0;
  std::memcpy(&u, &f, sizeof u);
  Put(bytes, at, u, 4, little_endian);
}

// A raw-image record (0x1) of `raw` (CV_16U): a 16-bit PNG holding the values in the record's byte
// order, as FLIR cameras write it, or the values themselves.
std::string RawRecord(const cv::Mat& raw, bool little_endian, bool png) {
  std::string r(32, '\0');
  Put(&r, 0, 2, 2, little_endian);
  Put(&r, 2, static_cast<uint64_t>(raw.cols), 2, little_endian);
  Put(&r, 4, static_cast<uint64_t>(raw.rows), 2, little_endian);
  if (png) {
    cv::Mat stored = raw.clone();
    if (little_endian) {
      for (auto it = stored.begin<uint16_t>(); it != stored.end<uint16_t>(); ++it) {
        *it = static_cast<uint16_t>((*it >> 8) | (*it << 8));
      }
    }
    std::vector<uchar> encoded;
    EXPECT_TRUE(cv::imencode(".png", stored, encoded));
    r.append(encoded.begin(), encoded.end());
  } else {
    for (auto it = raw.begin<uint16_t>(); it != raw.end<uint16_t>(); ++it) Put(&r, r.size(), *it, 2, little_endian);
  }
  return r;
}

// A camera-info record (0x20) of `c`, `bytes` long.
std::string CameraInfoRecord(const FlirCalibration& c, bool little_endian, size_t bytes = 0x310) {
  std::string r(0x310, '\0');
  Put(&r, 0, 2, 2, little_endian);
  PutFloat(&r, 0x20, c.emissivity, little_endian);
  PutFloat(&r, 0x28, c.reflected_temperature_k, little_endian);
  PutFloat(&r, 0x58, c.planck_r1, little_endian);
  PutFloat(&r, 0x5c, c.planck_b, little_endian);
  PutFloat(&r, 0x60, c.planck_f, little_endian);
  Put(&r, 0x308, static_cast<uint32_t>(static_cast<int32_t>(c.planck_o)), 4, little_endian);
  PutFloat(&r, 0x30c, c.planck_r2, little_endian);
  r.resize(bytes);
  return r;
}

// An FFF record: header, a directory of `records` (type, bytes), then the records in that order.
std::string Fff(const std::vector<std::pair<uint16_t, std::string>>& records) {
  std::string f("FFF\0", 4);
  Put(&f, 0x14, 100, 4, false);
  Put(&f, 0x18, 0x40, 4, false);
  Put(&f, 0x1c, records.size(), 4, false);
  f.resize(0x40 + 0x20 * records.size(), '\0');
  size_t offset = f.size();
  for (size_t i = 0; i < records.size(); ++i) {
    Put(&f, 0x40 + 0x20 * i, records[i].first, 2, false);
    Put(&f, 0x40 + 0x20 * i + 0x0c, offset, 4, false);
    Put(&f, 0x40 + 0x20 * i + 0x10, records[i].second.size(), 4, false);
    offset += records[i].second.size();
  }
  for (const auto& record : records) f += record.second;
  return f;
}

// An APP1 segment of `payload`.
std::string App1(const std::string& payload) {
  std::string segment("\xff\xe1", 2);
  Put(&segment, segment.size(), payload.size() + 2, 2, false);
  return segment + payload;
}

// The payload of FLIR chunk `index` of 0..`last`.
std::string Chunk(int index, int last, const std::string& data) {
  return std::string("FLIR\0\x01", 6) + static_cast<char>(index) + static_cast<char>(last) + data;
}

// A JPEG of `segments`, then a small grey picture.
std::string Jpeg(const std::string& segments) {
  std::vector<uchar> picture;
  EXPECT_TRUE(cv::imencode(".jpg", cv::Mat(24, 32, CV_8U, cv::Scalar(128)), picture));
  return std::string("\xff\xd8", 2) + segments + std::string(picture.begin() + 2, picture.end());
}

// A JPEG whose APP1 "FLIR" segments carry `fff` in chunks of `chunk_bytes`, leaving out chunk
// `missing` (-1: none).
std::string FlirJpeg(const std::string& fff, size_t chunk_bytes = 60000, int missing = -1) {
  const int chunks = static_cast<int>((fff.size() + chunk_bytes - 1) / chunk_bytes);
  std::string segments;
  for (int i = 0; i < chunks; ++i) {
    if (i != missing) segments += App1(Chunk(i, chunks - 1, fff.substr(i * chunk_bytes, chunk_bytes)));
  }
  return Jpeg(segments);
}

// 32 x 24 px of 15..45 °C, a ramp along x, as raw values of LinearLoadCalibration.
cv::Mat RampRaw(cv::Mat* temperature_c) {
  const FlirCalibration c = LinearLoadCalibration();
  cv::Mat raw(24, 32, CV_16U);
  temperature_c->create(24, 32, CV_32F);
  for (int y = 0; y < raw.rows; ++y) {
    for (int x = 0; x < raw.cols; ++x) {
      temperature_c->at<float>(y, x) = static_cast<float>(15 + 30.0 * x / (raw.cols - 1));
      raw.at<uint16_t>(y, x) = RawOf(c, temperature_c->at<float>(y, x) + 273.15);
    }
  }
  return raw;
}

std::string Write(const TestDir& dir, const std::string& name, const std::string& bytes) {
  std::ofstream(dir / name, std::ios::binary) << bytes;
  return dir / name;
}

double Median(const cv::Mat& values) {
  std::vector<float> v(values.begin<float>(), values.end<float>());
  std::sort(v.begin(), v.end());
  return v.size() % 2 == 1 ? v[v.size() / 2] : (static_cast<double>(v[v.size() / 2 - 1]) + v[v.size() / 2]) / 2;
}

TEST(FlirJpeg, LinearLoadMatchesThePythonReferenceConverterToAHundredthOfAKelvin) {
  const RealFrame f = ReadRealFrame(std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/flir/linear_load.jpg", {});
  ASSERT_TRUE(f.radiometric);
  ASSERT_EQ(f.image.type(), CV_32F);
  ASSERT_EQ(f.image.size(), cv::Size(120, 120));
  // From the Python reference converter, outside the repository (numpy, float64 then float32):
  // `flir_to_npy.py OUT "15 - Linear_load.jpg"`, the .npy's min, max, median and some pixels.
  double lo = 0, hi = 0;
  cv::minMaxLoc(f.image, &lo, &hi);
  EXPECT_NEAR(lo, 29.938461303710938, 0.01);
  EXPECT_NEAR(hi, 88.72039794921875, 0.01);
  EXPECT_NEAR(Median(f.image), 34.099212646484375, 0.01);
  EXPECT_NEAR(f.image.at<float>(84, 98), 29.938461303710938, 0.01);  // the coldest pixel
  EXPECT_NEAR(f.image.at<float>(63, 56), 88.72039794921875, 0.01);   // the hottest
  EXPECT_NEAR(f.image.at<float>(0, 0), 32.80978775024414, 0.01);
  EXPECT_NEAR(f.image.at<float>(0, 119), 31.63538932800293, 0.01);
  EXPECT_NEAR(f.image.at<float>(60, 60), 55.26992416381836, 0.01);
  EXPECT_NEAR(f.image.at<float>(119, 0), 34.12739181518555, 0.01);
  EXPECT_NEAR(f.image.at<float>(119, 119), 31.592193603515625, 0.01);
  EXPECT_NEAR(f.image.at<float>(30, 90), 34.28225326538086, 0.01);
}

TEST(FlirJpeg, AnObjectAtTheReflectedTemperatureReadsItWhateverItsEmissivity) {
  for (const double emissivity : {0.1, 0.5, 0.96, 1.0}) {
    FlirCalibration c = LinearLoadCalibration();
    c.emissivity = emissivity;
    const double raw =
        c.planck_r1 / (c.planck_r2 * (std::exp(c.planck_b / c.reflected_temperature_k) - c.planck_f)) - c.planck_o;
    EXPECT_NEAR(c.TemperatureC(raw), c.reflected_temperature_k - 273.15, 1e-9) << emissivity;
  }
}

TEST(FlirJpeg, SyntheticFilesReadBackTheirTemperaturesInEitherByteOrderAsPngOrRawValues) {
  const TestDir dir;
  cv::Mat expected;
  const cv::Mat raw = RampRaw(&expected);
  for (const bool little_endian : {true, false}) {
    for (const bool png : {true, false}) {
      const std::string fff = Fff({{0x22, std::string(100, 'p')},
                                   {0x01, RawRecord(raw, little_endian, png)},
                                   {0x20, CameraInfoRecord(LinearLoadCalibration(), little_endian)}});
      for (const size_t chunk_bytes : {size_t{60000}, size_t{500}}) {  // one chunk, several
        const std::string name = std::string(little_endian ? "le" : "be") + (png ? "_png" : "_raw") + "_" +
                                 std::to_string(chunk_bytes) + ".jpeg";
        const RealFrame f = ReadRealFrame(Write(dir, name, FlirJpeg(fff, chunk_bytes)), {});
        ASSERT_TRUE(f.radiometric) << name;
        cv::Mat difference;
        cv::absdiff(f.image, expected, difference);
        double worst = 0;
        cv::minMaxLoc(difference, nullptr, &worst);
        EXPECT_LT(worst, 0.02) << name;  // half a raw count is ~0.006 K here
      }
    }
  }
}

TEST(FlirJpeg, AJpegWithoutFlirSegmentsOrNoJpegIsNotFlir) {
  std::vector<uchar> plain;
  ASSERT_TRUE(cv::imencode(".jpg", cv::Mat(24, 32, CV_8U, cv::Scalar(128)), plain));
  EXPECT_FALSE(ReadFlirTemperatures("plain.jpg", std::string(plain.begin(), plain.end())));
  EXPECT_FALSE(ReadFlirTemperatures("empty.jpg", ""));
  EXPECT_FALSE(ReadFlirTemperatures("text.jpg", "FLIR FFF"));
}

// The message of fn's InputError holds every one of `parts`.
template <typename Fn>
void ExpectError(Fn fn, const std::vector<std::string>& parts) {
  const std::string message = InputErrorOf(fn);
  ASSERT_FALSE(message.empty()) << "no InputError; expected " << parts.front();
  for (const std::string& part : parts)
    EXPECT_NE(message.find(part), std::string::npos) << message << "\nlacks: " << part;
}

TEST(FlirJpeg, MalformedFilesAreInputErrorsNamingTheFileAndWhatWasExpected) {
  const TestDir dir;
  cv::Mat expected;
  const cv::Mat raw = RampRaw(&expected);
  const FlirCalibration c = LinearLoadCalibration();
  const std::string raw_record = RawRecord(raw, true, false), camera_info = CameraInfoRecord(c, true);
  const auto expect = [&](const std::string& name, const std::string& jpeg, const std::vector<std::string>& parts) {
    const std::string path = Write(dir, name, jpeg);
    std::vector<std::string> all = {path};
    all.insert(all.end(), parts.begin(), parts.end());
    ExpectError([&] { ReadRealFrame(path, {}); }, all);
  };
  const std::string good = Fff({{0x01, raw_record}, {0x20, camera_info}});

  const std::string fixture = ReadFileBytes(std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/flir/linear_load.jpg");
  expect("cut.jpg", fixture.substr(0, 10000), {"runs past the end of the file (10000 bytes)", "FLIR APP1"});
  expect("short_fff.jpg", FlirJpeg(good.substr(0, 40)), {"FLIR FFF data is 40 bytes: expected at least 64"});
  std::string no_magic = good;
  no_magic[0] = 'X';
  expect("no_magic.jpg", FlirJpeg(no_magic), {"does not open with \"FFF\\0\""});
  std::string version = good;
  Put(&version, 0x14, 7, 4, false);
  expect("version.jpg", FlirJpeg(version), {"FLIR FFF version 7: expected 100 to 199"});
  expect("cut_fff.jpg", FlirJpeg(good.substr(0, good.size() - 100)),
         {"FLIR record 0x20 (camera info) at byte", "runs past the end of the FFF data"});
  std::string far = good;
  Put(&far, 0x40 + 0x0c, 1u << 30, 4, false);
  expect("far.jpg", FlirJpeg(far),
         {"FLIR record 0x1 (raw thermal image) at byte 1073741824", "runs past the end of the FFF data"});
  std::string many = good;
  Put(&many, 0x1c, 1000000, 4, false);
  expect("directory.jpg", FlirJpeg(many), {"FLIR FFF directory of 1000000 entries at byte 64 runs past the end"});
  expect("missing_chunk.jpg", FlirJpeg(good, 500, 1), {"FLIR APP1 chunk 1 of 0..", "is missing"});
  expect("short_chunk.jpg", Jpeg(App1(std::string("FLIR\0\x01", 6))),
         {"FLIR APP1 segment at byte 2 holds 6 bytes: expected at least 8 (its chunk header)"});
  expect("two_lasts.jpg", Jpeg(App1(Chunk(0, 1, good)) + App1(Chunk(1, 2, ""))),
         {"FLIR APP1 chunks give 1 and 2 as the last chunk's index"});
  expect("beyond_last.jpg", Jpeg(App1(Chunk(2, 1, good))),
         {"FLIR APP1 chunk 2 of 0..1: expected an index up to the last"});
  expect("twice.jpg", Jpeg(App1(Chunk(0, 0, good)) + App1(Chunk(0, 0, good))), {"FLIR APP1 chunk 0 appears twice"});
  expect("no_raw.jpg", FlirJpeg(Fff({{0x20, camera_info}})), {"no FLIR record 0x1 (raw thermal image)"});
  expect("no_camera_info.jpg", FlirJpeg(Fff({{0x01, raw_record}})), {"no FLIR record 0x20 (camera info)"});
  expect("raw_size.jpg", FlirJpeg(Fff({{0x01, raw_record.substr(0, raw_record.size() - 2)}, {0x20, camera_info}})),
         {"FLIR record 0x1 (raw thermal image) holds 1534 bytes of 16-bit values: expected 32 x 24 x 2 = 1536"});
  expect("raw_header.jpg", FlirJpeg(Fff({{0x01, raw_record.substr(0, 10)}, {0x20, camera_info}})),
         {"FLIR record 0x1 (raw thermal image) is 10 bytes: expected at least 32"});
  expect("tiny.jpg", FlirJpeg(Fff({{0x01, RawRecord(raw(cv::Rect(0, 0, 8, 8)), true, false)}, {0x20, camera_info}})),
         {"frame of 8x8 px: expected 16 to"});
  std::string png_record = RawRecord(raw, true, true);
  Put(&png_record, 2, 30, 2, true);  // the record says 30 px wide, its PNG 32
  expect("png_size.jpg", FlirJpeg(Fff({{0x01, png_record}, {0x20, camera_info}})),
         {"holds a PNG of 32x24 px: expected the record's 30x24"});
  const std::string headless_png = raw_record.substr(0, 32) + "\x89PNG\r\n\x1a\n" + std::string(40, '\0');
  expect("headless_png.jpg", FlirJpeg(Fff({{0x01, headless_png}, {0x20, camera_info}})),
         {"holds a PNG without its IHDR header: expected a 16-bit grey PNG"});
  std::string broken_png = RawRecord(raw, true, true);
  broken_png.resize(broken_png.size() - 40);
  expect("broken_png.jpg", FlirJpeg(Fff({{0x01, broken_png}, {0x20, camera_info}})),
         {"holds a PNG that does not decode to 32x24 px of one 16-bit channel"});
  expect("camera_info.jpg", FlirJpeg(Fff({{0x01, raw_record}, {0x20, CameraInfoRecord(c, true, 200)}})),
         {"FLIR record 0x20 (camera info) is 200 bytes: expected at least 784"});
  FlirCalibration no_emissivity = c;
  no_emissivity.emissivity = 0;
  expect("emissivity.jpg", FlirJpeg(Fff({{0x01, raw_record}, {0x20, CameraInfoRecord(no_emissivity, true)}})),
         {"emissivity 0: expected above 0, at most 1"});
  FlirCalibration sun = c;
  sun.reflected_temperature_k = 5800;
  expect("reflected.jpg", FlirJpeg(Fff({{0x01, raw_record}, {0x20, CameraInfoRecord(sun, true)}})),
         {"FLIR record 0x20 (camera info): reflected temperature 5800 K: expected 173.15 to 1273.15 K"});
  FlirCalibration no_planck = c;
  no_planck.planck_r1 = 0;
  expect("planck.jpg", FlirJpeg(Fff({{0x01, raw_record}, {0x20, CameraInfoRecord(no_planck, true)}})),
         {"Planck R1 0, B 1395.6", "expected R1, B and R2 positive"});
  cv::Mat off_curve = raw.clone();
  off_curve.at<uint16_t>(3, 4) = 0;  // below -O: no radiance reads it
  expect("off_curve.jpg", FlirJpeg(Fff({{0x01, RawRecord(off_curve, true, true)}, {0x20, camera_info}})),
         {"pixel [3, 4] reads raw value 0, outside the Planck curve", "R1 14861.6", "O -992"});
  cv::Mat hot = raw.clone();
  hot.at<uint16_t>(3, 4) = 65535;
  FlirCalibration steep = c;
  steep.planck_r2 = 0.2;  // raw 65535 reads 1600 °C
  expect("hot.jpg", FlirJpeg(Fff({{0x01, RawRecord(hot, true, true)}, {0x20, CameraInfoRecord(steep, true)}})),
         {"°C (FLIR radiometric JPEG", "expected -100 to 1000 °C"});
}

}  // namespace
}  // namespace hoilcd
