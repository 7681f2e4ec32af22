#include "hoilcd/sim/render/renderer.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/scene/scene_options.h"
#include "hoilcd/sim/sensor/sensor.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

using nlohmann::json;

// A closed room, every surface and the surroundings at 25 °C, with mixed emissivities and a
// specular floor: Kirchhoff says the camera must read 25 °C everywhere.
TEST(Renderer, IsothermalEnclosureRendersItsTemperatureWhateverTheEmissivities) {
  json doc = {{"tables", json::array()},
              {"objects", json::array()},
              {"room",
               {{"environment_temperature_c", 25.0},
                {"floor", {{"temperature_c", 25.0}, {"emissivity", 0.3}, {"specular", true}}},
                {"ceiling", {{"temperature_c", 25.0}, {"emissivity", 0.95}}},
                {"walls", {{"temperature_bottom_c", 25.0}, {"temperature_top_c", 25.0}, {"emissivity", 0.6}}},
                {"windows",
                 {{{"wall", "north"},
                   {"center_m", 2.0},
                   {"bottom_m", 0.5},
                   {"width_m", 1.0},
                   {"height_m", 1.0},
                   {"temperature_c", 25.0},
                   {"emissivity", 0.5}}}},
                {"surfaces",
                 {{"thermal_bridges", false},
                  {"radiator_plume", false},
                  {"glass_from_u_value", false},
                  {"window_frames", false},
                  {"texture", false}}},
                {"sun", {{"enabled", false}}},
                {"hvac", {{"enabled", false}}}}}};
  const Scene scene = SceneFromJson(doc, "iso.json");
  const BandRadianceTable table;
  World world(scene, table);
  FrameRenderer renderer(world, IntrinsicsFromScene(scene), RenderOptionsFromScene(scene, 1));
  CameraPose pose;
  pose.x_m = 1.0, pose.y_m = 1.5, pose.z_m = 0.6, pose.pitch_rad = 0.3;
  const FrameBuffers frame = renderer.Render(pose);
  SensorOptions ideal;
  SensorModel sensor(ideal, frame.radiance.cols, frame.radiance.rows, 25, 1, &table);
  const cv::Mat t = sensor.IdealTemperature(frame.radiance);
  double lo, hi;
  cv::minMaxLoc(t, &lo, &hi);
  EXPECT_NEAR(lo, 25.0, 0.01);
  EXPECT_NEAR(hi, 25.0, 0.01);
}

class PaperRoomView : public ::testing::Test {
 protected:
  // The robot's camera at the west end of the route, looking along the table row (+x).
  static CameraPose CorridorPose() {
    CameraPose pose;
    pose.x_m = 0.4, pose.y_m = 1.5, pose.z_m = 0.95;
    pose.yaw_rad = 0.0, pose.pitch_rad = 8.0 * M_PI / 180.0;
    return pose;
  }
};

TEST_F(PaperRoomView, RenderIsIdenticalAtOneAndTwoThreads) {
  const Scene scene = LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json");
  const BandRadianceTable table;
  World world(scene, table);
  FrameRenderer one(world, IntrinsicsFromScene(scene), RenderOptionsFromScene(scene, 1));
  FrameRenderer two(world, IntrinsicsFromScene(scene), RenderOptionsFromScene(scene, 2));
  const FrameBuffers a = one.Render(CorridorPose()), b = two.Render(CorridorPose());
  EXPECT_EQ(cv::norm(a.radiance, b.radiance, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.instance, b.instance, cv::NORM_INF), 0.0);
  EXPECT_GT(a.edge_pixels, 100);
}

TEST_F(PaperRoomView, PacketCastsHitWhatSingleRaysHitWithAndWithoutTheRestOfTheScene) {
  const Scene scene = LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json");
  const BandRadianceTable table;
  World world(scene, table);
  const RayCaster& caster = world.caster();
  const CameraIntrinsics intrinsics = IntrinsicsFromScene(scene);
  const Rigid3 world_from_cam = CorridorPose().WorldFromCam();
  const Eigen::Matrix3f R = world_from_cam.rotation.toRotationMatrix().cast<float>();
  const Eigen::Vector3f origin = world_from_cam.translation.cast<float>();
  // The instance seen in the middle of the image, cast against alone.
  const RayHit centre = caster.Intersect(origin, R * Eigen::Vector3f::UnitZ());
  ASSERT_TRUE(centre.hit());
  const int part = centre.instance;
  int hits = 0, part_hits = 0;
  for (int by = 0; by < intrinsics.height; by += 4) {
    for (int bx = 0; bx < intrinsics.width; bx += 4) {
      Eigen::Vector3f directions[kRayPacketSize], origins[kRayPacketSize];
      for (int i = 0; i < kRayPacketSize; ++i) {
        directions[i] = (R * intrinsics.Unproject(bx + i % 4, by + i / 4).cast<float>()).normalized();
        origins[i] = origin + 0.01f * i * directions[i];
      }
      const int count = 1 + (bx / 4) % kRayPacketSize;  // partial packets too
      RayHitPacket packet, from_origins, alone;
      caster.IntersectPacket(origin, directions, count, &packet);
      caster.IntersectPacket(origins, directions, count, &from_origins);
      caster.IntersectInstancePacket(part, origin, directions, count, &alone);
      for (int i = 0; i < count; ++i) {
        const RayHit single = caster.Intersect(origin, directions[i]);
        ASSERT_EQ(packet.instance[i], single.instance);
        ASSERT_EQ(packet.triangle[i], single.triangle);
        ASSERT_EQ(packet.distance_m[i], single.distance_m);
        const RayHit full = caster.Hit(packet, i, directions[i]);
        ASSERT_EQ(full.normal_world, single.normal_world);
        const RayHit shifted = caster.Intersect(origins[i], directions[i]);
        ASSERT_EQ(from_origins.instance[i], shifted.instance);
        ASSERT_EQ(from_origins.distance_m[i], shifted.distance_m);
        const RayHit part_alone = caster.IntersectInstance(part, origin, directions[i]);
        ASSERT_EQ(alone.instance[i], part_alone.instance);
        ASSERT_EQ(alone.distance_m[i], part_alone.distance_m);
        hits += single.hit();
        part_hits += part_alone.hit();
      }
    }
  }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(part_hits, 0);
}

