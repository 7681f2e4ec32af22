#include "hoilcd/bench/realism/real_frames.h"

#include <cmath>
#include <cstring>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "input_error_of.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

using test::InputErrorOf;
using test::TestDir;

// 20..30 °C over the frame, in 0.01 K steps so that centikelvin holds it exactly.
cv::Mat Temperatures() {
  cv::Mat t(48, 64, CV_32F);
  for (int y = 0; y < t.rows; ++y)
    for (int x = 0; x < t.cols; ++x)
      t.at<float>(y, x) = static_cast<float>(std::round(2000 + 1000.0 * (y * 64 + x) / (48 * 64)) / 100);
  return t;
}

cv::Mat Centikelvin(const cv::Mat& t) {
  cv::Mat ck;
  t.convertTo(ck, CV_16U, 100.0, 27315.0);
  return ck;
}

// A .npy file of `values` with dtype `descr` and numpy's header, padded to 64 bytes.
void WriteNpy(const std::string& path, const std::string& descr, const std::string& shape, const void* data,
              size_t bytes) {
  std::string header = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': " + shape + ", }";
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::ofstream out(path, std::ios::binary);
  out.write("\x93NUMPY\x01\x00", 8);
  const char length[2] = {static_cast<char>(header.size() & 0xff), static_cast<char>(header.size() >> 8)};
  out.write(length, 2);
  out << header;
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
}

RealFrameOptions Centikelvins() {
  RealFrameOptions o;
  o.scale = 0.01;
  o.offset_c = -273.15;
  return o;
}

double MaxDifference(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat diff;
  cv::absdiff(a, b, diff);
  double lo = 0, hi = 0;
  cv::minMaxLoc(diff, &lo, &hi);
  return hi;
}

TEST(RealFrames, SixteenBitPngAndTiffRoundTripThroughScaleAndOffset) {
  const TestDir dir;
  const cv::Mat t = Temperatures();
  for (const std::string name : {"frame.png", "frame.tif", "frame.TIFF"}) {
    ASSERT_TRUE(cv::imwrite(dir / name, Centikelvin(t))) << name;
    const RealFrame f = ReadRealFrame(dir / name, Centikelvins());
    EXPECT_TRUE(f.radiometric) << name;
    EXPECT_EQ(f.file, name);
    EXPECT_LT(MaxDifference(f.image, t), 1e-3) << name;
  }
}

TEST(RealFrames, FloatTiffAndNpyRoundTripInCelsiusAndKelvin) {
  const TestDir dir;
  const cv::Mat t = Temperatures();
  ASSERT_TRUE(cv::imwrite(dir / "float.tiff", t));
  EXPECT_LT(MaxDifference(ReadRealFrame(dir / "float.tiff", {}).image, t), 1e-5);
  WriteNpy(dir / "c.npy", "<f4", "(48, 64)", t.data, t.total() * 4);
  EXPECT_LT(MaxDifference(ReadRealFrame(dir / "c.npy", {}).image, t), 1e-5);
  cv::Mat kelvin;
  t.convertTo(kelvin, CV_64F, 1.0, 273.15);
  WriteNpy(dir / "k.npy", "<f8", "(48, 64, 1)", kelvin.data, kelvin.total() * 8);
  EXPECT_LT(MaxDifference(ReadRealFrame(dir / "k.npy", {}).image, t), 1e-4);  // auto: kelvin
  RealFrameOptions celsius;
  celsius.float_unit = "c";
  cv::Mat kelvin_f32;
  kelvin.convertTo(kelvin_f32, CV_32F);
  EXPECT_LT(MaxDifference(ReadRealFrame(dir / "k.npy", celsius).image, kelvin_f32), 1e-4);  // as told
  RealFrameOptions in_kelvin;
  in_kelvin.float_unit = "k";
  EXPECT_NE(InputErrorOf([&] {
              ReadRealFrame(dir / "c.npy", in_kelvin);
            }).find("°C (read as kelvin): expected -100 to 1000 °C"),
            std::string::npos);
  const cv::Mat ck = Centikelvin(t);
  WriteNpy(dir / "counts.npy", "<u2", "(48, 64)", ck.data, ck.total() * 2);
  EXPECT_LT(MaxDifference(ReadRealFrame(dir / "counts.npy", Centikelvins()).image, t), 1e-3);
}

