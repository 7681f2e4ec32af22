#include "hoilcd/sim/output/sequence.h"

#include <cstdio>
#include <filesystem>
#include <functional>
#include <utility>

#include <gtest/gtest.h>
#include <unistd.h>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/dataset/frame_encoding.h"
#include "hoilcd/core/dataset/video.h"
#include "hoilcd/sim/sensor/sensor.h"
#include "processes.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

// Each test's folders live under its own test::TestDir (pid + test name).
class Sequence : public ::testing::Test {
 protected:
  std::string TempDir(const std::string& name) const { return root_ / name; }

 private:
  test::TestDir root_;
};

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

// What a render of `frames` frames into dir stopped after its first `written` leaves: those frames'
// files (and maybe later ones, unlisted), listed by a manifest that says it is partial. Made from
// shard 0/1 of the sequence, whose frames are the render's bytes, with thermal PNGs uncompressed as
// while a render runs (video mode replaces them only at the end).
void RenderStoppedAfter(const Scene& scene, const std::string& dir, int frames, int written,
                        const std::string& outputs = "thermal,radiometric,exr,video,persons") {
  SequenceOptions options;
  options.output_dir = dir;
  options.frames = frames;
  options.outputs = outputs;
  options.shard = Shard{0, 1};
  RenderSequence(scene, options);
  DatasetManifest m = DatasetManifest::FromJson(ReadFileBytes(dir + "/manifest.json"), "manifest.json");
  m.shard.reset();
  m.complete = false;
  for (auto it = m.files.begin(); it != m.files.end();) {
    const size_t slash = it->first.find('/');
    const bool kept = slash != std::string::npos && std::stoi(it->first.substr(slash + 1, 6)) < written;
    it = kept ? std::next(it) : m.files.erase(it);
  }
  WriteFileAtomic(dir + "/manifest.json", m.ToJson());
}

TEST_F(Sequence, SameSceneAndSeedGiveByteIdenticalDatasetsAtOneAndTwoThreads) {
  const Scene scene = PaperRoom();
  const DatasetManifest one = Render(scene, TempDir("t1"), 4, 1);
  const DatasetManifest two = Render(scene, TempDir("t2"), 4, 2);
  EXPECT_EQ(one.files, two.files);
  EXPECT_EQ(one.files.size(), 4u * 3 + 7);  // three files a frame + seven side files
  EXPECT_EQ(one.files.at("thermal.mp4"), two.files.at("thermal.mp4"));
  EXPECT_EQ(one.files.count("footprints.json"), 1u);
  EXPECT_TRUE(one.complete);
}

// A FLIR Lepton 3.5 (camera.profile): 160 × 120 frames at 8.7 Hz through every file that holds
// the size or the rate.
TEST_F(Sequence, ALeptonProfileRenders160By120FramesAt8Point7Hz) {
  const Scene scene = LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/lepton_room.json");
  const std::string dir = TempDir("lepton");
  const DatasetManifest manifest = Render(scene, dir, 3, 0);
  EXPECT_EQ(manifest.intrinsics.width, 160);
  EXPECT_EQ(manifest.intrinsics.height, 120);
  EXPECT_EQ(manifest.frame_rate_hz, 8.7);
  const Dataset dataset = Dataset::Open(dir);
  EXPECT_EQ(dataset.Thermal(2).size(), cv::Size(160, 120));
  EXPECT_EQ(dataset.RadiometricCentikelvin(2).size(), cv::Size(160, 120));
  ASSERT_EQ(dataset.poses().size(), 3u);
  EXPECT_EQ(dataset.poses()[2].time_s, 2 / 8.7);
  const DecodedVideo video = DecodeVideo(ReadFileBytes(dir + "/thermal.mp4"), "thermal.mp4");
  EXPECT_EQ(video.width, 160);
  EXPECT_EQ(video.height, 120);
  EXPECT_NEAR(video.frame_rate_hz, 8.7, 1e-9);
  EXPECT_EQ(video.frames.size(), 3u);
  const nlohmann::json resolved = nlohmann::json::parse(ReadFileBytes(dir + "/scene.json"));
  EXPECT_EQ(resolved["camera"]["profile"], "flir_lepton_3_5");
  EXPECT_EQ(resolved["frame_rate_hz"].get<double>(), 8.7);
}

