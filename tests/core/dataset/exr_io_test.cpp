#include "hoilcd/core/dataset/exr_io.h"

#include <cstdlib>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/error.h"
#include "input_error_of.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

TEST(Exr, WrittenChannelsReadBackExactly) {
  const test::TestDir temp;
  cv::Mat t(6, 8, CV_32F);
  for (int i = 0; i < 48; ++i) t.at<float>(i / 8, i % 8) = 20.0f + 0.25f * i;
  WriteFileAtomic(temp / "f.exr", EncodeExr({{"T", t}, {"Z", t * 2}}));
  const ExrChannels back = ReadExr(temp / "f.exr", t.size());
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(cv::norm(back[0].second, t, cv::NORM_INF), 0.0);
}

TEST(Exr, EveryCompressionAndPixelTypeReadsBackAsTheDatasetStoredIt) {
  const test::TestDir temp;
  cv::Mat t(6, 8, CV_32F), ids(6, 8, CV_32S), depth(6, 8, CV_32F);
  for (int i = 0; i < 48; ++i) {
    t.at<float>(i / 8, i % 8) = 20.0f + 0.013f * i;
    ids.at<int>(i / 8, i % 8) = i % 5 == 0 ? -1 : 1000 + i;  // -1: nothing
    depth.at<float>(i / 8, i % 8) = 0.5f + 0.1517f * i;
  }
  const ExrChannels frame = FrameExrChannels(t, t, depth, ids, ids);
  for (ExrCompression c : {ExrCompression::kNone, ExrCompression::kRle, ExrCompression::kZips, ExrCompression::kZip,
                           ExrCompression::kPiz}) {
    WriteFileAtomic(temp / "f.exr", EncodeExr(frame, {c, 1}));
    const ExrChannels back = ReadExr(temp / "f.exr", t.size());
    ASSERT_EQ(back.size(), 5u);
    for (const auto& [name, image] : back) {
      ASSERT_EQ(image.type(), CV_32F) << name;
      cv::Mat expected;
      if (name == "T" || name == "T_true") expected = t;
      if (name == "id" || name == "class") ids.convertTo(expected, CV_32F);
      if (name == "Z") frame[2].second.convertTo(expected, CV_32F);  // the half the file holds
      EXPECT_EQ(cv::norm(image, expected, cv::NORM_INF), 0.0) << name << " compression " << static_cast<int>(c);
    }
  }
}

// The hand-laid RLE file is OpenEXR's, byte for byte: every run-length case (runs of 1 to 300
// equal bytes, literal stretches up to and past 127, lines that do not shrink and are stored raw,
// runs at a line's end), every pixel type, odd sizes, and channels given out of name order.
TEST(Exr, HandLaidRleFramesAreOpenExrsByteForByte) {
  std::mt19937 rng(20261203);
  ExrWriteOptions library;
  library.openexr_rle = true;
  const auto check = [&](const ExrChannels& channels, const std::string& what) {
    const std::string hand = EncodeExr(channels);
    const std::string openexr = EncodeExr(channels, library);
    ASSERT_EQ(hand.size(), openexr.size()) << what;
    EXPECT_TRUE(hand == openexr) << what;
  };
  for (const cv::Size size : {cv::Size(256, 192), cv::Size(1, 1), cv::Size(7, 5), cv::Size(300, 3)}) {
    const std::string at = " at " + std::to_string(size.width) + "x" + std::to_string(size.height);
    cv::Mat noise(size, CV_32F), runs(size, CV_32F), ids(size, CV_32S), depth(size, CV_32F);
    std::uniform_real_distribution<float> temperature(18.0f, 36.0f);
    std::uniform_int_distribution<int> run_length(1, 300), id(-1, 40);
    for (int i = 0; i < size.area(); ++i) noise.at<float>(i / size.width, i % size.width) = temperature(rng);
    for (int i = 0; i < size.area();) {  // stretches of equal values of every length
      const int length = run_length(rng);
      const float value = temperature(rng);
      const int label = id(rng);
      for (int k = 0; k < length && i < size.area(); ++k, ++i) {
        runs.at<float>(i / size.width, i % size.width) = value;
        ids.at<int>(i / size.width, i % size.width) = label;
        depth.at<float>(i / size.width, i % size.width) = 0.5f + 0.001f * static_cast<float>(i % 977);
      }
    }
    check(FrameExrChannels(noise, runs, depth, ids, ids), "a frame" + at);
    check({{"id", ids}, {"T", noise}, {"Z", FrameExrChannels(noise, noise, depth, ids, ids)[2].second}},
          "channels out of name order" + at);
    check({{"T", noise}}, "noise alone (stored raw)" + at);
    check({{"T", cv::Mat::zeros(size, CV_32F)}, {"id", cv::Mat(size, CV_32S, cv::Scalar(-1))}}, "constants" + at);
    cv::Mat bytes(size, CV_32S);  // random bytes: literal stretches of every length
    for (int i = 0; i < size.area(); ++i) {
      std::uniform_int_distribution<int> byte(0, 3);
      int v = 0;
      for (int k = 0; k < 4; ++k) v = (v << 8) | (byte(rng) == 0 ? 7 : static_cast<int>(rng() & 0xff));
      bytes.at<int>(i / size.width, i % size.width) = v;
    }
    check({{"class", bytes}}, "mostly random bytes" + at);
  }
}