TEST(RealFrames, EightBitFramesAreGreyWithoutTemperatures) {
  const TestDir dir;
  cv::Mat grey(48, 64, CV_8U);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) grey.at<uint8_t>(y, x) = static_cast<uint8_t>(x * 4);
  ASSERT_TRUE(cv::imwrite(dir / "grey.png", grey));
  RealFrame f = ReadRealFrame(dir / "grey.png", {});
  EXPECT_FALSE(f.radiometric);
  EXPECT_EQ(MaxDifference(f.image, grey), 0);
  cv::Mat colour;
  cv::merge(std::vector<cv::Mat>{grey, grey, grey}, colour);
  ASSERT_TRUE(cv::imwrite(dir / "colour.png", colour));
  EXPECT_EQ(MaxDifference(ReadRealFrame(dir / "colour.png", {}).image, grey), 0);
  ASSERT_TRUE(cv::imwrite(dir / "photo.JPG", grey, {cv::IMWRITE_JPEG_QUALITY, 100}));
  f = ReadRealFrame(dir / "photo.JPG", {});
  EXPECT_FALSE(f.radiometric);
  EXPECT_LE(MaxDifference(f.image, grey), 3);
  WriteNpy(dir / "grey.npy", "|u1", "(48, 64)", grey.data, grey.total());
  EXPECT_EQ(MaxDifference(ReadRealFrame(dir / "grey.npy", {}).image, grey), 0);
}

// The message of fn's InputError holds every one of `parts`.
template <typename Fn>
void ExpectError(Fn fn, const std::vector<std::string>& parts) {
  const std::string message = InputErrorOf(fn);
  ASSERT_FALSE(message.empty()) << "no InputError; expected " << parts.front();
  for (const std::string& part : parts)
    EXPECT_NE(message.find(part), std::string::npos) << message << "\nlacks: " << part;
}

