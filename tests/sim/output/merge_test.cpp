// Sharded rendering (`render --shard I/N`) and `hoilcd merge`: the merged shards are the unsharded
// render byte for byte (every file, the manifest included) at any thread count, in video mode and
// across an FFC freeze at a shard's first frame; a shard stopped half way and re-run alone merges
// to the same bytes; every refusal of the merge names the folder and writes nothing.
#include "hoilcd/sim/output/merge.h"

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/sim/output/sequence.h"
#include "input_error_of.h"
#include "processes.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

#define EXPECT_SAYS(message, text) EXPECT_NE((message).find(text), std::string::npos) << (message)

// 39 frames in 3 shards (0–12, 13–25, 26–38); an FFC at frame 25 freezes 25–27, so shard 2 starts
// on a frozen frame showing frame 24 of shard 1.
constexpr int kFrames = 39;
const std::vector<std::string> kFfcAtFrame25 = {"camera.ffc_interval_s=1", "camera.ffc_freeze_s=0.12"};

Scene PaperRoom(std::vector<std::string> overrides = {}) {
  overrides.insert(overrides.end(), kFfcAtFrame25.begin(), kFfcAtFrame25.end());
  return LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json", overrides);
}

SequenceOptions Options(const std::string& dir, int threads, std::optional<Shard> shard = std::nullopt,
                        const std::string& outputs = "thermal,radiometric,exr,video,persons") {
  SequenceOptions options;
  options.output_dir = dir;
  options.frames = kFrames;
  options.threads = threads;
  options.shard = shard;
  options.outputs = outputs;
  return options;
}

// Every file under dir (relative path -> bytes).
std::map<std::string, std::string> FilesOf(const std::string& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file()) files[fs::relative(entry.path(), dir).string()] = ReadFileBytes(entry.path().string());
  }
  return files;
}

void ExpectSameFiles(const std::string& expected_dir, const std::string& dir) {
  const std::map<std::string, std::string> expected = FilesOf(expected_dir), got = FilesOf(dir);
  ASSERT_FALSE(expected.empty());
  for (const auto& [name, bytes] : expected) {
    const auto it = got.find(name);
    if (it == got.end()) {
      ADD_FAILURE() << dir << " lacks " << name;
    } else {
      EXPECT_TRUE(it->second == bytes) << name << " differs";
    }
  }
  for (const auto& [name, bytes] : got) EXPECT_EQ(expected.count(name), 1u) << dir << " has an extra " << name;
}

// Renders the 3 shards into root/shard_I on `threads` threads; returns their folders.
std::vector<std::string> RenderShards(const Scene& scene, const test::TestDir& root, int threads,
                                      const std::string& outputs = "thermal,radiometric,exr,video,persons") {
  std::vector<std::string> dirs;
  for (int i = 0; i < 3; ++i) {
    dirs.push_back(root / ("shard_" + std::to_string(i)));
    EXPECT_TRUE(RenderSequence(scene, Options(dirs.back(), threads, Shard{i, 3}, outputs)).complete);
  }
  return dirs;
}

TEST(ShardedRender, MergedShardsAreTheUnshardedRenderByteForByteAtOneAndTwoThreads) {
  const Scene scene = PaperRoom();
  const test::TestDir whole("whole");
  RenderSequence(scene, Options(whole.str(), 1));
  for (int threads : {1, 2}) {
    const test::TestDir root("t" + std::to_string(threads));
    const std::vector<std::string> shards = RenderShards(scene, root, threads);
    const std::string opened = test::InputErrorOf([&] { Dataset::Open(shards[1]); });
    EXPECT_NE(opened.find("is shard 1/3 of a sequence (frames 13 to 25 of 39), not a dataset; join the shards with "
                          "hoilcd merge"),
              std::string::npos)
        << opened;
    const MergeResult r = MergeShards({shards[2], shards[0], shards[1]}, root / "merged", threads);
    EXPECT_EQ(r.frames, kFrames);
    EXPECT_EQ(r.shards, 3);
    ExpectSameFiles(whole.str(), root / "merged");
    EXPECT_NO_THROW(Dataset::Open(root / "merged"));
  }
}

// Two recording runs of 20 frames: the second starts inside shard 1 (frames 13 to 25), whose render
// switches the second run's camera on there; the last run is cut to 19 frames.
TEST(ShardedRender, ASequenceOfRunsMergesToTheUnshardedBytesAcrossARunBoundary) {
  const Scene scene = PaperRoom({R"(runs=[{"time_of_day_h": 9, "frames": 20}, {"time_of_day_h": 15, "frames": 20}])"});
  const test::TestDir whole("whole"), root("shards");
  RenderSequence(scene, Options(whole.str(), 2));
  MergeShards(RenderShards(scene, root, 2), root / "merged", 2);
  ExpectSameFiles(whole.str(), root / "merged");
  EXPECT_EQ(Dataset::Open(root / "merged").runs().size(), 2u);
}