TEST_F(Sequence, WalkersPlannedInFreeSpaceGiveByteIdenticalDatasetsAtOneAndTwoThreads) {
  const Scene scene = LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/open_room.json", {"crowd.walkers=4"});
  const DatasetManifest one = Render(scene, TempDir("w1"), 3, 1);
  const DatasetManifest two = Render(scene, TempDir("w2"), 3, 2);
  EXPECT_EQ(one.files, two.files);
  // A walker is in view (keeping pace ahead of the robot).
  EXPECT_NE(ReadFileBytes(TempDir("w1") + "/persons.json").find("\"ahead\""), std::string::npos);
}

TEST_F(Sequence, AnotherSeedChangesNoiseCrowdAndOdometry) {
  const DatasetManifest a = Render(PaperRoom(), TempDir("s1"), 2, 0);
  const DatasetManifest b = Render(PaperRoom({"seed=2"}), TempDir("s2"), 2, 0);
  EXPECT_NE(a.files.at("thermal/000000.png"), b.files.at("thermal/000000.png"));
  EXPECT_NE(a.files.at("poses.csv"), b.files.at("poses.csv"));
  EXPECT_NE(a.files.at("scene.json"), b.files.at("scene.json"));
}

TEST_F(Sequence, ResumingAnInterruptedRenderGivesTheSameBytesAsOneRun) {
  const Scene scene = PaperRoom();
  const DatasetManifest whole = Render(scene, TempDir("whole"), 6, 0);
  const std::string dir = TempDir("resumed");
  RenderStoppedAfter(scene, dir, 6, 4);
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
  // The whole run encoded thermal.mp4 while writing; the resumed one from the EXRs on disk.
  EXPECT_EQ(Dataset::Open(dir).manifest().files.at("thermal.mp4"), whole.files.at("thermal.mp4"));
}

// What `ffprobe` says about the first video stream of `path` ("" when ffprobe is missing).
std::string Ffprobe(const std::string& path) {
  const std::string command =
      "ffprobe -v error -select_streams v:0 -count_frames -show_entries "
      "stream=codec_name,width,height,r_frame_rate,nb_read_frames -of csv=p=0 '" +
      path + "' 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return "";
  std::string out;
  char buffer[256];
  while (fgets(buffer, sizeof(buffer), pipe) != nullptr) out += buffer;
  pclose(pipe);
  return out;
}

TEST_F(Sequence, FfprobeReadsThermalMp4AsH264256x192At25FpsWithOneFramePerFrame) {
  if (std::system("ffprobe -version > /dev/null 2>&1") != 0) GTEST_SKIP() << "ffprobe (Debian ffmpeg) not installed";
  const std::string dir = TempDir("ffprobe");
  Render(PaperRoom(), dir, 7, 0);
  EXPECT_EQ(Ffprobe(dir + "/thermal.mp4"), "h264,256,192,25/1,7\n");
}

