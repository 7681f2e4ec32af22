#include "hoilcd/sim/output/frame_writer.h"

#include <filesystem>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "hoilcd/core/dataset/video.h"
#include "hoilcd/core/util/error.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 12;

// Frame f: a temperature ramp shifted by the frame, ids with "nothing" (-1) in places.
FrameImages MakeFrame(int f) {
  cv::Mat t(24, 32, CV_32F), ids(24, 32, CV_32S);
  for (int i = 0; i < t.rows * t.cols; ++i) {
    t.at<float>(i / t.cols, i % t.cols) = 20.0f + 0.01f * i + 0.1f * f;
    ids.at<int>(i / t.cols, i % t.cols) = (i + f) % 7 == 0 ? -1 : i % 3;
  }
  FrameImages frame;
  frame.frame = f;
  frame.temperature_c = t;
  frame.exr = FrameExrChannels(t, t, t * 0.1, ids, ids);
  return frame;
}

struct Written {
  std::map<std::string, std::string> files;  // the manifest's listing
  std::string mp4;
};

Written WriteAll(const std::string& dir, int workers, int capacity) {
  DatasetManifest manifest;
  VideoEncoder video(VideoOptions(), 32, 24, 25.0);
  FrameWriterOptions options;
  options.dir = dir;
  options.workers = workers;
  options.capacity = capacity;
  FrameWriter writer(options, &manifest, &video);
  for (int f = 0; f < kFrames; ++f) {
    writer.Submit(MakeFrame(f));
    if (f % 5 == 4) writer.Checkpoint();
  }
  writer.Finish();
  return {manifest.files, video.Finish()};
}

TEST(FrameWriter, SameBytesAndVideoWithOneOrFourWorkersAndAnyQueueLength) {
  const test::TestDir temp;
  const Written one = WriteAll(temp / "one", 1, 1);
  const Written four = WriteAll(temp / "four", 4, 2);
  const Written deep = WriteAll(temp / "deep", 3, 16);
  EXPECT_EQ(one.files.size(), 3u * kFrames);
  EXPECT_EQ(one.files, four.files);
  EXPECT_EQ(one.files, deep.files);
  EXPECT_EQ(one.mp4, four.mp4);  // the encoder got the frames in order
  EXPECT_EQ(one.mp4, deep.mp4);
  EXPECT_EQ(DecodeVideo(one.mp4, "one.mp4").frames.size(), static_cast<size_t>(kFrames));
  for (const auto& [relative, checksum] : one.files) {
    EXPECT_EQ(ChecksumOf(ReadFileBytes(temp / ("four/" + relative))), checksum) << relative;
  }
}

// Options writing into `dir` on two workers, no video.
FrameWriterOptions TwoWorkersIn(const std::string& dir) {
  FrameWriterOptions options;
  options.dir = dir;
  options.workers = 2;
  return options;
}

TEST(FrameWriter, CheckpointWritesAManifestListingOnlyFilesInPlace) {
  const test::TestDir temp;
  DatasetManifest manifest;
  FrameWriter writer(TwoWorkersIn(temp / "ds"), &manifest, nullptr);
  for (int f = 0; f < 4; ++f) writer.Submit(MakeFrame(f));
  writer.Checkpoint();
  writer.Finish();  // waits for the checkpoint too
  const DatasetManifest listed = DatasetManifest::FromJson(ReadFileBytes(temp / "ds/manifest.json"), "manifest.json");
  for (const auto& [relative, checksum] : listed.files) {
    EXPECT_EQ(ChecksumOf(ReadFileBytes(temp / ("ds/" + relative))), checksum) << relative;
  }
  EXPECT_EQ(manifest.files.size(), 12u);
  for (const auto& entry : fs::recursive_directory_iterator(temp / "ds")) {
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();
  }
}

// A checkpoint asked for while the last one still syncs is skipped, never waited for: the
// manifest on disk always lists only files in place, and nothing is lost at the end.
TEST(FrameWriter, CheckpointsAskedFasterThanTheDiskSyncsListOnlyFilesInPlace) {
  const test::TestDir temp;
  DatasetManifest manifest;
  FrameWriter writer(TwoWorkersIn(temp / "ds"), &manifest, nullptr);
  for (int f = 0; f < kFrames; ++f) {
    writer.Submit(MakeFrame(f));
    writer.Checkpoint();
  }
  writer.Finish();
  const DatasetManifest listed = DatasetManifest::FromJson(ReadFileBytes(temp / "ds/manifest.json"), "manifest.json");
  for (const auto& [relative, checksum] : listed.files) {
    EXPECT_EQ(ChecksumOf(ReadFileBytes(temp / ("ds/" + relative))), checksum) << relative;
  }
  EXPECT_EQ(manifest.files.size(), 3u * kFrames);
  writer.Checkpoint();  // none is running now: this one is written, listing every frame
  writer.Finish();
  EXPECT_EQ(DatasetManifest::FromJson(ReadFileBytes(temp / "ds/manifest.json"), "manifest.json").files, manifest.files);
}

TEST(FrameWriter, AWriteErrorIsRethrownNamingTheFile) {
  const test::TestDir temp;
  WriteFileAtomic(temp / "ds/thermal", "a file where the thermal folder should be");
  DatasetManifest manifest;
  FrameWriter writer(TwoWorkersIn(temp / "ds"), &manifest, nullptr);
  try {
    for (int f = 0; f < kFrames; ++f) writer.Submit(MakeFrame(f));
    writer.Finish();
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("thermal/0000"), std::string::npos) << e.what();
  }
}

// The video encoder's failure (here frames of another size than the video's) reaches Submit or
// Finish, the frames after it are not encoded, and nothing hangs.
TEST(FrameWriter, AVideoErrorIsRethrownAndStopsTheEncoding) {
  const test::TestDir temp;
  DatasetManifest manifest;
  VideoEncoder video(VideoOptions(), 64, 48, 25.0);
  FrameWriter writer(TwoWorkersIn(temp / "ds"), &manifest, &video);
  try {
    for (int f = 0; f < kFrames; ++f) writer.Submit(MakeFrame(f));
    writer.Finish();
    FAIL() << "expected the encoder's error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("expected CV_8UC1 64x48"), std::string::npos) << e.what();
  }
  EXPECT_EQ(video.frames_added(), 0);
}

}  // namespace
}  // namespace hoilcd
