// The dataset's frame encodings: display window to 8 bits, temperature to centikelvin.
#include "hoilcd/core/dataset/frame_encoding.h"

#include <gtest/gtest.h>

namespace hoilcd {
namespace {

TEST(ToDisplay8Bit, MapsWindowLinearlyAndClamps) {
  const cv::Mat temperature = (cv::Mat_<float>(1, 6) << 20.0f, 30.0f, 22.0f, 10.0f, 40.0f, 20.02f);
  const cv::Mat display = ToDisplay8Bit(temperature, 20.0, 30.0);
  ASSERT_EQ(display.type(), CV_8U);
  EXPECT_EQ(display.at<uint8_t>(0, 0), 0);
  EXPECT_EQ(display.at<uint8_t>(0, 1), 255);
  EXPECT_EQ(display.at<uint8_t>(0, 2), 51);
  EXPECT_EQ(display.at<uint8_t>(0, 3), 0);
  EXPECT_EQ(display.at<uint8_t>(0, 4), 255);
  EXPECT_EQ(display.at<uint8_t>(0, 5), 1);  // 0.51 rounds up
}

TEST(ToCentikelvin16, EncodesKelvinTimes100RoundedAndClamped) {
  const cv::Mat temperature = (cv::Mat_<float>(1, 5) << 25.0f, 0.0f, -300.0f, 400.0f, 25.004f);
  const cv::Mat centikelvin = ToCentikelvin16(temperature);
  ASSERT_EQ(centikelvin.type(), CV_16U);
  EXPECT_EQ(centikelvin.at<uint16_t>(0, 0), 29815);
  EXPECT_EQ(centikelvin.at<uint16_t>(0, 1), 27315);
  EXPECT_EQ(centikelvin.at<uint16_t>(0, 2), 0);
  EXPECT_EQ(centikelvin.at<uint16_t>(0, 3), 65535);
  EXPECT_EQ(centikelvin.at<uint16_t>(0, 4), 29815);
}

TEST(CelsiusFromCentikelvin16, InvertsToCentikelvin16ToTheCentikelvin) {
  const cv::Mat temperature = (cv::Mat_<float>(1, 4) << 25.0f, 0.0f, 33.456f, -20.0f);
  const cv::Mat back = CelsiusFromCentikelvin16(ToCentikelvin16(temperature));
  ASSERT_EQ(back.type(), CV_32F);
  EXPECT_NEAR(back.at<float>(0, 0), 25.0f, 1e-4);
  EXPECT_NEAR(back.at<float>(0, 1), 0.0f, 1e-4);
  EXPECT_NEAR(back.at<float>(0, 2), 33.46f, 1e-4);  // rounded to the centikelvin
  EXPECT_NEAR(back.at<float>(0, 3), -20.0f, 1e-4);
}

}  // namespace
}  // namespace hoilcd
