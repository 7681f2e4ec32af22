#include "hoilcd/sim/render/visibility.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hoilcd/sim/render/renderer.h"
#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/scene/scene_options.h"
#include "planned_world.h"

namespace hoilcd {
namespace {

// Pixels a person covers alone, by the definition: one single ray per pixel of the image
// against each body part alone (IntersectInstance), no windows, no packets.
int AlonePixelsBySingleRays(const World& world, const CameraIntrinsics& intrinsics, const CameraPose& pose,
                            const Person& person) {
  const Rigid3 world_from_cam = pose.WorldFromCam();
  const Eigen::Matrix3f R = world_from_cam.rotation.toRotationMatrix().cast<float>();
  const Eigen::Vector3f origin = world_from_cam.translation.cast<float>();
  int alone = 0;
  for (int y = 0; y < intrinsics.height; ++y) {
    for (int x = 0; x < intrinsics.width; ++x) {
      const Eigen::Vector3f d = (R * intrinsics.Unproject(x, y).cast<float>()).normalized();
      for (int part : person.parts) {
        if (world.caster().IntersectInstance(part, origin, d).hit()) {
          ++alone;
          break;
        }
      }
    }
  }
  return alone;
}

// paper_room's world with the robot's run and the crowd planned, and a renderer of it.
class VisiblePersonsTest : public ::testing::Test {
 protected:
  test::PlannedWorld planned{LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json")};
  World& world = planned.world;
  const RobotRun& run = planned.run;
  const CameraIntrinsics intrinsics = IntrinsicsFromScene(planned.scene);
  const FrameRenderer renderer{world, intrinsics, RenderOptionsFromScene(planned.scene, 2)};
};

TEST_F(VisiblePersonsTest, VisibleFractionIsVisiblePixelsOverThePixelsEachPersonCoversAloneBySingleRays) {
  int checked = 0, occluded = 0;
  for (const int f : {300, 1200, 1900}) {
    world.SetTime(run.samples[f].time_s);
    const CameraPose& pose = run.samples[f].camera;
    const FrameBuffers frame = renderer.Render(pose);
    for (const PersonRecord& record : VisiblePersons(world, intrinsics, pose, frame.instance, frame.depth_m)) {
      const auto person = std::find_if(world.people().begin(), world.people().end(),
                                       [&](const Person& p) { return p.person_id == record.id; });
      ASSERT_NE(person, world.people().end());
      const int visible = cv::countNonZero(frame.instance == person->instance);
      const int alone = std::max(visible, AlonePixelsBySingleRays(world, intrinsics, pose, *person));
      ASSERT_GT(alone, 0);
      EXPECT_DOUBLE_EQ(record.visible_fraction, static_cast<double>(visible) / alone)
          << "frame " << f << " person " << record.id;
      ++checked;
      occluded += record.visible_fraction < 1.0;
    }
  }
  EXPECT_GT(checked, 10);
  EXPECT_GT(occluded, 3);
}

TEST_F(VisiblePersonsTest, KeypointVisibilityIsThatOfSingleRaysAndTheRecordsDoNotDependOnThreads) {
  int visible = 0, hidden = 0;
  for (const int f : {150, 300, 700, 1200, 1500, 1900}) {
    world.SetTime(run.samples[f].time_s);
    const CameraPose& pose = run.samples[f].camera;
    const FrameBuffers frame = renderer.Render(pose);
    const std::vector<PersonRecord> one = VisiblePersons(world, intrinsics, pose, frame.instance, frame.depth_m, 1);
    const std::vector<PersonRecord> two = VisiblePersons(world, intrinsics, pose, frame.instance, frame.depth_m, 2);
    EXPECT_EQ(PersonsToJson({{f, one}}), PersonsToJson({{f, two}})) << "frame " << f;
    // The definition, one ray per keypoint and body part: visible when nothing in the depth
    // buffer is closer than the person's own surface along the keypoint pixel's ray.
    const Rigid3 world_from_cam = pose.WorldFromCam();
    const Eigen::Matrix3f R = world_from_cam.rotation.toRotationMatrix().cast<float>();
    const Eigen::Vector3f origin = world_from_cam.translation.cast<float>();
    for (const PersonRecord& record : one) {
      const auto person = std::find_if(world.people().begin(), world.people().end(),
                                       [&](const Person& p) { return p.person_id == record.id; });
      ASSERT_NE(person, world.people().end());
      for (const KeypointRecord& kp : record.keypoints) {
        if (kp.u_px < -0.5 || kp.v_px < -0.5 || kp.u_px >= intrinsics.width - 0.5 ||
            kp.v_px >= intrinsics.height - 0.5) {
          EXPECT_FALSE(kp.visible);
          continue;
        }
        const int u = std::clamp(static_cast<int>(std::lround(kp.u_px)), 0, intrinsics.width - 1);
        const int v = std::clamp(static_cast<int>(std::lround(kp.v_px)), 0, intrinsics.height - 1);
        const Eigen::Vector3f ray = intrinsics.Unproject(u, v).cast<float>().normalized();
        float own = std::numeric_limits<float>::infinity();
        for (int part : person->parts)
          own = std::min(own, world.caster().IntersectInstance(part, origin, R * ray).distance_m);
        const bool expected = std::isfinite(own) && frame.depth_m.at<float>(v, u) >= own * ray.z() - 0.01f;
        EXPECT_EQ(kp.visible, expected) << "frame " << f << " person " << record.id << " " << kp.name;
        (expected ? visible : hidden)++;
      }
    }
  }
  EXPECT_GT(visible, 50) << hidden;
  EXPECT_GT(hidden, 20) << visible;
}

}  // namespace
}  // namespace hoilcd