// The frame PNGs (libdeflate, core/util/png.h) pass pngcheck, a checker independent of libpng.
TEST_F(Sequence, FramePngsPassPngcheck) {
  if (std::system("command -v pngcheck > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "pngcheck (Debian pngcheck) not installed";
  const std::string dir = TempDir("pngcheck");
  Render(PaperRoom(), dir, 2, 0);
  for (const char* folder : {"thermal", "radiometric"}) {
    const std::string png = dir + "/" + folder + "/000001.png";
    EXPECT_EQ(std::system(("pngcheck -q '" + png + "' > /dev/null").c_str()), 0) << png;
  }
  WriteFileAtomic(dir + "/cut.png", ReadFileBytes(dir + "/thermal/000001.png").substr(0, 500));
  EXPECT_NE(std::system(("pngcheck -q '" + dir + "/cut.png' > /dev/null").c_str()), 0);
}

TEST_F(Sequence, VideoModeThermalFramesAreTheDecodedVideoWithinTheDocumentedPsnr) {
  const Scene scene = PaperRoom({"camera.video.enabled=true"});
  const std::string whole_dir = TempDir("video_whole");
  const DatasetManifest whole = Render(scene, whole_dir, 6, 0);
  const Dataset d = Dataset::Open(whole_dir);
  const DecodedVideo video = DecodeVideo(ReadFileBytes(whole_dir + "/thermal.mp4"), "thermal.mp4");
  ASSERT_EQ(video.frames.size(), 6u);
  for (int f = 0; f < 6; ++f) {
    const cv::Mat read = d.Thermal(f);  // what every method reads
    EXPECT_EQ(cv::norm(read, video.frames[f], cv::NORM_INF), 0.0) << f;
    cv::Mat uncompressed;
    for (const auto& [name, channel] : ReadDatasetExr(d, f)) {
      if (name == "T") uncompressed = ToDisplay8Bit(channel, 20.0, 30.0);
    }
    ASSERT_FALSE(uncompressed.empty());
    EXPECT_GT(cv::norm(read, uncompressed, cv::NORM_INF), 0.0) << f;
    // Documented range (schema, camera.video): CRF 23 keeps these frames at 35–50 dB.
    const double psnr_db = cv::PSNR(read, uncompressed);
    EXPECT_GT(psnr_db, 35.0) << f;
    EXPECT_LT(psnr_db, 50.0) << f;
  }
  // Resuming a video-mode render stopped after 4 frames gives the same dataset, decoded frames included.
  const std::string dir = TempDir("video_resumed");
  RenderStoppedAfter(scene, dir, 6, 4);
  EXPECT_EQ(Render(scene, dir, 6, 0).files, whole.files);
}

TEST_F(Sequence, FramesFrozenByAnFfcRepeatTheFrameBeforeAndAreListedInEvents) {
  // An FFC every second lands on frame 25; 0.12 s at 25 Hz freezes frames 25–27.
  const Scene scene = PaperRoom({"camera.ffc_interval_s=1", "camera.ffc_freeze_s=0.12"});
  const std::string dir = TempDir("freeze");
  const DatasetManifest m = Render(scene, dir, 29, 0);
  for (const char* folder : {"thermal/", "radiometric/"}) {
    for (int f = 25; f <= 27; ++f) {
      EXPECT_EQ(m.files.at(folder + FrameFileName(f, "png")), m.files.at(folder + FrameFileName(24, "png")))
          << folder << f;
    }
    EXPECT_NE(m.files.at(folder + FrameFileName(28, "png")), m.files.at(folder + FrameFileName(24, "png")));
    EXPECT_NE(m.files.at(folder + FrameFileName(24, "png")), m.files.at(folder + FrameFileName(23, "png")));
  }
  std::vector<int> frozen;
  const Dataset dataset = Dataset::Open(dir);
  for (const DatasetEvent& e : dataset.events()) {
    if (e.type == "freeze") frozen.push_back(e.frame);
  }
  EXPECT_EQ(frozen, (std::vector<int>{25, 26, 27}));
}

TEST_F(Sequence, MissingOrDamagedVideoLeavesTheDatasetReadableWithAWarning) {
  const std::string dir = TempDir("bad_video");
  Render(PaperRoom(), dir, 2, 0);
  EXPECT_TRUE(Dataset::Open(dir).warnings().empty());
  WriteFileAtomic(dir + "/thermal.mp4", "damaged");
  Dataset damaged = Dataset::Open(dir);
  ASSERT_EQ(damaged.warnings().size(), 1u);
  EXPECT_NE(damaged.warnings()[0].find("thermal.mp4: checksum mismatch"), std::string::npos) << damaged.warnings()[0];
  EXPECT_EQ(damaged.Thermal(1).cols, 256);
  fs::remove(dir + "/thermal.mp4");
  const Dataset missing = Dataset::Open(dir);
  ASSERT_EQ(missing.warnings().size(), 1u);
  EXPECT_NE(missing.warnings()[0].find("thermal.mp4: listed in manifest.json but missing"), std::string::npos)
      << missing.warnings()[0];
}

TEST_F(Sequence, CancelLeavesAResumableDatasetThatReadersRejectAsPartial) {
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

TEST_F(Sequence, RefusesToWriteIntoAFolderItDidNotMake) {
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

TEST_F(Sequence, RefusesAFolderHoldingTheUsersFilesNamedLikeDatasetFilesAndLeavesThem) {
  const std::string dir = TempDir("named_like_ours");
  fs::create_directories(dir);
  WriteFileAtomic(dir + "/scene.json", "{\"my\": \"scene\"}");
  WriteFileAtomic(dir + "/poses.csv", "my,poses\n");
  SequenceOptions options;
  options.output_dir = dir;
  options.frames = 1;
  try {
    RenderSequence(PaperRoom(), options);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("poses.csv and scene.json"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ReadFileBytes(dir + "/scene.json"), "{\"my\": \"scene\"}");
  EXPECT_EQ(ReadFileBytes(dir + "/poses.csv"), "my,poses\n");
  EXPECT_FALSE(fs::exists(dir + "/manifest.json"));
}

TEST_F(Sequence, GroundTruthFilesDescribeTheFrames) {
  const std::string dir = TempDir("gt");
  Render(PaperRoom(), dir, 3, 0);
  const Dataset d = Dataset::Open(dir);
  ASSERT_EQ(d.poses().size(), 3u);
  EXPECT_DOUBLE_EQ(d.poses()[1].time_s, 0.04);
  EXPECT_EQ(d.manifest().intrinsics.width, 256);
  EXPECT_TRUE(d.manifest().classes.count("person"));
  ASSERT_EQ(d.persons().size(), 3u);
  const ExrChannels exr = ReadDatasetExr(d, 0);
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
TEST_F(Sequence, CameraVibrationMovesTheRenderedViewAndIsWrittenToThePoses) {
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

TEST_F(Sequence, ResumesAFolderWhereAKillLeftOnlyTheFirstManifestsTempFile) {
  // What `strace -e inject=rename:signal=SIGKILL:when=1 hoilcd render` leaves behind.
  const std::string dir = TempDir("first_manifest_killed");
  fs::create_directories(dir);
  const std::string temp = dir + "/manifest.json.tmp." + std::to_string(test::DeadPid());
  WriteFileAtomic(temp, "{\"hoilcd_version\"");
  Render(PaperRoom(), dir, 1, 0);
  EXPECT_FALSE(fs::exists(temp));
}

TEST_F(Sequence, ResumingDeletesOnlyItsOwnTempFiles) {
  const std::string dir = TempDir("own_temp");
  Render(PaperRoom(), dir, 2, 0);
  WriteFileAtomic(dir + "/notes.tmp.txt", "mine");
  const std::string temp = dir + "/thermal/000001.png.tmp." + std::to_string(test::DeadPid());
  WriteFileAtomic(temp, "half a frame");
  Render(PaperRoom(), dir, 2, 0);
  EXPECT_EQ(ReadFileBytes(dir + "/notes.tmp.txt"), "mine");
  EXPECT_FALSE(fs::exists(temp));
}

// Issue 45, defect 2: a render with another --frames over a finished dataset rewrote its manifest
// and left the other frames on disk, unlisted. The frame count is part of the folder's identity:
// refused, naming the folder and both counts, and the folder is left as it was.
TEST_F(Sequence, AnotherFrameCountOverADatasetIsRefusedNamingBothCounts) {
  const Scene scene = PaperRoom();
  const std::string dir = TempDir("three");
  const DatasetManifest three = Render(scene, dir, 3, 0);
  for (int frames : {2, 4}) {
    SequenceOptions options;
    options.output_dir = dir;
    options.frames = frames;
    try {
      RenderSequence(scene, options);
      ADD_FAILURE() << "--frames " << frames << " over a dataset of 3 frames was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(dir + ": holds a dataset of 3 frames (this render asks for " +
                                           std::to_string(frames)),
                std::string::npos)
          << e.what();
    }
    EXPECT_EQ(Dataset::Open(dir).manifest().files, three.files);
  }
  EXPECT_FALSE(fs::exists(dir + "/thermal/000003.png"));
  EXPECT_FALSE(fs::exists(dir + "/hoilcd.lock"));
}

TEST_F(Sequence, RefusalNamesTheFilesThatAreNotItsOwn) {
  const std::string dir = TempDir("named");
  fs::create_directories(dir);
  WriteFileAtomic(dir + "/thesis.tex", "precious");
  WriteFileAtomic(dir + "/manifest.json.tmp.1", "");
  SequenceOptions options;
  options.output_dir = dir;
  options.frames = 1;
  try {
    RenderSequence(PaperRoom(), options);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("it holds thesis.tex and no manifest.json)"), std::string::npos) << e.what();
  }
}

TEST_F(Sequence, OutputsLeaveOutWhatWasNotAskedForAndTheManifestAndReadersSaySo) {
  const std::string dir = TempDir("thermal_video");
  SequenceOptions options;
  options.output_dir = dir;
  options.frames = 3;
  options.outputs = "video,thermal";
  RenderSequence(PaperRoom(), options);
  const Dataset d = Dataset::Open(dir);
  EXPECT_EQ(d.manifest().outputs.ToText(), "thermal,video");
  EXPECT_NE(ReadFileBytes(dir + "/manifest.json").find("\"outputs\": [\n    \"thermal\",\n    \"video\"\n  ]"),
            std::string::npos);
  EXPECT_EQ(d.manifest().files.size(), 3u + 6);  // three thermal PNGs, thermal.mp4, five side files
  EXPECT_FALSE(fs::exists(dir + "/exr"));
  EXPECT_FALSE(fs::exists(dir + "/radiometric"));
  EXPECT_FALSE(fs::exists(dir + "/persons.json"));
  EXPECT_EQ(d.Thermal(2).cols, 256);
  for (const auto& [what, read] : std::vector<std::pair<std::string, std::function<void()>>>{
           {"radiometric", [&] { d.RadiometricC(0); }}, {"persons", [&] { d.persons(); }}, {"exr", [&] {
                                                                                              ReadDatasetExr(d, 0);
                                                                                            }}}) {
    try {
      read();
      ADD_FAILURE() << what << ": expected an InputError";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("has no " + what + " output"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("--outputs thermal,video"), std::string::npos) << e.what();
    }
  }
  // Resuming with other outputs would mix datasets.
  options.outputs = "thermal";
  try {
    RenderSequence(PaperRoom(), options);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("holds a dataset with --outputs thermal,video"), std::string::npos)
        << e.what();
  }
}

TEST_F(Sequence, ResumingWithoutExrsGivesTheSameBytesAsOneRun) {
  // Kept frames' people come from casting them again, the video from their thermal PNGs.
  const Scene scene = PaperRoom();
  SequenceOptions options;
  options.outputs = "thermal,video,persons";
  options.output_dir = TempDir("whole");
  options.frames = 5;
  RenderSequence(scene, options);
  options.output_dir = TempDir("resumed");
  RenderStoppedAfter(scene, options.output_dir, 5, 3, options.outputs);
  const SequenceResult r = RenderSequence(scene, options);
  EXPECT_EQ(r.frames_reused, 3);
  EXPECT_EQ(Dataset::Open(TempDir("resumed")).manifest().files, Dataset::Open(TempDir("whole")).manifest().files);
}

TEST(SequenceOptions, CheckNamesEveryWrongFlagAndRenderRejectsThem) {
  SequenceOptions options;
  EXPECT_EQ(options.checkpoint_every_frames, 25);
  EXPECT_NE(options.Check().find("output_dir: an output folder is required"), std::string::npos) << options.Check();
  options.output_dir = "out";
  EXPECT_EQ(options.Check(), "");
  options.frames = -1;
  EXPECT_NE(options.Check().find("frames: must be in [0, 1000000] frames"), std::string::npos) << options.Check();
  options.frames = 0;
  options.checkpoint_every_frames = 0;
  EXPECT_NE(options.Check().find("checkpoint_every_frames: must be at least 1"), std::string::npos) << options.Check();
  options.checkpoint_every_frames = 25;
  options.threads = -2;
  EXPECT_NE(options.Check().find("threads: must be at least 0"), std::string::npos) << options.Check();
  options.threads = 0;
  options.outputs = "thermal,depth";
  EXPECT_NE(options.Check().find("outputs: unknown output 'depth'"), std::string::npos) << options.Check();
  options.outputs = "exr,exr";
  EXPECT_NE(options.Check().find("output 'exr' is listed twice"), std::string::npos) << options.Check();
  options.outputs = "";
  EXPECT_NE(options.Check().find("expected at least one of"), std::string::npos) << options.Check();
  EXPECT_THROW(RenderSequence(PaperRoom(), options), InputError);
}

TEST_F(Sequence, RouteProblemsFoundWhileSimulatingNameTheSceneFile) {
  SequenceOptions options;
  options.output_dir = TempDir("route");
  options.frames = 1;
  const Scene scene = PaperRoom({"route.corner_radius_m=5"});
  try {
    RenderSequence(scene, options);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problems().at(0).where, scene.file + ": /route") << e.what();
  }
}

}  // namespace
}  // namespace hoilcd
