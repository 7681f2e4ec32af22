// Warm bodies mirrored in glossy surfaces: what a whiteboard (or a glossy floor) shows of a person
// in front of it is its own emission plus (1 − ε) of the person's radiance, and a reader sees it.
#include <cmath>

#include <gtest/gtest.h>

#include "hoilcd/sim/render/renderer.h"
#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/scene/scene_options.h"

namespace hoilcd {
namespace {

using nlohmann::json;

// A 7 × 4 m room, a whiteboard on the west wall (y 1.1–2.9 m, z 0.9–2.1 m, facing +x) and one
// person standing at (1.5, 2.6) in front of it; the camera looks at the board from (3.5, 1.0).
Scene WhiteboardScene(double floor_roughness_um = 0.0) {
  json doc = {{"tables", json::array()},
              {"objects", {{{"asset", "whiteboard"}, {"position_m", {0.0, 2.0, 0.9}}, {"yaw_deg", 0.0}}}},
              {"crowd", {{"standing", {{{"position_m", {1.5, 2.6}}, {"yaw_deg", 180.0}}}}}},
              {"room",
               {{"size_m", {7.0, 4.0, 2.6}},
                {"windows", json::array()},
                {"floor", {{"specular", true}, {"emissivity", 0.90}, {"roughness_um", floor_roughness_um}}},
                // The mirror law alone: the board at its declared 22 °C, not the solution's.
                {"thermal", {{"enabled", false}}}}}};
  return SceneFromJson(doc, "whiteboard.json");
}

struct Mirror {
  RayHit board, person;
  Eigen::Vector3f board_point, person_point, reflected;
};

// The board point seen along `direction` from `origin` and the person point its reflection ray
// hits, or nothing (board.instance or person.instance −1).
Mirror Trace(const World& world, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction) {
  Mirror m;
  m.board = world.caster().Intersect(origin, direction);
  if (!m.board.hit() || world.instance(m.board.instance).asset == nullptr ||
      world.instance(m.board.instance).asset->class_name != "whiteboard") {
    m.board.instance = -1;
    return m;
  }
  m.board_point = origin + m.board.distance_m * direction;
  const Eigen::Vector3f n = m.board.normal_world;
  m.reflected = direction - 2.0f * direction.dot(n) * n;
  m.person = world.caster().Intersect(m.board_point + 1e-3f * n, m.reflected);
  if (m.person.hit() && world.instance(m.person.instance).role == InstanceRole::kPerson) {
    m.person_point = m.board_point + 1e-3f * n + m.person.distance_m * m.reflected;
  } else {
    m.person.instance = -1;
  }
  return m;
}

TEST(Reflection, AWhiteboardMirrorsAPersonAsItsEmissionPlusOneMinusEpsilonOfThePersonsRadiance) {
  const Scene scene = WhiteboardScene();
  const BandRadianceTable table;
  World world(scene, table);
  world.SetTime(0.0);
  FrameRenderer renderer(world, IntrinsicsFromScene(scene), RenderOptionsFromScene(scene, 1));
  const Eigen::Vector3f camera(3.5f, 1.0f, 1.5f);
  const float board_emissivity = 0.88f;  // assets/whiteboard.gltf, docs/models/room_objects.md
  const float board_c = 22.0f;
  int mirrored = 0, plain = 0;
  double plain_c = 0, max_contrast_k = 0;
  for (float y = 1.2f; y <= 2.8f; y += 0.02f) {
    for (float z = 1.0f; z <= 2.0f; z += 0.02f) {
      const Eigen::Vector3f d = (Eigen::Vector3f(0.0f, y, z) - camera).normalized();
      const Mirror m = Trace(world, camera, d);
      if (m.board.instance < 0) continue;
      RayHit hit;
      const float seen = renderer.Radiance(camera, d, &hit);
      const InstanceInfo& info = world.instance(hit.instance);
      if (static_cast<int>(info.mesh->triangle_material[hit.triangle]) != info.asset->MaterialIndex("whiteboard"))
        continue;
      if (m.person.instance < 0) {
        plain_c += table.CelsiusFromRadiance(seen);
        ++plain;
        continue;
      }
      // The person's radiance along the reflected ray, as a camera at the board would see it
      // (a ray from just in front of the person point, so nothing but the person is in the way).
      RayHit direct_hit;
      const float person = renderer.Radiance(m.person_point - 0.05f * m.reflected, m.reflected, &direct_hit);
      ASSERT_EQ(direct_hit.instance, m.person.instance);
      const float expected = board_emissivity * table.RadianceFromCelsius(board_c) + (1.0f - board_emissivity) * person;
      EXPECT_NEAR(seen, expected, 1e-4 * expected) << "board point " << m.board_point.transpose();
      max_contrast_k = std::max<double>(max_contrast_k, table.CelsiusFromRadiance(seen) - board_c);
      ++mirrored;
    }
  }
  ASSERT_GT(mirrored, 50) << "the person must be mirrored in the board";
  ASSERT_GT(plain, 500);
  // A plain part of the board mirrors the 22 °C-ish room: it reads about the board's temperature.
  EXPECT_NEAR(plain_c / plain, board_c, 0.3);
  // The mirrored person stands out: 12 % of a 28–34 °C body over a 22 °C board is over 0.7 K,
  // about 15× the camera's NETD.
  EXPECT_GT(max_contrast_k, 0.7);
}

TEST(Reflection, ARoughFloorMixesItsMirrorImageWithTheAmbientByTheDaviesFactor) {
  const BandRadianceTable table;
  float seen[2];
  const Eigen::Vector3f camera(3.5f, 1.0f, 1.5f);
  // A floor point whose mirror ray meets the person's legs (the person stands at (1.5, 2.6)).
  const Eigen::Vector3f floor_point(2.3f, 2.0f, 0.0f);
  const Eigen::Vector3f d = (floor_point - camera).normalized();
  for (int k = 0; k < 2; ++k) {
    const Scene scene = WhiteboardScene(k == 0 ? 0.0 : 0.8);
    World world(scene, table);
    world.SetTime(0.0);
    FrameRenderer renderer(world, IntrinsicsFromScene(scene), RenderOptionsFromScene(scene, 1));
    RayHit hit;
    seen[k] = renderer.Radiance(camera, d, &hit);
    ASSERT_EQ(world.instance(hit.instance).role, InstanceRole::kRoom);
    if (k == 0) {
      const Eigen::Vector3f r(d.x(), d.y(), -d.z());
      const RayHit legs = world.caster().Intersect(floor_point + Eigen::Vector3f(0, 0, 1e-3f), r);
      ASSERT_TRUE(legs.hit() && world.instance(legs.instance).role == InstanceRole::kPerson)
          << "the floor point must mirror the person";
    }
  }
  // L = εB(T) + (1 − ε)(s·L_mirror + (1 − s)·L_env), s = exp(−(4π·σ·cos θ / 10 µm)²): the rough
  // floor's excess over a diffuse one is s times the smooth floor's.
  json doc = WhiteboardScene().resolved;
  doc["room"]["floor"]["specular"] = false;
  const Scene scene = SceneFromJson(doc, "matte.json");
  World world(scene, table);
  world.SetTime(0.0);
  FrameRenderer renderer(world, IntrinsicsFromScene(scene), RenderOptionsFromScene(scene, 1));
  RayHit hit;
  const float matte = renderer.Radiance(camera, d, &hit);
  EXPECT_GT(seen[0] - matte, 0.0f);
  const double cos_incidence = std::abs(d.z());
  const double s = std::exp(-std::pow(4 * M_PI * 0.8 * cos_incidence / 10.0, 2));
  EXPECT_GT(s, 0.3);
  EXPECT_LT(s, 0.9);
  EXPECT_NEAR((seen[1] - matte) / (seen[0] - matte), s, 2e-3);
}

}  // namespace
}  // namespace hoilcd