TEST(Exr, DepthStoredAsHalfIsWithinTwoMillimetresBelowEightMetres) {
  cv::Mat depth(1, 4000, CV_32F);
  for (int i = 0; i < depth.cols; ++i) depth.at<float>(0, i) = 0.002f * i;  // 0 to 8 m
  const cv::Mat zero = cv::Mat::zeros(1, 4000, CV_32S);
  cv::Mat back;
  FrameExrChannels(depth, depth, depth, zero, zero)[2].second.convertTo(back, CV_32F);
  EXPECT_LE(cv::norm(back, depth, cv::NORM_INF), 1.0 / 512 + 1e-6);  // 2^-9 m: half's spacing in [4, 8) m, halved
}

// A frame as the dataset writes it passes OpenEXR's own tools (Debian openexr, which has no
// exrcheck): exrinfo reads the header, exrmaketiled decodes every pixel of every channel.
TEST(Exr, DatasetFramePassesOpenExrsOwnTools) {
  if (std::system("command -v exrinfo exrmaketiled > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "exrinfo, exrmaketiled (Debian openexr) not installed";
  }
  const test::TestDir temp;
  cv::Mat t(192, 256, CV_32F), ids(192, 256, CV_32S, cv::Scalar(-1));
  cv::randu(t, 18.0f, 36.0f);
  WriteFileAtomic(temp / "f.exr", EncodeExr(FrameExrChannels(t, t, t, ids, ids)));
  EXPECT_EQ(std::system(("exrinfo -v '" + (temp / "f.exr") + "' > /dev/null").c_str()), 0);
  EXPECT_EQ(std::system(("exrmaketiled '" + (temp / "f.exr") + "' '" + (temp / "tiled.exr") + "' > /dev/null").c_str()),
            0);
  // The check can fail: a truncated frame does not pass.
  WriteFileAtomic(temp / "cut.exr", ReadFileBytes(temp / "f.exr").substr(0, 3000));
  EXPECT_NE(
      std::system(("exrmaketiled '" + (temp / "cut.exr") + "' '" + (temp / "tiled2.exr") + "' 2> /dev/null").c_str()),
      0);
}

TEST(Exr, AttributeDeclaredLargerThanTheFileIsRefusedBeforeOpenExrAllocatesIt) {
  const test::TestDir temp;
  // Magic, version 2, one attribute "x" of type "fl" declaring 2^31 - 1 bytes (fuzz_dataset's
  // finding: OpenEXR allocated the declared size, taking seconds and gigabytes).
  const std::string bytes = std::string("\x76\x2f\x31\x01\x02\x00\x00\x00", 8) + std::string("x\0fl\0", 5) +
                            std::string("\xff\xff\xff\x7f", 4) + "abc";
  WriteFileAtomic(temp / "bad.exr", bytes);
  try {
    ReadExr(temp / "bad.exr", cv::Size(8, 6));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("damaged header"), std::string::npos) << e.what();
  }
}

