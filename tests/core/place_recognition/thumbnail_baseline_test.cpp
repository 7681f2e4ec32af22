#include "hoilcd/core/place_recognition/thumbnail_baseline.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "hoilcd/core/util/random.h"
#include "option_properties.h"

namespace hoilcd {
namespace {

// A 256x192 frame of smooth random structure: a coarse random grid upsampled, keyed by `key`.
cv::Mat RandomScene(uint64_t key) {
  cv::Mat coarse(24, 32, CV_32F);
  Rng rng = KeyedRng(7, "test.thumbnail.scene", key);
  for (int y = 0; y < coarse.rows; ++y)
    for (int x = 0; x < coarse.cols; ++x) coarse.at<float>(y, x) = rng.Uniform(40.0, 200.0);
  cv::Mat scene_f32, scene_u8;
  cv::resize(coarse, scene_f32, cv::Size(256, 192), 0, 0, cv::INTER_CUBIC);
  scene_f32.convertTo(scene_u8, CV_8U);
  return scene_u8;
}

float Similarity(const cv::Mat& a, const cv::Mat& b, const ThumbnailOptions& options = {}) {
  return ThumbnailSimilarity(ThumbnailDescriptor(a, options), ThumbnailDescriptor(b, options));
}

TEST(ThumbnailBaseline, IdenticalFramesScoreOneAndShiftedOrDifferentFramesScoreLower) {
  const cv::Mat scene = RandomScene(1);
  EXPECT_NEAR(Similarity(scene, scene), 1.0f, 1e-5f);
  cv::Mat shifted;
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, 24, 0, 1, 0);
  cv::warpAffine(scene, shifted, shift, scene.size(), cv::INTER_NEAREST, cv::BORDER_REPLICATE);
  const float shifted_score = Similarity(scene, shifted);
  const float other_score = Similarity(scene, RandomScene(2));
  EXPECT_LT(shifted_score, 0.9f);
  EXPECT_LT(other_score, shifted_score);
  EXPECT_LT(std::abs(other_score), 0.3f);
  EXPECT_GE(other_score, -1.0f);
}

TEST(ThumbnailBaseline, PatchNormalisationMakesBrightnessAndContrastIrrelevant) {
  const cv::Mat scene = RandomScene(3);
  cv::Mat brighter, scaled;
  scene.convertTo(brighter, CV_8U, 1.0, 30.0);  // RandomScene stays below 225: no clipping
  EXPECT_NEAR(Similarity(scene, brighter), 1.0f, 1e-5f);
  // A gain changes the 8-bit rounding a little, hence the looser bound.
  scene.convertTo(scaled, CV_8U, 0.5, 10.0);
  EXPECT_GT(Similarity(scene, scaled), 0.99f);
}

TEST(ThumbnailBaseline, PatchNormalisationRemovesAPerPatchOffsetThatGlobalNccWouldSee) {
  // A brightness ramp across patches (as FFC drift or vignetting) hurts plain NCC but not the
  // patch-normalised score, provided the ramp is constant inside each patch.
  const cv::Mat scene = RandomScene(4);
  cv::Mat ramped = scene.clone();
  for (int y = 0; y < ramped.rows; ++y)
    for (int x = 0; x < ramped.cols; ++x)
      ramped.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(scene.at<uint8_t>(y, x) * 0.2 + (x / 64) * 50);
  ThumbnailOptions per_patch;  // 8x8 thumbnail px = 64x64 image px: the ramp's step width
  ThumbnailOptions whole_image;
  whole_image.patch_px = 32;
  EXPECT_GT(Similarity(scene, ramped, per_patch), 0.98f);
  EXPECT_LT(Similarity(scene, ramped, whole_image), 0.6f);
}

TEST(ThumbnailBaseline, FlatFrameCorrelatesZeroWithEverything) {
  const cv::Mat flat(192, 256, CV_8U, cv::Scalar(100));
  EXPECT_EQ(Similarity(flat, flat), 0.0f);
  EXPECT_EQ(Similarity(flat, RandomScene(5)), 0.0f);
}

TEST(ThumbnailBaseline, ScoreAllIsSymmetricAndIdenticalAtOneAndTwoThreads) {
  ThumbnailIndex index;
  for (int f = 0; f < 40; ++f) index.Add(RandomScene(static_cast<uint64_t>(f % 25)));
  std::vector<int> all(40);
  for (int f = 0; f < 40; ++f) all[static_cast<size_t>(f)] = f;
  const auto one = index.ScoreAll(all, all, 1);
  const auto two = index.ScoreAll(all, all, 2);
  EXPECT_EQ(one, two);
  for (int a = 0; a < 40; ++a) {
    EXPECT_NEAR(one[a][a], 1.0f, 1e-5f);
    for (int b = 0; b < 40; ++b) EXPECT_EQ(one[a][b], one[b][a]);
  }
  EXPECT_NEAR(one[3][28], 1.0f, 1e-5f);  // frame 28 repeats frame 3's scene
  const auto subset = index.ScoreAll({28, 5}, {3, 7, 30}, 2);
  EXPECT_EQ(subset[0][0], one[28][3]);
  EXPECT_EQ(subset[1][2], one[5][30]);
}

// Top-1 accuracy against the diagonal: the fraction of rows whose best column is the row itself.
double DiagonalTop1(const std::vector<std::vector<float>>& scores) {
  int correct = 0;
  for (size_t i = 0; i < scores.size(); ++i) {
    const auto best = std::max_element(scores[i].begin(), scores[i].end());
    if (static_cast<size_t>(best - scores[i].begin()) == i) ++correct;
  }
  return static_cast<double>(correct) / static_cast<double>(scores.size());
}

TEST(ThumbnailBaseline, SequenceSearchRecoversTheDiagonalWhereSingleFramesAreTooNoisy) {
  // Two traversals of the same 150-frame route with independent noise: the true match of query
  // frame i is database frame i, but single-frame similarities are weak.
  constexpr int kFrames = 150;
  std::vector<std::vector<float>> similarity(kFrames, std::vector<float>(kFrames));
  for (int i = 0; i < kFrames; ++i) {
    for (int j = 0; j < kFrames; ++j) {
      Rng rng = KeyedRng(11, "test.thumbnail.noise", i, j);
      similarity[i][j] = static_cast<float>((i == j ? 0.15 : 0.0) + rng.Normal(0.0, 0.1));
    }
  }
  const double single = DiagonalTop1(similarity);
  SeqSlamOptions options;
  const auto sequence = SequenceScores(similarity, options, 2);
  const double matched = DiagonalTop1(sequence);
  EXPECT_LT(single, 0.4);
  EXPECT_GT(matched, 0.9);
  EXPECT_EQ(sequence, SequenceScores(similarity, options, 1));
}

TEST(ThumbnailBaseline, SequenceSearchFollowsTheVelocityOfTheDatabase) {
  // The database was recorded at half the speed: query frame i matches database frame 2i.
  constexpr int kQueries = 60, kDatabase = 120;
  std::vector<std::vector<float>> similarity(kQueries, std::vector<float>(kDatabase));
  for (int i = 0; i < kQueries; ++i)
    for (int j = 0; j < kDatabase; ++j) {
      Rng rng = KeyedRng(12, "test.thumbnail.noise", i, j);
      similarity[i][j] = static_cast<float>((j == 2 * i ? 0.3 : 0.0) + rng.Normal(0.0, 0.1));
    }
  SeqSlamOptions options;
  options.min_velocity = 1.5;
  options.max_velocity = 2.5;
  options.velocity_steps = 3;
  const auto sequence = SequenceScores(similarity, options, 2);
  int correct = 0;
  for (int i = 0; i < kQueries; ++i) {
    const auto best = std::max_element(sequence[i].begin(), sequence[i].end());
    if (best - sequence[i].begin() == 2 * i) ++correct;
  }
  EXPECT_GT(correct, kQueries * 9 / 10);
}

TEST(ThumbnailBaseline, SequenceOfLengthOneIsTheSingleFrameMatrix) {
  const std::vector<std::vector<float>> similarity = {{0.1f, -0.5f}, {0.9f, 0.2f}, {0.3f, 0.4f}};
  SeqSlamOptions options;
  options.sequence_length = 1;
  EXPECT_EQ(SequenceScores(similarity, options, 1), similarity);
}

TEST(ThumbnailBaseline, SequenceIsShortenedAtTheFirstRowsAndCountsStepsPastTheColumnsAsZero) {
  // 3x3 matrix, length 3, velocity 1: (2,2) averages the diagonal, (1,1) its two rows, (2,1)
  // has one step past column 0 counted as 0.
  const std::vector<std::vector<float>> similarity = {{1.0f, 0.0f, 0.0f}, {0.6f, 0.5f, 0.0f}, {0.0f, 0.0f, 0.0f}};
  SeqSlamOptions options;
  options.sequence_length = 3;
  options.min_velocity = options.max_velocity = 1.0;
  const auto sequence = SequenceScores(similarity, options, 1);
  EXPECT_FLOAT_EQ(sequence[2][2], 0.5f);
  EXPECT_FLOAT_EQ(sequence[1][1], 0.75f);
  EXPECT_FLOAT_EQ(sequence[0][0], 1.0f);
  EXPECT_FLOAT_EQ(sequence[2][1], 0.6f / 3.0f);
}

TEST(ThumbnailBaseline, OptionChecksNameTheBadField) {
  ThumbnailOptions thumbnail;
  thumbnail.patch_px = 0;
  EXPECT_NE(thumbnail.Check().find("patch_px"), std::string::npos);
  thumbnail = ThumbnailOptions();
  thumbnail.width_px = 0;
  EXPECT_NE(thumbnail.Check().find("width_px"), std::string::npos);
  SeqSlamOptions sequence;
  EXPECT_EQ(sequence.Check(), "");
  sequence.min_velocity = 2.0;
  EXPECT_NE(sequence.Check().find("min_velocity"), std::string::npos);
  sequence = SeqSlamOptions();
  sequence.sequence_length = 0;
  EXPECT_NE(sequence.Check().find("sequence_length"), std::string::npos);
  sequence = SeqSlamOptions();
  sequence.velocity_steps = 0;
  EXPECT_NE(sequence.Check().find("velocity_steps"), std::string::npos);
}

TEST(ThumbnailBaseline, OptionsHoldTheirTablesDefaultsAndEveryBoundIsChecked) {
  ExpectConstructedHoldsTheTableDefaults<ThumbnailOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<ThumbnailOptions>(), 6);
  ExpectConstructedHoldsTheTableDefaults<SeqSlamOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<SeqSlamOptions>(), 8);
}

