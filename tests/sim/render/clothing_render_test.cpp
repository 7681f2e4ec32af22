// Clothing as the camera sees it: rendered frames of the paper room with the material region of
// every pixel known (cast again through the World), so clothing and skin are told apart exactly.
#include <algorithm>
#include <cstdio>
#include <map>

#include <gtest/gtest.h>

#include "hoilcd/core/util/stats.h"
#include "hoilcd/sim/render/renderer.h"
#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/scene/scene_options.h"
#include "hoilcd/sim/sensor/sensor.h"

namespace hoilcd {
namespace {

struct ClothingPixels {
  int pairs = 0, equal_pairs = 0;                  // neighbouring garment pixels of one person
  std::map<int, std::vector<double>> by_person_c;  // garment pixel temperatures per person
  double EqualShare() const { return pairs ? static_cast<double>(equal_pairs) / pairs : 1.0; }
};

// Is the hit a garment (a clothing region, not a forearm the ensemble leaves bare)? Returns the
// person id, or -1.
int GarmentPerson(const World& world, const RayHit& hit) {
  if (!hit.hit()) return -1;
  const InstanceInfo& info = world.instance(hit.instance);
  if (info.role != InstanceRole::kPerson || info.asset == nullptr) return -1;
  const int m = static_cast<int>(info.mesh->triangle_material[hit.triangle]);
  if (info.asset->materials[m].region.rfind("clothing", 0) != 0) return -1;
  if (info.materials[m].emissivity > 0.95f) return -1;  // a bared forearm has skin's emissivity
  return info.person_id;
}

// The paper room (seed 1) from the robot's camera at the west end looking along the tables and
// from the south corridor, at several times.
ClothingPixels MeasureClothing(const Scene& scene) {
  const BandRadianceTable table;
  World world(scene, table);
  const CameraIntrinsics intrinsics = IntrinsicsFromScene(scene);
  FrameRenderer renderer(world, intrinsics, RenderOptionsFromScene(scene, 2));
  SensorModel sensor(SensorOptions(), intrinsics.width, intrinsics.height, 25, 1, &table);
  ClothingPixels out;
  for (double time_s : {0.0, 20.0, 40.0}) {
    world.SetTime(time_s);
    for (double y_m : {1.5, 0.4, 2.6}) {
      CameraPose pose;
      pose.x_m = 0.4, pose.y_m = y_m, pose.z_m = 0.95;
      pose.pitch_rad = 8.0 * M_PI / 180.0;
      const FrameBuffers frame = renderer.Render(pose);
      const cv::Mat t = sensor.IdealTemperature(frame.radiance);
      const Rigid3 world_from_cam = pose.WorldFromCam();
      const Eigen::Matrix3f r = world_from_cam.rotation.toRotationMatrix().cast<float>();
      const Eigen::Vector3f origin = world_from_cam.translation.cast<float>();
      cv::Mat person(t.size(), CV_32S, cv::Scalar(-1));
      for (int y = 1; y + 1 < t.rows; ++y) {
        for (int x = 1; x + 1 < t.cols; ++x) {
          // Interior pixels only (all eight neighbours show the same instance): no edge samples.
          const int label = frame.instance.at<int>(y, x);
          bool interior = true;
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) interior &= frame.instance.at<int>(y + dy, x + dx) == label;
          if (!interior) continue;
          const Eigen::Vector3f d = r * intrinsics.Unproject(x, y).cast<float>().normalized();
          person.at<int>(y, x) = GarmentPerson(world, world.caster().Intersect(origin, d));
        }
      }
      for (int y = 0; y < t.rows; ++y) {
        for (int x = 0; x < t.cols; ++x) {
          const int id = person.at<int>(y, x);
          if (id < 0) continue;
          out.by_person_c[id].push_back(t.at<float>(y, x));
          for (const auto& [nx, ny] : {std::pair<int, int>{x + 1, y}, std::pair<int, int>{x, y + 1}}) {
            if (nx >= t.cols || ny >= t.rows || person.at<int>(ny, nx) != id) continue;
            ++out.pairs;
            out.equal_pairs += std::abs(t.at<float>(ny, nx) - t.at<float>(y, x)) <= 0.02f;
          }
        }
      }
    }
  }
  return out;
}

Scene PaperRoom(bool garments) {
  const std::string on = garments ? "true" : "false";
  return LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json",
                   {"seed=1", "crowd.garments.enabled=" + on, "crowd.garments.skin_pattern=" + on});
}