TEST(Exr, DataWindowFarLargerThanAFrameIsRefusedBeforeOpenExrAllocatesLineBuffers) {
  const test::TestDir temp;
  cv::Mat t(6, 8, CV_32F, cv::Scalar(21.0f));
  std::string bytes = EncodeExr({{"T", t}});
  // Widen the data window (box2i xMin yMin xMax yMax) to 2^30 columns.
  const size_t at = bytes.find(std::string("dataWindow\0box2i\0", 17)) + 17 + 4;
  ASSERT_LT(at, bytes.size());
  bytes.replace(at + 8, 4, std::string("\x00\x00\x00\x40", 4));
  WriteFileAtomic(temp / "wide.exr", bytes);
  try {
    ReadExr(temp / "wide.exr", cv::Size(8, 6));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("data window"), std::string::npos) << e.what();
  }
}

TEST(Exr, ChannelListWhoseDeclaredSizeDisagreesWithItsEntriesIsRefused) {
  const test::TestDir temp;
  // OpenEXR reads a chlist entry by entry and ignores the declared size, so a shorter size puts
  // the next attributes at other offsets than ours (fuzz_dataset's long run found one that then
  // allocated gigabytes for a garbage "attribute"). Shrink the declared size by 18 bytes.
  std::string bytes = EncodeExr({{"T", cv::Mat(6, 8, CV_32F, cv::Scalar(21.0f))}});
  const size_t at = bytes.find(std::string("channels\0chlist\0", 16)) + 16;
  ASSERT_LT(at + 4, bytes.size());
  bytes[at] = static_cast<char>(static_cast<unsigned char>(bytes[at]) - 18);
  WriteFileAtomic(temp / "desync.exr", bytes);
  try {
    ReadExr(temp / "desync.exr", cv::Size(8, 6));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("disagrees with its type's size"), std::string::npos) << e.what();
  }
}

TEST(Exr, DecodingBytesInMemoryEqualsReadingTheFileAndATruncatedFileIsAnInputError) {
  const test::TestDir temp;
  cv::Mat t(6, 8, CV_32F), ids(6, 8, CV_32S, cv::Scalar(3));
  cv::randu(t, 18.0f, 36.0f);
  const std::string bytes = EncodeExr(FrameExrChannels(t, t, t, ids, ids));
  WriteFileAtomic(temp / "f.exr", bytes);
  const ExrChannels from_file = ReadExr(temp / "f.exr", t.size());
  const ExrChannels from_bytes = DecodeExr(bytes, "mem.exr", t.size());
  ASSERT_EQ(from_bytes.size(), from_file.size());
  for (size_t c = 0; c < from_file.size(); ++c) {
    EXPECT_EQ(from_bytes[c].first, from_file[c].first);
    EXPECT_EQ(cv::norm(from_bytes[c].second, from_file[c].second, cv::NORM_INF), 0.0) << from_file[c].first;
  }
  // Every cut of the file, header or pixel data, is an InputError naming the path: no crash, no
  // read past the bytes.
  for (size_t length = 0; length < bytes.size(); length += 1 + length / 8) {
    try {
      DecodeExr(bytes.substr(0, length), "cut.exr", t.size());
      ADD_FAILURE() << "a file cut to " << length << " of " << bytes.size() << " bytes was read";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("cut.exr: ", 0), 0u) << e.what();
    }
  }
}

// A dataset of one 8 x 6 px frame with an EXR, its manifest listing every file.
void WriteOneFrameExrDataset(const std::string& dir, const cv::Mat& t) {
  DatasetManifest m;
  m.hoilcd_version = "test";
  m.scene_hash = ChecksumOf("{}");
  m.intrinsics = CameraIntrinsics::FromHorizontalFov(t.cols, t.rows, 50);
  m.frame_count = 1;
  m.outputs.thermal = m.outputs.radiometric = m.outputs.video = m.outputs.persons = false;
  const cv::Mat ids(t.size(), CV_32S, cv::Scalar(-1));
  WriteDatasetFile(dir, "scene.json", "{}\n", &m);
  WriteDatasetFile(dir, "exr/000000.exr", EncodeExr(FrameExrChannels(t, t, t, ids, ids)), &m);
  WriteDatasetFile(dir, "poses.csv", PosesToCsv({PoseRecord{}}), &m);
  WriteDatasetFile(dir, "events.json", EventsToJson({}), &m);
  m.complete = true;
  WriteFileAtomic(dir + "/manifest.json", m.ToJson());
}