TEST(RealFrames, ErrorsNameTheFileAndWhatWasExpected) {
  const TestDir dir;
  const cv::Mat t = Temperatures();
  const std::string counts = dir / "counts.png";
  ASSERT_TRUE(cv::imwrite(counts, Centikelvin(t)));
  ExpectError([&] { ReadRealFrame(counts, {}); },
              {counts, "16-bit frame holds counts", "--scale 0.01 --offset -273.15"});
  RealFrameOptions raw;
  raw.scale = 1;
  raw.offset_c = 0;
  ExpectError([&] { ReadRealFrame(counts, raw); },
              {counts, "temperatures 29315", "scale 1, offset 0", "is the scale, offset or unit right?"});
  ExpectError([&] { ReadRealFrame(dir / "missing.png", {}); }, {dir / "missing.png"});
  std::ofstream(dir / "broken.png") << "not a png";
  ExpectError([&] { ReadRealFrame(dir / "broken.png", {}); },
              {dir / "broken.png", "cannot decode: expected a PNG, TIFF or JPEG"});
  const float values[4] = {20, 21, 22, 23};
  WriteNpy(dir / "complex.npy", "<c8", "(2, 1)", values, 16);
  ExpectError([&] { ReadRealFrame(dir / "complex.npy", {}); },
              {dir / "complex.npy", "dtype '<c8'", "expected float32 or float64"});
  cv::Mat big(48, 64, CV_32FC3, cv::Scalar(22, 22, 22));
  WriteNpy(dir / "rgb.npy", "<f4", "(48, 64, 3)", big.data, big.total() * 12);
  ExpectError([&] { ReadRealFrame(dir / "rgb.npy", {}); },
              {dir / "rgb.npy", "shape (48, 64, 3)", "expected (height, width)"});
  WriteNpy(dir / "short.npy", "<f4", "(48, 64)", t.data, 100);
  ExpectError([&] { ReadRealFrame(dir / "short.npy", {}); },
              {dir / "short.npy", "holds 100 data bytes: expected 12288"});
  cv::Mat with_nan = t.clone();
  with_nan.at<float>(3, 4) = NAN;
  WriteNpy(dir / "nan.npy", "<f4", "(48, 64)", with_nan.data, with_nan.total() * 4);
  ExpectError([&] { ReadRealFrame(dir / "nan.npy", {}); }, {dir / "nan.npy", "element [3, 4] is not finite"});
  std::ofstream(dir / "text.npy") << "hello";
  ExpectError([&] { ReadRealFrame(dir / "text.npy", {}); }, {dir / "text.npy", "expected a NumPy .npy file"});
  ASSERT_TRUE(cv::imwrite(dir / "tiny.png", cv::Mat(8, 8, CV_8U, cv::Scalar(0))));
  ExpectError([&] { ReadRealFrame(dir / "tiny.png", {}); }, {dir / "tiny.png", "frame of 8x8 px: expected 16 to"});
  // An empty image file (the fuzzer's crash: OpenCV's imdecode asserts on an empty buffer).
  for (const char* name : {"empty.png", "empty.tif", "empty.jpg", "empty.npy"}) {
    std::ofstream(dir / name).flush();
    ExpectError([&] { ReadRealFrame(dir / name, {}); }, {dir / name});
  }
  ExpectError([&] { ReadRealFrame(dir / "empty.jpg", {}); },
              {dir / "empty.jpg", "is empty: expected a PNG, TIFF or JPEG image"});
}

TEST(RealFrames, NonsenseScaleOffsetOrUnitIsRefusedNamingTheFlag) {
  RealFrameOptions o = Centikelvins();
  EXPECT_EQ(o.Check(), "");
  o.scale = -0.01;
  EXPECT_NE(o.Check().find("--scale -0.01: expected kelvin per count in (0, 1]"), std::string::npos);
  o.scale = 0;
  EXPECT_NE(o.Check().find("--scale 0:"), std::string::npos);
  o.scale = 5;
  EXPECT_NE(o.Check().find("--scale 5:"), std::string::npos);
  o = Centikelvins();
  o.offset_c = 1e9;
  EXPECT_NE(o.Check().find("--offset 1e+09:"), std::string::npos);
  o = RealFrameOptions();
  o.scale = 0.01;
  EXPECT_EQ(o.Check(), "--scale and --offset: give both or neither");
  o = RealFrameOptions();
  o.float_unit = "fahrenheit";
  EXPECT_EQ(o.Check(), "--float-unit fahrenheit: expected auto, c or k");
}

TEST(RealFrames, FolderListsFramesByNameAndRefusesAMissingOrEmptyOne) {
  const TestDir dir;
  ExpectError([&] { ListRealFrames(dir / "nowhere", nullptr); }, {dir / "nowhere", "no such folder"});
  ExpectError([&] { ListRealFrames(dir.str(), nullptr); }, {dir.str(), "holds no frame"});
  std::ofstream(dir / "SOURCES.txt") << "where they came from";
  ExpectError([&] { ListRealFrames(dir.str(), nullptr); }, {"holds no frame"});
  ExpectError([&] { ListRealFrames(dir / "SOURCES.txt", nullptr); }, {"is a file: expected a folder"});
  for (const char* name : {"b.png", "a.npy", "c.JPEG"}) std::ofstream(dir / name) << "x";
  std::vector<std::string> skipped;
  EXPECT_EQ(ListRealFrames(dir.str(), &skipped), (std::vector<std::string>{"a.npy", "b.png", "c.JPEG"}));
  EXPECT_EQ(skipped, std::vector<std::string>{"SOURCES.txt"});
}

}  // namespace
}  // namespace hoilcd