TEST_F(PaperRoomView, RenderIntoBuffersReusesThemUnlessSharedAndGivesTheSameFrame) {
  const Scene scene = LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json");
  const BandRadianceTable table;
  World world(scene, table);
  FrameRenderer renderer(world, IntrinsicsFromScene(scene), RenderOptionsFromScene(scene, 2));
  const FrameBuffers reference = renderer.Render(CorridorPose());
  FrameBuffers buffers;
  CameraPose other = CorridorPose();
  other.yaw_rad = 1.0;
  renderer.Render(other, &buffers);
  const uchar* radiance_data = buffers.radiance.data;
  const cv::Mat kept = buffers.depth_m;  // shared: must not be overwritten
  const cv::Mat kept_copy = kept.clone();
  renderer.Render(CorridorPose(), &buffers);
  EXPECT_EQ(buffers.radiance.data, radiance_data);
  EXPECT_NE(buffers.depth_m.data, kept.data);
  EXPECT_EQ(cv::norm(kept, kept_copy, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(buffers.radiance, reference.radiance, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(buffers.depth_m, reference.depth_m, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(buffers.instance, reference.instance, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(buffers.class_id, reference.class_id, cv::NORM_INF), 0.0);
  EXPECT_EQ(buffers.edge_pixels, reference.edge_pixels);
}

TEST_F(PaperRoomView, PeopleWallsAndCupsReadPlausibleTemperatures) {
  const Scene scene = LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json");
  const BandRadianceTable table;
  World world(scene, table);
  FrameRenderer renderer(world, IntrinsicsFromScene(scene), RenderOptionsFromScene(scene, 0));
  const FrameBuffers frame = renderer.Render(CorridorPose());
  SensorModel sensor(SensorOptionsFromScene(scene), frame.radiance.cols, frame.radiance.rows, 25, 1, &table);
  // Assert on what a user reads: the frame's EXR channels T and class, written and read back.
  cv::Mat class_f;
  frame.class_id.convertTo(class_f, CV_32F);
  const test::TestDir temp;
  const std::string exr_path = temp / "frame.exr";
  WriteFileAtomic(exr_path, EncodeExr({{"T", sensor.Apply(0, frame.radiance)}, {"class", class_f}}));
  cv::Mat t, class_id;
  for (const auto& [name, channel] : ReadExr(exr_path, frame.radiance.size())) {
    if (name == "T") t = channel;
    if (name == "class") channel.convertTo(class_id, CV_32S);
  }
  ASSERT_FALSE(t.empty());
  ASSERT_EQ(cv::norm(class_id, frame.class_id, cv::NORM_INF), 0.0);
  const int person = world.classes().at("person");
  // Interior pixels of each class (one pixel away from any other class), so edge mixing and
  // the optics blur do not count.
  auto interior = [&](int cls) {
    cv::Mat mask = class_id == cls;
    cv::erode(mask, mask, cv::Mat::ones(3, 3, CV_8U));
    return mask;
  };
  const cv::Mat people = interior(person);
  ASSERT_GT(cv::countNonZero(people), 500) << "the corridor view must show people";
  double lo, hi;
  cv::minMaxLoc(t, &lo, &hi, nullptr, nullptr, people);
  // The coolest clothing is a loose jacket's hem: t_cl 25.7 °C less its hem and air-gap cooling
  // (docs/models/people.md), read through ε = 0.90.
  EXPECT_GE(lo, 23.0);
  EXPECT_LE(hi, 37.0);
  EXPECT_GT(hi, 32.0) << "exposed skin reads above 32 °C";
  // Walls and floor from the south corridor, where they fill most of the view.
  CameraPose corridor = CorridorPose();
  corridor.y_m = 0.4;
  const FrameBuffers side = renderer.Render(corridor);
  const cv::Mat side_t = sensor.Apply(1, side.radiance);
  for (const char* background : {"wall", "floor"}) {
    cv::Mat m = side.class_id == world.classes().at(background);
    cv::erode(m, m, cv::Mat::ones(3, 3, CV_8U));
    ASSERT_GT(cv::countNonZero(m), 100) << background;
    cv::minMaxLoc(side_t, &lo, &hi, nullptr, nullptr, m);
    EXPECT_GE(lo, 19.0) << background;
    EXPECT_LE(hi, 25.0) << background;
  }
  const cv::Mat cups = class_id == world.classes().at("cup");
  ASSERT_GT(cv::countNonZero(cups), 0) << "a cup must be in view";
  cv::minMaxLoc(t, &lo, &hi, nullptr, nullptr, cups);
  EXPECT_GT(hi, 40.0) << "a hot cup reads above 40 °C";
}

}  // namespace
}  // namespace hoilcd