TEST(ShardedRender, VideoModeMergeEncodesAndDecodesTheWholeSequenceAsTheUnshardedRender) {
  const Scene scene = PaperRoom({"camera.video.enabled=true"});
  const test::TestDir whole("whole"), root("shards");
  RenderSequence(scene, Options(whole.str(), 2));
  const std::vector<std::string> shards = RenderShards(scene, root, 2);
  EXPECT_EQ(FilesOf(shards[0]).count("thermal.mp4"), 0u) << "a shard leaves the video to the merge";
  MergeShards(shards, root / "merged", 2);
  ExpectSameFiles(whole.str(), root / "merged");
}

TEST(ShardedRender, WithoutExrsOrPersonsMergesToTheUnshardedBytes) {
  const Scene scene = PaperRoom();
  const test::TestDir whole("whole"), root("shards");
  RenderSequence(scene, Options(whole.str(), 2, std::nullopt, "thermal,video"));
  MergeShards(RenderShards(scene, root, 2, "thermal,video"), root / "merged", 2);
  ExpectSameFiles(whole.str(), root / "merged");
}

TEST(ShardedRender, AShardStoppedHalfWayAndRerunAloneMergesToTheSameBytes) {
  const Scene scene = PaperRoom();
  const test::TestDir whole("whole"), root("shards");
  RenderSequence(scene, Options(whole.str(), 2));
  std::vector<std::string> shards = RenderShards(scene, root, 2);
  // Shard 2 again, stopped after 3 of its 13 frames (as Ctrl-C does, through the test hook that
  // stops it there every time), then run again.
  fs::remove_all(shards[2]);
  SequenceOptions options = Options(shards[2], 1, Shard{2, 3});
  options.checkpoint_every_frames = 1;
  options.cancel_after_frames = 3;
  EXPECT_THROW(RenderSequence(scene, options), RenderInterrupted);
  const std::string refused = test::InputErrorOf([&] { MergeShards(shards, root / "early", 2); });
  EXPECT_NE(refused.find(shards[2] + ": shard 2/3 is incomplete (frames 26 to 38"), std::string::npos) << refused;
  EXPECT_FALSE(fs::exists(root / "early"));
  options.cancel_after_frames = -1;
  const SequenceResult r = RenderSequence(scene, options);
  EXPECT_EQ(r.frames_total, 13);
  EXPECT_EQ(r.frames_reused, 3) << "the checkpoint after each frame kept the 3 done";
  EXPECT_EQ(r.frames_rendered, 10);
  MergeShards(shards, root / "merged", 2);
  ExpectSameFiles(whole.str(), root / "merged");
}

TEST(ShardedRender, MoreShardsThanFramesGiveEmptyShardsThatMergeToo) {
  const Scene scene = PaperRoom();
  const test::TestDir whole("whole"), root("shards");
  SequenceOptions options = Options(whole.str(), 0);
  options.frames = 2;
  RenderSequence(scene, options);
  std::vector<std::string> shards;
  for (int i = 0; i < 3; ++i) {  // frames: none, 0, 1
    shards.push_back(root / ("shard_" + std::to_string(i)));
    options = Options(shards.back(), 0, Shard{i, 3});
    options.frames = 2;
    EXPECT_EQ(RenderSequence(scene, options).frames_total, i == 0 ? 0 : 1);
  }
  MergeShards(shards, root / "merged", 0);
  ExpectSameFiles(whole.str(), root / "merged");
}