// Issue 31's acceptance: with one temperature per clothing region every interior pair of
// neighbouring clothing pixels of one person reads the same to 0.02 K (94 % of all pairs in a
// dataset, edges included); garments bring it to at most half. Every person's mean clothing
// temperature as seen stays where their garments' own surface temperatures put it: the camera
// sees seated people mostly from the waist up, and upper garments' local insulation runs from a
// T-shirt's 0.26 clo (t_cl 30.9 °C at 1.0 met) to a jacket over a shirt's 1.5 clo (25.7 °C);
// fabric (ε = 0.90) reads up to 0.9 K below its surface temperature in a 22 °C room.
// (garments_test checks the whole-body means against ISO 7730's office range.)
TEST(ClothingRender, NeighbouringClothingPixelsDifferAndPeopleStayInTheOfficeRange) {
  const ClothingPixels before = MeasureClothing(PaperRoom(false));
  const ClothingPixels after = MeasureClothing(PaperRoom(true));
  std::printf("equal neighbouring clothing pairs: before %.1f %% of %d, after %.1f %% of %d\n",
              100 * before.EqualShare(), before.pairs, 100 * after.EqualShare(), after.pairs);
  ASSERT_GT(after.pairs, 2000);
  EXPECT_GT(before.EqualShare(), 0.8);
  EXPECT_LE(after.EqualShare(), 0.5);
  std::vector<double> means;
  for (const auto& [id, values] : after.by_person_c) {
    if (values.size() < 50) continue;
    double sum = 0;
    for (double v : values) sum += v;
    means.push_back(sum / static_cast<double>(values.size()));
    EXPECT_GE(means.back(), 25.0) << "person " << id;
    EXPECT_LE(means.back(), 31.0) << "person " << id;
  }
  ASSERT_GE(means.size(), 5u);
  std::printf("mean clothing temperature over %zu people: p5 %.2f, p50 %.2f, p95 %.2f °C\n", means.size(),
              Quantile(means, 0.05), Quantile(means, 0.5), Quantile(means, 0.95));
}

// A garment's pattern is fixed to the body: the same point of a person's torso keeps its offset
// while the torso moves.
TEST(ClothingRender, GarmentPatternMovesWithTheBody) {
  const Scene scene = PaperRoom(true);
  const BandRadianceTable table;
  World world(scene, table);
  const Person& person = world.people().at(0);
  const int torso = person.parts[1];
  const Eigen::Vector4f rest(0.12f, 0.0f, 1.2f, 1.0f);
  std::vector<Eigen::Vector3f> at;
  std::vector<float> offset;
  for (double time_s : {0.0, 13.0, 37.0}) {
    world.SetTime(time_s);
    const InstanceInfo& info = world.instance(torso);
    ASSERT_NE(info.materials.at(0).field, nullptr);
    const Eigen::Vector3f w = (world.caster().transform_of(torso) * rest).head<3>();
    const Eigen::Vector3f object = (info.object_from_world * w.homogeneous()).head<3>();
    at.push_back(w);
    offset.push_back(info.materials[0].field->OffsetK(object, w));
  }
  EXPECT_GT((at[1] - at[0]).norm() + (at[2] - at[0]).norm(), 0.005f) << "the torso must move";
  EXPECT_NEAR(offset[1], offset[0], 1e-4f);
  EXPECT_NEAR(offset[2], offset[0], 1e-4f);
  EXPECT_NE(offset[0], 0.0f);
}

}  // namespace
}  // namespace hoilcd
