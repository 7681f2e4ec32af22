#include "hoilcd/core/util/file_io.h"

#include <filesystem>
#include <iterator>
#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <sys/stat.h>
#include <unistd.h>

#include "hoilcd/core/util/error.h"
#include "input_error_of.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

using test::InputErrorOf;

TEST(Checksum, HasPrefixAnd32HexDigitsAndChangesWithOneByte) {
  const std::string a = ChecksumOf("hello");
  ASSERT_EQ(a.size(), 9u + 32u);
  EXPECT_EQ(a.substr(0, 9), "xxh3-128:");
  EXPECT_EQ(a.find_first_not_of("0123456789abcdef", 9), std::string::npos);
  EXPECT_EQ(a, ChecksumOf("hello"));
  EXPECT_NE(a, ChecksumOf("hellp"));
}

TEST(EncodePng, IsDeterministicAndDecodesToTheSamePixels) {
  cv::Mat image16(6, 8, CV_16UC1);
  for (int i = 0; i < 48; ++i) image16.at<uint16_t>(i / 8, i % 8) = 29000 + 37 * i;
  const std::string bytes = EncodePng(image16);
  EXPECT_EQ(bytes, EncodePng(image16.clone()));
  const cv::Mat decoded = cv::imdecode(std::vector<uchar>(bytes.begin(), bytes.end()), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(decoded.type(), CV_16UC1);
  EXPECT_EQ(cv::countNonZero(decoded != image16), 0);
  EXPECT_THROW(EncodePng(cv::Mat(2, 2, CV_8UC4)), std::logic_error);
  EXPECT_THROW(EncodePng(cv::Mat(2, 2, CV_32FC1)), std::logic_error);
}

TEST(WritePng, WritesADecodableBgrPngAndNoTemporaryFile) {
  test::TestDir dir;
  const std::string path = dir / "plot.png";
  cv::Mat image(5, 7, CV_8UC3);
  cv::randu(image, 0, 256);
  WritePng(path, image);
  const cv::Mat read = cv::imread(path, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(read.type(), CV_8UC3);
  EXPECT_EQ(cv::norm(read, image, cv::NORM_INF), 0.0);
  int entries = 0;
  for (const auto& entry : fs::directory_iterator(dir.str())) {
    ++entries;
    EXPECT_EQ(entry.path().filename(), "plot.png");
  }
  EXPECT_EQ(entries, 1);
}

TEST(WritePng, UnwritableFolderIsAnInputErrorNamingThePath) {
  test::TestDir dir;
  WriteFileAtomic(dir / "file", "a file, not a folder");
  const std::string path = dir / "file/plot.png";
  try {
    WritePng(path, cv::Mat(4, 4, CV_8UC3, cv::Scalar::all(0)));
    FAIL() << "no error";
  } catch (const InputError& e) {
    ASSERT_EQ(e.problems().size(), 1u);
    EXPECT_EQ(e.problems()[0].where, path);
  }
}

TEST(WriteFileAtomic, ReplacesContentCreatesDirectoriesAndLeavesNoTempFile) {
  test::TestDir dir;
  const std::string path = dir / "a/b/file.txt";
  WriteFileAtomic(path, "first version, longer");
  EXPECT_EQ(ReadFileBytes(path), "first version, longer");
  WriteFileAtomic(path, "second");
  EXPECT_EQ(ReadFileBytes(path), "second");
  int entries = 0;
  for (const auto& entry : fs::directory_iterator(dir / "a/b")) {
    ++entries;
    EXPECT_EQ(entry.path().filename(), "file.txt");
  }
  EXPECT_EQ(entries, 1);
}

TEST(WriteFileAtomicUnsynced, ReplacesContentLeavesNoTempFileAndSyncFilesFlushesItAndItsFolder) {
  test::TestDir dir;
  const std::string path = dir / "frames/000001.png";
  WriteFileAtomicUnsynced(path, "old");
  WriteFileAtomicUnsynced(path, "new");
  EXPECT_EQ(ReadFileBytes(path), "new");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "frames"), fs::directory_iterator()), 1);
  EXPECT_NO_THROW(SyncFiles({path, dir / "frames/000001.png"}));
}

TEST(SyncFiles, AMissingFileIsAnInputErrorNamingIt) {
  test::TestDir dir;
  const std::string message = InputErrorOf([&] { SyncFiles({dir / "gone.exr"}); });
  EXPECT_NE(message.find("gone.exr: cannot open to flush it to disk"), std::string::npos) << message;
}

TEST(ReadFileBytes, MissingFileIsAnInputErrorNamingIt) {
  test::TestDir dir;
  const std::string message = InputErrorOf([&] { ReadFileBytes(dir / "nope.bin"); });
  EXPECT_NE(message.find("nope.bin: cannot read"), std::string::npos) << message;
}