TEST(Exr, DatasetFrameReadWithVerifyOnReadIsCheckedAgainstTheManifest) {
  const test::TestDir temp;
  const cv::Mat t(6, 8, CV_32F, cv::Scalar(25.5f));
  WriteOneFrameExrDataset(temp.str(), t);
  EXPECT_EQ(ReadDatasetExr(Dataset::Open(temp.str(), Verify::kOnRead), 0)[0].second.at<float>(5, 7), 25.5f);
  // One flipped bit in the last pixel block: Open does not read the EXR; reading it is an error.
  std::string bytes = ReadFileBytes(temp / "exr/000000.exr");
  bytes[bytes.size() - 2] ^= 0x10;
  WriteFileAtomic(temp / "exr/000000.exr", bytes);
  const Dataset ds = Dataset::Open(temp.str(), Verify::kOnRead);
  try {
    ReadDatasetExr(ds, 0);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(temp / "exr/000000.exr" + ": checksum mismatch", 0), 0u) << e.what();
  }
  EXPECT_THROW(Dataset::Open(temp.str(), Verify::kEveryFile), InputError);
}

TEST(Exr, FrameOfAnotherSizeThanTheDatasetsIsRefusedNamingBoth) {
  const test::TestDir temp;
  WriteFileAtomic(temp / "f.exr", EncodeExr({{"T", cv::Mat(6, 8, CV_32F, cv::Scalar(21.0f))}}));
  try {
    ReadExr(temp / "f.exr", cv::Size(256, 192));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("expected a 256x192 px frame, the data window is 8x6"), std::string::npos)
        << e.what();
  }
}

TEST(Exr, MoreChannelsThanAFrameCanHaveAreRefused) {
  const test::TestDir temp;
  ExrChannels many;
  for (int i = 0; i < 17; ++i) many.emplace_back("c" + std::to_string(i), cv::Mat(6, 8, CV_32F, cv::Scalar(i)));
  WriteFileAtomic(temp / "many.exr", EncodeExr(many));
  try {
    ReadExr(temp / "many.exr", cv::Size(8, 6));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("expected at most 16 channels, found 17"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hoilcd

namespace hoilcd {
namespace {

// `only` reads just the channels asked for, in the order asked, the values those of a full read (which
// equal the frame: RLE through the hand-laid reader, ZIP through OpenEXR); a channel the file lacks is
// an InputError naming it.
TEST(Exr, ReadingOnlySomeChannelsGivesThemInTheOrderAskedWithTheFullReadsValues) {
  cv::Mat t(5, 7, CV_32F), ids(5, 7, CV_32S);  // odd sizes: lines of 126 bytes, not a multiple of 16
  cv::randu(t, 18.0f, 36.0f);
  cv::randu(ids, -1, 40);
  for (ExrCompression c : {ExrCompression::kRle, ExrCompression::kZip}) {
    const std::string bytes = EncodeExr(FrameExrChannels(t, t, t, ids, ids), {c, 1});
    const ExrChannels all = DecodeExr(bytes, "f.exr", t.size());
    EXPECT_EQ(cv::norm(ExrChannel(all, "T", "f.exr"), t, cv::NORM_INF), 0.0);
    cv::Mat ids_as_read;
    ids.convertTo(ids_as_read, CV_32F);
    EXPECT_EQ(cv::norm(ExrChannel(all, "id", "f.exr"), ids_as_read, cv::NORM_INF), 0.0);
    const ExrChannels two = DecodeExr(bytes, "f.exr", t.size(), {"id", "Z"});
    ASSERT_EQ(two.size(), 2u);
    EXPECT_EQ(two[0].first, "id");
    EXPECT_EQ(two[1].first, "Z");
    for (const auto& [name, image] : two) {
      EXPECT_EQ(cv::norm(image, ExrChannel(all, name, "f.exr"), cv::NORM_INF), 0.0) << name;
    }
    EXPECT_NE(test::InputErrorOf([&] {
                DecodeExr(bytes, "f.exr", t.size(), {"depth"});
              }).find("f.exr: has no channel 'depth'"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace hoilcd