TEST(ThumbnailBaseline, ThumbnailSizeBeyondTheImageIsRefusedByName) {
  ThumbnailOptions thumbnail;
  thumbnail.width_px = thumbnail.height_px = 100000;  // the audit's 40 GB request
  EXPECT_NE(thumbnail.Check().find("width_px: must be in [1, 8192]"), std::string::npos) << thumbnail.Check();
  thumbnail = ThumbnailOptions();
  EXPECT_EQ(thumbnail.CheckImage(256, 192), "");
  thumbnail.width_px = 257;
  EXPECT_EQ(thumbnail.CheckImage(256, 192), "width_px: must be at most the image width, 256 px");
  thumbnail = ThumbnailOptions();
  thumbnail.height_px = 193;
  EXPECT_EQ(thumbnail.CheckImage(256, 192), "height_px: must be at most the image height, 192 px");
  EXPECT_DOUBLE_EQ(ThumbnailOptions().DatabaseBytes(1996), 1996.0 * 32 * 24 * 4);
}

TEST(ThumbnailBaseline, SequenceLengthBeyondAnySequenceIsRefusedByName) {
  SeqSlamOptions sequence;
  sequence.sequence_length = 2147483647;  // the audit's endless run
  EXPECT_NE(sequence.Check().find("sequence_length: must be in [1, 1000000]"), std::string::npos) << sequence.Check();
  sequence = SeqSlamOptions();
  sequence.velocity_steps = 101;
  EXPECT_NE(sequence.Check().find("velocity_steps"), std::string::npos);
}

TEST(ThumbnailBaseline, SequenceLongerThanTheMatrixCountsAsAllOfItsRows) {
  const std::vector<std::vector<float>> similarity = {{1.0f, 0.0f, 0.0f}, {0.6f, 0.5f, 0.0f}, {0.0f, 0.0f, 0.0f}};
  SeqSlamOptions three, all;
  three.sequence_length = 3;
  all.sequence_length = 1000000;
  EXPECT_EQ(SequenceScores(similarity, all, 1), SequenceScores(similarity, three, 1));
}

}  // namespace
}  // namespace hoilcd