// Three shards of the default render and the refusals a merge of them must give.
class MergeRefusal : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new test::TestDir("refusals");
    const Scene scene = PaperRoom();
    shards_ = RenderShards(scene, *root_, 0);
    RenderSequence(PaperRoom({"seed=2"}), Options(*root_ / "seed2_shard_1", 0, Shard{1, 3}));
    RenderSequence(scene, Options(*root_ / "thermal_shard_1", 0, Shard{1, 3}, "thermal,persons"));
    RenderSequence(scene, Options(*root_ / "of2_shard_1", 0, Shard{1, 2}));
    SequenceOptions eight = Options(*root_ / "frames38_shard_1", 0, Shard{1, 3});
    eight.frames = 38;
    RenderSequence(scene, eight);
    RenderSequence(scene, Options(*root_ / "whole", 0));
  }
  static void TearDownTestSuite() {
    delete root_;
    root_ = nullptr;
  }

  // The merge's InputError; and it wrote nothing: the output folder was not even made.
  std::string Refusal(const std::vector<std::string>& dirs) const {
    const std::string out = *root_ / "out";
    const std::string message = test::InputErrorOf([&] { MergeShards(dirs, out, 0); });
    EXPECT_FALSE(fs::exists(out)) << message;
    EXPECT_FALSE(message.empty());
    return message;
  }
  static std::string Dir(const std::string& name) { return *root_ / name; }

  static test::TestDir* root_;
  static std::vector<std::string> shards_;
};
test::TestDir* MergeRefusal::root_ = nullptr;
std::vector<std::string> MergeRefusal::shards_;

TEST_F(MergeRefusal, ShardsOfAnotherSeedOutputsFrameCountOrShardCount) {
  EXPECT_SAYS(Refusal({shards_[0], Dir("seed2_shard_1"), shards_[2]}),
              Dir("seed2_shard_1") + ": is a shard of scene hash");
  EXPECT_SAYS(Refusal({shards_[0], shards_[2], Dir("thermal_shard_1")}),
              Dir("thermal_shard_1") + ": is a shard of --outputs thermal,persons, but " + shards_[0] +
                  " of --outputs thermal,radiometric,exr,video,persons");
  EXPECT_SAYS(Refusal({shards_[0], Dir("frames38_shard_1"), shards_[2]}),
              Dir("frames38_shard_1") + ": is a shard of a sequence of 38 frames, but " + shards_[0] +
                  " of a sequence of 39 frames");
  EXPECT_SAYS(Refusal({shards_[0], Dir("of2_shard_1")}),
              Dir("of2_shard_1") + ": is a shard of a render split into 2 shards");
}

TEST_F(MergeRefusal, ARepeatedOrMissingShard) {
  EXPECT_SAYS(Refusal({shards_[0], shards_[1], shards_[1], shards_[2]}),
              shards_[1] + ": repeats shard 1/3, which " + shards_[1] + " holds");
  EXPECT_SAYS(Refusal({shards_[0], shards_[2]}), "hoilcd merge: shard 1/3 (frames 13 to 25) is missing");
}

TEST_F(MergeRefusal, AWholeDatasetAFolderWithoutManifestOrAnotherSimulatorsShard) {
  EXPECT_SAYS(Refusal({shards_[0], Dir("whole")}), Dir("whole") + ": is a whole dataset (rendered without --shard)");
  EXPECT_SAYS(Refusal({shards_[0], Dir("nothing")}), Dir("nothing") + ": no manifest.json: not a shard folder");
  const test::TestDir old("old");
  fs::copy(shards_[1], old.str(), fs::copy_options::recursive);
  DatasetManifest m = DatasetManifest::FromJson(ReadFileBytes(old / "manifest.json"), "manifest.json");
  m.hoilcd_version = "0.1.0+sim1";
  WriteFileAtomic(old / "manifest.json", m.ToJson());
  EXPECT_SAYS(Refusal({shards_[0], old.str(), shards_[2]}), old.str() + ": is a shard rendered by hoilcd 0.1.0+sim1");
}

TEST_F(MergeRefusal, AnIncompleteShardOrOneWhoseSideFilesDiffer) {
  const test::TestDir partial("partial");
  fs::copy(shards_[1], partial.str(), fs::copy_options::recursive);
  DatasetManifest m = DatasetManifest::FromJson(ReadFileBytes(partial / "manifest.json"), "manifest.json");
  m.complete = false;
  m.files.erase("thermal/" + FrameFileName(25, "png"));
  WriteFileAtomic(partial / "manifest.json", m.ToJson());
  EXPECT_SAYS(Refusal({shards_[0], partial.str(), shards_[2]}),
              partial.str() + ": shard 1/3 is incomplete (frames 13 to 25, 12 written); re-run its hoilcd render");
  m.complete = true;
  m.files["thermal/" + FrameFileName(25, "png")] = "0";
  m.files["poses.csv"] = "0";
  WriteFileAtomic(partial / "manifest.json", m.ToJson());
  EXPECT_SAYS(Refusal({shards_[0], partial.str(), shards_[2]}),
              partial.str() + "/poses.csv: differs from " + shards_[0] + "/poses.csv");
}

