// A sequence of several recording runs (/runs): one dataset, each run starting at the dock with its
// own people, time of day, robot and camera noise; the first run is the scene rendered without runs.
#include <functional>
#include <set>

#include <gtest/gtest.h>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/sim/output/sequence.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

const std::string kTwoRuns = R"(runs=[{"time_of_day_h": 9, "frames": 6}, {"time_of_day_h": 15, "frames": 5}])";

Scene PaperRoom(const std::vector<std::string>& overrides) {
  return LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json", overrides);
}

Dataset Render(const Scene& scene, const std::string& dir, int threads, int frames = 0) {
  SequenceOptions options;
  options.output_dir = dir;
  options.threads = threads;
  options.frames = frames;
  EXPECT_TRUE(RenderSequence(scene, options).complete);
  return Dataset::Open(dir);
}

std::set<int> PersonIds(const Dataset& d, int first, int end) {
  std::set<int> ids;
  for (const FramePersons& f : d.persons()) {
    if (f.frame < first || f.frame >= end) continue;
    for (const PersonRecord& p : f.persons) ids.insert(p.id);
  }
  return ids;
}

TEST(RunsRender, RunsFollowEachOtherInOneDatasetEachFromTheDockWithItsOwnPeopleAndTime) {
  const test::TestDir root;
  const Dataset d = Render(PaperRoom({kTwoRuns}), root / "two", 2);
  ASSERT_EQ(d.num_frames(), 11);
  ASSERT_EQ(d.runs().size(), 2u);
  EXPECT_EQ(d.runs()[1].first_frame, 6);
  EXPECT_EQ(d.runs()[1].frames, 5);
  EXPECT_EQ(d.runs()[1].time_of_day_h, 15);
  EXPECT_EQ(d.runs()[1].start_time_s, 6 * 3600.0);
  const std::vector<PoseRecord>& poses = d.poses();
  EXPECT_EQ(poses[5].run, 0);
  EXPECT_EQ(poses[6].run, 1);
  EXPECT_DOUBLE_EQ(poses[7].time_s, 6 * 3600.0 + 0.04);
  // Each run starts at the dock, where its odometry starts.
  for (int first : {0, 6}) {
    EXPECT_NEAR(poses[first].x_m, poses[0].x_m, 1e-9);
    EXPECT_NEAR(poses[first].y_m, poses[0].y_m, 1e-9);
    EXPECT_NEAR(poses[first].odo_x_m, poses[first].x_m, 1e-9);
    EXPECT_NEAR(poses[first].odo_theta_rad, poses[first].theta_rad, 1e-9);
  }
  // Other occupants: no person of the first run is seen in the second.
  const std::set<int> first_ids = PersonIds(d, 0, 6), second_ids = PersonIds(d, 6, 11);
  ASSERT_FALSE(first_ids.empty());
  ASSERT_FALSE(second_ids.empty());
  EXPECT_GT(*second_ids.begin(), *first_ids.rbegin());
  EXPECT_GT(cv::norm(d.Thermal(0), d.Thermal(6), cv::NORM_L1), 0.0);

  // The same bytes at one thread.
  const Dataset one = Render(PaperRoom({kTwoRuns}), root / "one", 1);
  EXPECT_EQ(one.manifest().files, d.manifest().files);
}

TEST(RunsRender, TheFirstRunIsTheSceneRenderedWithoutRunsByteForByte) {
  const test::TestDir root;
  const Dataset runs = Render(PaperRoom({kTwoRuns}), root / "runs", 2);
  const Dataset plain = Render(PaperRoom({"room.sun.time_of_day_h=9"}), root / "plain", 2, 6);
  for (int f = 0; f < 6; ++f) {
    for (const std::string folder : {"thermal/", "radiometric/"}) {
      const std::string name = folder + FrameFileName(f, "png");
      EXPECT_EQ(runs.manifest().files.at(name), plain.manifest().files.at(name)) << name;
    }
    const std::string exr = "exr/" + FrameFileName(f, "exr");
    EXPECT_EQ(runs.manifest().files.at(exr), plain.manifest().files.at(exr)) << exr;
  }
  EXPECT_FALSE(plain.manifest().files.count("runs.json"));
}

TEST(RunsRender, ARunGivenTheFirstRunsSeedDrivesItsPathAndSeesItsPeople) {
  const test::TestDir root;
  const Dataset d =
      Render(PaperRoom({R"(runs=[{"time_of_day_h": 9, "frames": 5}, {"time_of_day_h": 15, "frames": 5, "seed": 1}])"}),
             root / "d", 2);
  const int offset = *PersonIds(d, 5, 10).begin() - *PersonIds(d, 0, 5).begin();
  EXPECT_GT(offset, 0);
  for (int f = 0; f < 5; ++f) {
    EXPECT_EQ(d.poses()[f].x_m, d.poses()[5 + f].x_m);
    EXPECT_EQ(d.poses()[f].odo_y_m, d.poses()[5 + f].odo_y_m);
    const std::vector<PersonRecord>& a = d.persons()[f].persons;
    const std::vector<PersonRecord>& b = d.persons()[5 + f].persons;
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].id + offset, b[i].id);
      EXPECT_EQ(a[i].box_px, b[i].box_px);
    }
  }
}

TEST(RunsRender, FramesCutInsideALaterRunListItsRenderedPart) {
  const test::TestDir root;
  const Dataset cut = Render(PaperRoom({kTwoRuns}), root / "cut", 2, 8);
  ASSERT_EQ(cut.runs().size(), 2u);
  EXPECT_EQ(cut.runs()[1].frames, 2);
  const Dataset first_only = Render(PaperRoom({kTwoRuns}), root / "first", 2, 4);
  ASSERT_EQ(first_only.runs().size(), 1u);
  EXPECT_EQ(first_only.runs()[0].frames, 4);
}

TEST(RunsRender, ARunWhoseRouteCannotBeDrivenIsNamedByCheckAndRender) {
  const Scene scene = PaperRoom({R"(runs=[{"time_of_day_h": 9, "frames": 5},
                                         {"time_of_day_h": 15, "frames": 5, "set": {"route.corner_radius_m": 5}}])"});
  const test::TestDir root;
  SequenceOptions options;
  options.output_dir = root / "d";
  for (const std::function<void()>& check :
       std::vector<std::function<void()>>{[&] { CheckSceneRenders(scene); }, [&] { RenderSequence(scene, options); }}) {
    try {
      check();
      ADD_FAILURE() << "expected an InputError";
    } catch (const InputError& e) {
      ASSERT_FALSE(e.problems().empty());
      EXPECT_EQ(e.problems()[0].where, scene.file + ": /runs/1") << e.what();
      EXPECT_NE(e.problems()[0].message.find(scene.file + ": /route"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace hoilcd