TEST(ReadFileBytes, ReadsEveryByteOfLargeEmptyAndUnsizedFiles) {
  test::TestDir dir;
  std::string large(3 * 65536 + 17, '\0');
  for (size_t i = 0; i < large.size(); ++i) large[i] = static_cast<char>(i * 7919 % 251);
  WriteFileAtomic(dir / "large.bin", large);
  EXPECT_EQ(ReadFileBytes(dir / "large.bin"), large);
  WriteFileAtomic(dir / "empty.bin", "");
  EXPECT_EQ(ReadFileBytes(dir / "empty.bin"), "");
  // /proc files report size 0 to stat but have content.
  EXPECT_NE(ReadFileBytes("/proc/self/status").find("Name:"), std::string::npos);
}

TEST(ReadFileBytes, AFolderIsAnInputErrorNamingIt) {
  test::TestDir dir;
  const std::string message = InputErrorOf([&] { ReadFileBytes(dir.str()); });
  EXPECT_NE(message.find(dir.str() + ": is a folder: expected a regular file"), std::string::npos) << message;
}

TEST(ReadFileBytes, RefusesAFifoWithoutBlocking) {
  test::TestDir dir;
  const std::string fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // No writer ever opens the FIFO: a reader that opened it blocking would wait forever.
  const std::string message = InputErrorOf([&] { ReadFileBytes(fifo); });
  EXPECT_NE(message.find(fifo + ": is a FIFO: expected a regular file"), std::string::npos) << message;
  EXPECT_NE(InputErrorOf([&] { ChecksumOfFile(fifo); }).find("is a FIFO"), std::string::npos);
  EXPECT_NE(InputErrorOf([&] { RegularFile{fifo}; }).find("is a FIFO"), std::string::npos);
}

TEST(ReadFileBytes, RefusesADeviceInsteadOfReadingItForever) {
  const std::string message = InputErrorOf([&] { ReadFileBytes("/dev/zero"); });
  EXPECT_NE(message.find("/dev/zero: is a character device: expected a regular file"), std::string::npos) << message;
}

TEST(ReadFileBytes, AFileLongerThanItsBoundIsRefusedByItsSizeBeforeItIsRead) {
  test::TestDir dir;
  const std::string path = dir / "sparse.bin";
  WriteFileAtomic(path, "");
  // 64 GiB of holes: reading it whole would take minutes and more memory than the machine has.
  ASSERT_EQ(::truncate(path.c_str(), off_t{1} << 36), 0);
  const std::string message = InputErrorOf([&] { ReadFileBytes(path, 1000); });
  EXPECT_NE(message.find(path + ": is 68719476736 bytes: expected at most 1000"), std::string::npos) << message;
  WriteFileAtomic(path, std::string(1000, 'x'));
  EXPECT_EQ(ReadFileBytes(path, 1000).size(), 1000u);
  EXPECT_NE(InputErrorOf([&] { ReadFileBytes(path, 999); }).find("is 1000 bytes: expected at most 999"),
            std::string::npos);
}

TEST(ReadFileBytes, AFileWhoseSizeStatDoesNotKnowIsStillReadOnlyUpToItsBound) {
  // /proc files report size 0 to stat but have content.
  const std::string message = InputErrorOf([&] { ReadFileBytes("/proc/self/status", 10); });
  EXPECT_NE(message.find("/proc/self/status: is more than 10 bytes: expected at most 10"), std::string::npos)
      << message;
}

TEST(RegularFile, ReadsInPiecesAndGivesTheSizeBeforeReading) {
  test::TestDir dir;
  WriteFileAtomic(dir / "file.bin", "header|body");
  RegularFile file(dir / "file.bin");
  EXPECT_EQ(file.size(), 11u);
  EXPECT_EQ(file.Read(7), "header|");
  EXPECT_EQ(file.Read(100), "body");
  EXPECT_EQ(file.Read(100), "");
}

TEST(ChecksumOfFile, IsTheChecksumOfTheWholeFileAtEverySizeAroundItsBlocks) {
  test::TestDir dir;
  constexpr size_t kBlock = size_t{1} << 18;  // the block it reads
  for (size_t size : {size_t{0}, size_t{1}, size_t{240}, kBlock - 1, kBlock, kBlock + 1, 3 * kBlock + 17}) {
    std::string bytes(size, '\0');
    for (size_t i = 0; i < size; ++i) bytes[i] = static_cast<char>(i * 7919 % 251);
    WriteFileAtomic(dir / "file.bin", bytes);
    EXPECT_EQ(ChecksumOfFile(dir / "file.bin"), ChecksumOf(bytes)) << size << " bytes";
  }
  // /proc files report size 0 to stat but have content.
  EXPECT_EQ(ChecksumOfFile("/proc/self/cmdline"), ChecksumOf(ReadFileBytes("/proc/self/cmdline")));
}

TEST(ChecksumOfFile, AMissingFileOrAFolderIsAnInputErrorNamingIt) {
  test::TestDir dir;
  std::string message = InputErrorOf([&] { ChecksumOfFile(dir / "nope.bin"); });
  EXPECT_NE(message.find("nope.bin: cannot read file (missing or not readable)"), std::string::npos) << message;
  message = InputErrorOf([&] { ChecksumOfFile(dir.str()); });
  EXPECT_NE(message.find(dir.str() + ": is a folder: expected a regular file"), std::string::npos) << message;
}

}  // namespace
}  // namespace hoilcd
