#include "hoilcd/sim/sequence.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include "hoilcd/core/dataset.h"
#include "hoilcd/sim/exr_io.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

std::string TempDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("hoilcd_sequence_test_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  return dir.string();
}

Scene PaperRoom(const std::vector<std::string>& overrides = {}) {
  return LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json", overrides);
}

DatasetManifest Render(const Scene& scene, const std::string& dir, int frames, int threads) {
  SequenceOptions options;
  options.output_dir = dir;
  options.frames = frames;
  options.threads = threads;
  RenderSequence(scene, options);
  return Dataset::Open(dir).manifest();
}

TEST(Sequence, SameSceneAndSeedGiveByteIdenticalDatasetsAtOneAndTwoThreads) {
  const Scene scene = PaperRoom();
  const DatasetManifest one = Render(scene, TempDir("t1"), 4, 1);
  const DatasetManifest two = Render(scene, TempDir("t2"), 4, 2);
  EXPECT_EQ(one.files, two.files);
  EXPECT_EQ(one.files.size(), 4u * 3 + 5);  // three files a frame + five side files
  EXPECT_TRUE(one.complete);
}

TEST(Sequence, AnotherSeedChangesNoiseCrowdAndOdometry) {
  const DatasetManifest a = Render(PaperRoom(), TempDir("s1"), 2, 0);
  const DatasetManifest b = Render(PaperRoom({"seed=2"}), TempDir("s2"), 2, 0);
  EXPECT_NE(a.files.at("thermal/000000.png"), b.files.at("thermal/000000.png"));
  EXPECT_NE(a.files.at("poses.csv"), b.files.at("poses.csv"));
  EXPECT_NE(a.files.at("scene.json"), b.files.at("scene.json"));
}

TEST(Sequence, ResumingAShorterRenderGivesTheSameBytesAsOneRun) {
  const Scene scene = PaperRoom();
  const DatasetManifest whole = Render(scene, TempDir("whole"), 6, 0);
  const std::string dir = TempDir("resumed");
  Render(scene, dir, 4, 0);
  // Damage two finished frames apart: the resumed run must notice and render both again.
  WriteFileAtomic(dir + "/thermal/000001.png", "not a png");
  WriteFileAtomic(dir + "/exr/000003.exr", "not an exr");
  SequenceOptions options;
  options.output_dir = dir;
  options.frames = 6;
  const SequenceResult r = RenderSequence(scene, options);
  EXPECT_EQ(r.frames_reused, 2);
  EXPECT_EQ(r.frames_rendered, 4);
  EXPECT_EQ(Dataset::Open(dir).manifest().files, whole.files);
}

TEST(Sequence, CancelLeavesAResumableDatasetThatReadersRejectAsPartial) {
  const Scene scene = PaperRoom();
  const std::string dir = TempDir("cancel");
  std::atomic<bool> cancel{true};
  SequenceOptions options;
  options.output_dir = dir;
  options.frames = 3;
  options.cancel = &cancel;
  EXPECT_THROW(RenderSequence(scene, options), RenderInterrupted);
  try {
    Dataset::Open(dir);
    FAIL() << "a partial dataset must not open";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("partial"), std::string::npos) << e.what();
  }
  options.cancel = nullptr;
  EXPECT_TRUE(RenderSequence(scene, options).complete);
  EXPECT_NO_THROW(Dataset::Open(dir));
}

TEST(Sequence, RefusesToWriteIntoAFolderItDidNotMake) {
  const std::string dir = TempDir("foreign");
  fs::create_directories(dir);
  WriteFileAtomic(dir + "/thesis.tex", "precious");
  SequenceOptions options;
  options.output_dir = dir;
  options.frames = 1;
  EXPECT_THROW(RenderSequence(PaperRoom(), options), InputError);
  EXPECT_EQ(ReadFileBytes(dir + "/thesis.tex"), "precious");
  // A dataset of another scene is not overwritten either.
  const std::string other = TempDir("other");
  Render(PaperRoom(), other, 1, 0);
  options.output_dir = other;
  EXPECT_THROW(RenderSequence(PaperRoom({"crowd.people_per_table=2"}), options), InputError);
}

TEST(Sequence, GroundTruthFilesDescribeTheFrames) {
  const std::string dir = TempDir("gt");
  Render(PaperRoom(), dir, 3, 0);
  const Dataset d = Dataset::Open(dir);
  ASSERT_EQ(d.poses().size(), 3u);
  EXPECT_DOUBLE_EQ(d.poses()[1].time_s, 0.04);
  EXPECT_EQ(d.manifest().intrinsics.width, 256);
  EXPECT_TRUE(d.manifest().classes.count("person"));
  ASSERT_EQ(d.persons().size(), 3u);
  const ExrChannels exr = ReadExr(dir + "/exr/000000.exr");
  std::vector<std::string> names;
  for (const auto& [name, channel] : exr) names.push_back(name);
  for (const char* c : {"T", "T_true", "Z", "id", "class"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), c), names.end()) << c;
  }
  for (const FramePersons& f : d.persons()) {
    for (const PersonRecord& p : f.persons) {
      EXPECT_GE(p.visible_fraction, 0.0);
      EXPECT_LE(p.visible_fraction, 1.0);
      EXPECT_NEAR(p.occlusion_fraction, 1.0 - p.visible_fraction, 1e-9);
      EXPECT_GE(p.box_px.x, 0);
      EXPECT_LE(p.box_px.x + p.box_px.width, 256);
      EXPECT_FALSE(p.contacts.empty());
    }
  }
}

// The mount's vibration moves the camera that renders the frame, and poses.csv / poses_tum.txt say
// where it was; the base's path does not depend on it.
TEST(Sequence, CameraVibrationMovesTheRenderedViewAndIsWrittenToThePoses) {
  const std::string shaking_dir = TempDir("vibration_on"), rigid_dir = TempDir("vibration_off");
  Render(PaperRoom(), shaking_dir, 3, 0);
  Render(PaperRoom({"robot.vibration.enabled=false"}), rigid_dir, 3, 0);
  const Dataset shaking = Dataset::Open(shaking_dir), rigid = Dataset::Open(rigid_dir);
  const PoseRecord &a = shaking.poses()[2], &b = rigid.poses()[2];
  EXPECT_EQ(a.x_m, b.x_m);
  EXPECT_EQ(a.theta_rad, b.theta_rad);
  EXPECT_NE(a.cam_pitch_rad, b.cam_pitch_rad);
  EXPECT_NE(a.cam_roll_rad, b.cam_roll_rad);
  EXPECT_EQ(b.cam_roll_rad, 0.0);
  EXPECT_NE(shaking.manifest().files.at("exr/000002.exr"), rigid.manifest().files.at("exr/000002.exr"));
  EXPECT_NE(shaking.manifest().files.at("poses_tum.txt"), rigid.manifest().files.at("poses_tum.txt"));
}

}  // namespace
}  // namespace hoilcd
