#include "hoilcd/core/util/png.h"

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/geometry/camera.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"

namespace hoilcd {
namespace {

cv::Mat OpenCvDecode(const std::string& bytes) {
  return cv::imdecode(std::vector<uchar>(bytes.begin(), bytes.end()), cv::IMREAD_UNCHANGED);
}

bool Same(const cv::Mat& a, const cv::Mat& b) {
  return a.type() == b.type() && a.size() == b.size() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

// Random pixels, or a smooth ramp with a little noise (like a thermal frame).
cv::Mat TestImage(int rows, int cols, int type, bool smooth, uint64_t seed) {
  cv::Mat image(rows, cols, type);
  cv::RNG rng(seed);
  const double top = type == CV_16UC1 ? 65535 : 255;
  for (int y = 0; y < rows; ++y) {
    for (int x = 0; x < cols; ++x) {
      const double v = smooth ? top * 0.3 + 40 * x + 25 * y + rng.uniform(-3, 4) : rng.uniform(0.0, top + 1);
      if (type == CV_16UC1)
        image.at<uint16_t>(y, x) = cv::saturate_cast<uint16_t>(v);
      else
        image.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(v);
    }
  }
  return image;
}

// An independent PNG writer for the decoder's tests: any filter per row (cycling through `filters`),
// any interlace byte, extra chunks, and a zlib stream of stored (uncompressed) deflate blocks, with
// its own CRC-32 and Adler-32. OpenCV's libpng reading its files back checks the writer itself.
class TestPngWriter {
 public:
  std::vector<int> filters = {0};
  int interlace = 0;
  std::vector<std::pair<std::string, std::string>> extra_chunks;  // written after IHDR
  int idat_chunks = 1;
  std::string zlib_header = "\x78\x01";  // a 32 kB window
  std::string after_checksum;            // bytes after the zlib stream, inside the IDAT data

  std::string Write(const cv::Mat& image) const {
    const int bpp = image.depth() == CV_16U ? 2 : 1;
    const size_t stride = static_cast<size_t>(image.cols) * bpp;
    std::string raw;
    std::vector<unsigned char> previous(stride, 0), row(stride);
    for (int y = 0; y < image.rows; ++y) {
      for (int x = 0; x < image.cols; ++x) {
        if (bpp == 2) {
          const uint16_t v = image.at<uint16_t>(y, x);
          row[2 * x] = static_cast<unsigned char>(v >> 8), row[2 * x + 1] = static_cast<unsigned char>(v);
        } else {
          row[x] = image.at<uint8_t>(y, x);
        }
      }
      const int filter = filters[static_cast<size_t>(y) % filters.size()];
      raw += static_cast<char>(filter);
      for (size_t i = 0; i < stride; ++i) {
        const int a = i >= static_cast<size_t>(bpp) ? row[i - bpp] : 0, b = previous[i];
        const int c = i >= static_cast<size_t>(bpp) ? previous[i - bpp] : 0;
        int predictor = 0;
        if (filter == 1) predictor = a;
        if (filter == 2) predictor = b;
        if (filter == 3) predictor = (a + b) / 2;
        if (filter == 4) {
          const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
          predictor = pa <= pb && pa <= pc ? a : (pb <= pc ? b : c);
        }
        raw += static_cast<char>((row[i] - predictor) & 0xff);
      }
      previous = row;
    }
    std::string zlib = zlib_header;
    for (size_t at = 0; at < raw.size() || at == 0; at += 65535) {
      const size_t n = std::min<size_t>(65535, raw.size() - at);
      zlib += static_cast<char>(at + n >= raw.size() ? 1 : 0);
      zlib += static_cast<char>(n & 0xff), zlib += static_cast<char>(n >> 8);
      zlib += static_cast<char>(~n & 0xff), zlib += static_cast<char>((~n >> 8) & 0xff);
      zlib += raw.substr(at, n);
    }
    uint32_t s1 = 1, s2 = 0;
    for (unsigned char ch : raw) s1 = (s1 + ch) % 65521, s2 = (s2 + s1) % 65521;
    zlib += BigEndian((s2 << 16) | s1) + after_checksum;

    std::string png("\x89PNG\r\n\x1a\n", 8);
    std::string ihdr = BigEndian(image.cols) + BigEndian(image.rows);
    ihdr += static_cast<char>(8 * bpp), ihdr += '\0', ihdr += '\0', ihdr += '\0', ihdr += static_cast<char>(interlace);
    png += Chunk("IHDR", ihdr);
    for (const auto& [type, data] : extra_chunks) png += Chunk(type, data);
    const size_t part = (zlib.size() + idat_chunks - 1) / idat_chunks;
    for (int i = 0; i < idat_chunks; ++i) png += Chunk("IDAT", zlib.substr(i * part, part));
    return png + Chunk("IEND", "");
  }

 private:
  static std::string BigEndian(uint32_t v) {
    return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
  }
  static std::string Chunk(const std::string& type, const std::string& data) {
    const std::string body = type + data;
    uint32_t crc = 0xffffffffu;
    for (unsigned char ch : body) {
      crc ^= ch;
      for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return BigEndian(static_cast<uint32_t>(data.size())) + body + BigEndian(~crc);
  }
};

TEST(GreyPng, RoundTripsEveryDepthAndSizeAndOpenCvReadsTheSamePixels) {
  for (int type : {CV_8UC1, CV_16UC1}) {
    for (const cv::Size size : {cv::Size(1, 1), cv::Size(3, 1), cv::Size(1, 5), cv::Size(7, 5), cv::Size(256, 192)}) {
      for (bool smooth : {false, true}) {
        const cv::Mat image = TestImage(size.height, size.width, type, smooth, 7 * size.area() + type);
        const std::string bytes = EncodeGreyPng(image);
        EXPECT_EQ(bytes, EncodeGreyPng(image.clone()));
        cv::Mat back;
        ASSERT_TRUE(DecodeGreyPng(bytes, size.width, size.height, type, &back)) << size << " type " << type;
        EXPECT_TRUE(Same(back, image)) << size << " type " << type;
        EXPECT_TRUE(Same(OpenCvDecode(bytes), image)) << size << " type " << type;
      }
    }
  }
}

TEST(GreyPng, AFrameIsCompressedAboutAsWellAsOpenCvsDefault) {
  for (int type : {CV_8UC1, CV_16UC1}) {
    const cv::Mat frame = TestImage(192, 256, type, true, 11);
    std::vector<uchar> opencv;
    ASSERT_TRUE(cv::imencode(".png", frame, opencv));
    EXPECT_LT(EncodeGreyPng(frame).size(), opencv.size() * 1.25) << "type " << type;
  }
}

TEST(GreyPng, DecodesEveryRowFilterAndSplitIdatAsLibpngDoes) {
  TestPngWriter writer;
  writer.filters = {0, 1, 2, 3, 4, 4, 3, 2, 1};
  writer.idat_chunks = 3;
  for (int type : {CV_8UC1, CV_16UC1}) {
    for (bool smooth : {false, true}) {
      const cv::Mat image = TestImage(23, 17, type, smooth, 5 + type);
      const std::string bytes = writer.Write(image);
      ASSERT_TRUE(Same(OpenCvDecode(bytes), image)) << "the test's own writer is wrong";
      cv::Mat back;
      ASSERT_TRUE(DecodeGreyPng(bytes, 17, 23, type, &back));
      EXPECT_TRUE(Same(back, image)) << "type " << type << " smooth " << smooth;
    }
  }
  // OpenCV's own files (several IDAT chunks, libpng's choice of filters) decode the same way.
  const cv::Mat frame = TestImage(192, 256, CV_16UC1, true, 3);
  std::vector<uchar> opencv;
  ASSERT_TRUE(cv::imencode(".png", frame, opencv));
  cv::Mat back;
  ASSERT_TRUE(DecodeGreyPng(std::string(opencv.begin(), opencv.end()), 256, 192, CV_16UC1, &back));
  EXPECT_TRUE(Same(back, frame));
}

TEST(GreyPng, EveryFlippedBitAndEveryCutIsRefused) {
  const cv::Mat image = TestImage(6, 8, CV_16UC1, false, 1);
  const std::string bytes = EncodeGreyPng(image);
  cv::Mat untouched(1, 1, CV_8UC1, cv::Scalar(42));
  for (size_t i = 0; i < bytes.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      std::string damaged = bytes;
      damaged[i] = static_cast<char>(damaged[i] ^ (1 << bit));
      EXPECT_FALSE(DecodeGreyPng(damaged, 8, 6, CV_16UC1, &untouched)) << "byte " << i << " bit " << bit;
    }
  }
  for (size_t length = 0; length < bytes.size(); ++length) {
    EXPECT_FALSE(DecodeGreyPng(bytes.substr(0, length), 8, 6, CV_16UC1, &untouched)) << length;
  }
  EXPECT_EQ(untouched.at<uint8_t>(0, 0), 42);
}

// Anything but the frames' own layout is left to OpenCV, and DecodeFramePng reads it all the same.
TEST(GreyPng, OtherSizesDepthsInterlacingAndChunksAreLeftToOpenCv) {
  const cv::Mat image = TestImage(6, 8, CV_8UC1, true, 2);
  cv::Mat out;
  EXPECT_FALSE(DecodeGreyPng(EncodeGreyPng(image), 8, 7, CV_8UC1, &out));
  EXPECT_FALSE(DecodeGreyPng(EncodeGreyPng(image), 9, 6, CV_8UC1, &out));
  EXPECT_FALSE(DecodeGreyPng(EncodeGreyPng(image), 8, 6, CV_16UC1, &out));
  EXPECT_FALSE(DecodeGreyPng(EncodeGreyPng(image), 8, 6, CV_32FC1, &out));
  TestPngWriter with_text;
  with_text.extra_chunks = {{"tEXt", std::string("Comment\0hello", 13)}};
  TestPngWriter interlaced;  // only the interlace byte: the rows are not Adam7 passes
  interlaced.interlace = 1;
  const std::string text_png = with_text.Write(image);
  EXPECT_FALSE(DecodeGreyPng(text_png, 8, 6, CV_8UC1, &out));
  EXPECT_FALSE(DecodeGreyPng(interlaced.Write(image), 8, 6, CV_8UC1, &out));
  EXPECT_TRUE(out.empty());
  // zlib streams libdeflate would read but zlib might not: a window under 32 kB (zlib enforces
  // it, libdeflate does not), bytes after the checksum.
  TestPngWriter small_window, trailing;
  small_window.zlib_header = "\x28\x15";  // CINFO 2: a 1 kB window (stored blocks fit any window)
  trailing.after_checksum = "junk";
  const std::string small_window_png = small_window.Write(image);
  EXPECT_FALSE(DecodeGreyPng(small_window_png, 8, 6, CV_8UC1, &out));
  EXPECT_FALSE(DecodeGreyPng(trailing.Write(image), 8, 6, CV_8UC1, &out));
  EXPECT_TRUE(out.empty());
  const CameraIntrinsics k = CameraIntrinsics::FromHorizontalFov(8, 6, 50);
  EXPECT_TRUE(Same(DecodeFramePng(text_png, "text.png", CV_8UC1, k), image));
  EXPECT_TRUE(Same(DecodeFramePng(small_window_png, "window.png", CV_8UC1, k), image));
}

TEST(GreyPng, EncodePngSendsGreyFramesHereAndColourToOpenCv) {
  const cv::Mat grey = TestImage(6, 8, CV_16UC1, true, 4);
  EXPECT_EQ(EncodePng(grey), EncodeGreyPng(grey));
  cv::Mat colour(6, 8, CV_8UC3, cv::Scalar(10, 20, 30));
  EXPECT_TRUE(Same(OpenCvDecode(EncodePng(colour)), colour));
  EXPECT_THROW(EncodeGreyPng(colour), std::logic_error);
  EXPECT_THROW(EncodeGreyPng(cv::Mat()), std::logic_error);
}

}  // namespace
}  // namespace hoilcd