TEST_F(MergeRefusal, AnOutputFolderHoldingTheUsersFilesOrAnotherDataset) {
  const test::TestDir users("users");
  WriteFileAtomic(users / "notes.txt", "mine");
  const std::string message = test::InputErrorOf([&] { MergeShards(shards_, users.str(), 0); });
  EXPECT_SAYS(message, users.str() + ": exists, is not empty and is not a hoilcd dataset (it holds notes.txt");
  EXPECT_EQ(FilesOf(users.str()).size(), 1u);
  const std::string other = test::InputErrorOf([&] { MergeShards(shards_, Dir("seed2_shard_1"), 0); });
  EXPECT_SAYS(other, Dir("seed2_shard_1") + ": holds shard 1/3, not a dataset");
  // An earlier merge of the same render is merged over.
  EXPECT_NO_THROW(MergeShards(shards_, Dir("whole"), 0));
  EXPECT_NO_THROW(Dataset::Open(Dir("whole")));
}

// Issue 45, defect 2: a merge over a longer dataset rewrote its manifest and left its later frames
// on disk. Refused, naming the folder and both frame counts.
TEST_F(MergeRefusal, AnOutputFolderHoldingADatasetOfAnotherFrameCount) {
  const test::TestDir longer("longer");
  fs::copy(Dir("whole"), longer.str(), fs::copy_options::recursive);
  DatasetManifest m = DatasetManifest::FromJson(ReadFileBytes(longer / "manifest.json"), "manifest.json");
  m.frame_count = kFrames + 1;
  WriteFileAtomic(longer / "manifest.json", m.ToJson());
  const std::string message = test::InputErrorOf([&] { MergeShards(shards_, longer.str(), 0); });
  EXPECT_SAYS(message, longer.str() + ": holds a dataset of 40 frames, but the shards are of 39");
  EXPECT_EQ(ReadFileBytes(longer / "manifest.json"), m.ToJson());
}

// Issue 45, defect 3: a merge re-run over its own output, or over what a killed merge left, made a
// second hard link of each placed frame as its temp file, which rename(2) left behind (both names
// were one file). Neither leaves a temp file, and the result is the unsharded render's bytes.
TEST_F(MergeRefusal, ARerunOverItsOwnOutputOrAfterAKillLeavesNoTempFileAndTheUnshardedBytes) {
  const test::TestDir out("rerun");
  const std::string dir = out / "merged";
  MergeShards(shards_, dir, 0);
  MergeShards(shards_, dir, 0);
  ExpectSameFiles(Dir("whole"), dir);
  // What a merge killed half way leaves: its first manifest, and a temp link of a frame it placed.
  DatasetManifest m = DatasetManifest::FromJson(ReadFileBytes(dir + "/manifest.json"), "manifest.json");
  m.complete = false;
  m.files.clear();
  WriteFileAtomic(dir + "/manifest.json", m.ToJson());
  fs::create_hard_link(dir + "/exr/000001.exr", dir + "/exr/000001.exr.tmp." + std::to_string(test::DeadPid()));
  MergeShards(shards_, dir, 0);
  ExpectSameFiles(Dir("whole"), dir);
}

TEST(ShardedRender, RefusesAnotherShardsFolderAndAVideoItCouldNotMerge) {
  const Scene scene = PaperRoom();
  const test::TestDir root("shards");
  SequenceOptions options = Options(root / "s", 0, Shard{0, 3});
  options.frames = 3;
  RenderSequence(scene, options);
  options.shard = Shard{1, 3};
  EXPECT_SAYS(test::InputErrorOf([&] { RenderSequence(scene, options); }),
              root / "s" + ": holds shard 0/3 (this render asks for shard 1/3)");
  options.shard.reset();
  EXPECT_SAYS(test::InputErrorOf([&] { RenderSequence(scene, options); }),
              "(this render asks for a whole sequence (rendered without --shard))");
  // Issue 45, defect 2: the same shard of another --frames (another range) is another folder.
  options.shard = Shard{0, 3};
  options.frames = 4;
  EXPECT_SAYS(test::InputErrorOf([&] { RenderSequence(scene, options); }),
              root / "s" + ": holds a dataset of 3 frames (this render asks for 4");
  options.frames = 3;
  options.shard.reset();
  options = Options(root / "v", 0, Shard{0, 3}, "video,persons");
  EXPECT_SAYS(test::InputErrorOf([&] { RenderSequence(scene, options); }),
              "--shard: with --outputs video,persons a shard keeps no frames");
  options.shard = Shard{3, 2};
  EXPECT_SAYS(options.Check(), "shard: the shard index must be in 0..1");
}

}  // namespace
}  // namespace hoilcd
