// The thermal solution of a world's static surfaces (room_network.h): it does not depend on the
// order in which times are asked, a closed room at one temperature stays at it, and an outside
// wall and its cold window cool what they should; the renderer reflects what surfaces face.
#include "hoilcd/sim/world/room_network.h"

#include <cmath>

#include <gtest/gtest.h>

#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/sensor/radiometry.h"
#include "hoilcd/sim/world/room_thermal.h"
#include "hoilcd/sim/world/world.h"
#include "planned_world.h"

namespace hoilcd {
namespace {

Scene PaperRoom(std::vector<std::string> overrides) {
  overrides.emplace_back("room.thermal.enabled=true");
  overrides.emplace_back("room.thermal.spin_up_s=7200");
  return LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json", overrides);
}

const BandRadianceTable& Table() {
  static const BandRadianceTable table(8.0, 14.0);
  return table;
}

TEST(RoomNetwork, TheStateAtATimeDoesNotDependOnTheTimesAskedBefore) {
  const Scene scene = PaperRoom({});
  World direct(scene, Table()), stepped(scene, Table());
  direct.SetTime(150.0);
  for (double t : {0.0, 30.0, 61.0, 120.5, 150.0}) stepped.SetTime(t);
  const RoomNetwork& a = *direct.room_network();
  const RoomNetwork& b = *stepped.room_network();
  for (const Eigen::Vector3f& p :
       {Eigen::Vector3f(3.5f, 0.0f, 1.2f), Eigen::Vector3f(1.0f, 3.0f, 0.3f), Eigen::Vector3f(7.0f, 1.3f, 2.0f)}) {
    ASSERT_FALSE(std::isnan(a.RoomTemperatureC(2, p))) << "a point on a wall";
    EXPECT_EQ(a.RoomTemperatureC(2, p), b.RoomTemperatureC(2, p));
  }
  for (int i = 0; i < direct.num_instances(); ++i) {
    for (int k = 0; k < static_cast<int>(direct.instance(i).materials.size()); ++k) {
      const float ta = a.InstanceTemperatureC(i, k), tb = b.InstanceTemperatureC(i, k);
      if (std::isnan(ta)) {
        EXPECT_TRUE(std::isnan(tb));
      } else {
        EXPECT_EQ(ta, tb) << direct.instance(i).name;
      }
    }
  }
}

TEST(RoomNetwork, AClosedRoomWithNoOutsideWallAndStillAirStaysAtTheAirsTemperature) {
  // The scene's hot cups and radiator (held at their temperatures) are left out.
  const Scene scene =
      PaperRoom({"objects=[]", "room.windows=[]", "room.surfaces.exterior_walls=none", "room.hvac.enabled=false",
                 "room.thermal.air_gradient_k_per_m=0", "room.environment_temperature_c=20.5"});
  World world(scene, Table());
  world.SetTime(40.0);
  const RoomNetwork& network = *world.room_network();
  std::vector<double> t;
  network.network().TemperaturesAt(40.0, &t);
  ASSERT_GT(t.size(), 1000u);
  for (double value : t) EXPECT_NEAR(value, 20.5, 1e-4);
}

TEST(RoomNetwork, TheOutsideWallAndTheFloorUnderItsWindowAreColderThanTheirCounterparts) {
  // The envelope alone, with the radiator: paper_room's heating pipes run along the wall under the
  // window and (rightly) warm the floor there.
  const Scene scene =
      PaperRoom({"room.hvac.enabled=false",
                 R"(objects=[{"asset": "radiator", "position_m": [3.4, 2.93, 0.12], "yaw_deg": -90}])"});
  World world(scene, Table());
  world.SetTime(0.0);
  const RoomNetwork& network = *world.room_network();
  // The north wall (its window makes it an outside wall) against the south wall, away from both
  // the window and the corners: T_i − U·R_si·(T_i − T_e) = 0.6 · 0.13 · 17 K ≈ 1.3 K colder.
  const float north = network.RoomTemperatureC(2, Eigen::Vector3f(4.5f, 3.0f, 1.4f));
  const float south = network.RoomTemperatureC(2, Eigen::Vector3f(4.5f, 0.0f, 1.4f));
  EXPECT_GT(south - north, 0.8f);
  EXPECT_LT(south - north, 2.0f);
  // The floor under the window sees the cold glass; the floor across the room far less.
  const float under = network.RoomTemperatureC(0, Eigen::Vector3f(1.8f, 2.8f, 0.0f));
  const float across = network.RoomTemperatureC(0, Eigen::Vector3f(5.5f, 0.3f, 0.0f));
  EXPECT_LT(under, across - 0.1f);
  // The glass is near its U-value's closed form (it also sees a room slightly off 22 °C).
  const float glass = network.RoomMeanTemperatureC(3);
  EXPECT_NEAR(glass, InsideSurfaceTemperatureC(2.8, 22.0, 5.0), 1.0);
  // The ceiling is warmer than the floor: the air is stratified.
  EXPECT_GT(network.RoomMeanTemperatureC(1), network.RoomMeanTemperatureC(0) + 0.5f);
  // The glass reflects what it faces: less than a black body at the room's air would send.
  EXPECT_LT(network.IncidentRadiance(world.room_instance(), 3), Table().RadianceFromCelsius(22.5f));
}

TEST(RoomNetwork, NoWallPatchHidesBehindTheWindowAndTheWallBesideItIsTheWalls) {
  // paper_room's window: the north wall, x 1.0 to 2.6 m, z 0.9 to 2.2 m, 2 mm in front of the wall.
  const Scene scene = PaperRoom({"room.hvac.enabled=false"});
  World world(scene, Table());
  world.SetTime(0.0);
  const RoomNetwork& network = *world.room_network();
  EXPECT_TRUE(std::isnan(network.RoomTemperatureC(2, Eigen::Vector3f(1.8f, 3.0f, 1.5f))))
      << "the wall behind the glass";
  EXPECT_FALSE(std::isnan(network.RoomTemperatureC(3, Eigen::Vector3f(1.8f, 2.998f, 1.5f)))) << "the glass";
  // Just above and beside the glass the wall reads the wall's own patches, within a kelvin of the
  // wall away from the window, not a blend with patches that only see the back of the glass.
  const float away = network.RoomTemperatureC(2, Eigen::Vector3f(5.0f, 3.0f, 1.5f));
  for (const Eigen::Vector3f& p :
       {Eigen::Vector3f(1.8f, 3.0f, 2.25f), Eigen::Vector3f(0.95f, 3.0f, 1.5f), Eigen::Vector3f(2.65f, 3.0f, 1.5f)}) {
    const float beside = network.RoomTemperatureC(2, p);
    ASSERT_FALSE(std::isnan(beside)) << p.transpose();
    EXPECT_NEAR(beside, away, 1.0f) << p.transpose();
  }
}

TEST(RoomNetwork, EveryFixtureMaterialDeclaredAtRoomTemperatureIsSolvedAndTheRestHeld) {
  const Scene scene = PaperRoom({});
  World world(scene, Table());
  world.SetTime(10.0);
  const RoomNetwork& network = *world.room_network();
  int solved = 0;
  for (int i = 0; i < world.num_instances(); ++i) {
    const InstanceInfo& info = world.instance(i);
    for (int k = 0; k < static_cast<int>(info.materials.size()); ++k) {
      const float t = network.InstanceTemperatureC(i, k);
      const bool powered = info.asset != nullptr && info.asset->materials[static_cast<size_t>(k)].power_w > 0;
      if (info.fixture && !std::isnan(t)) {
        ++solved;
        EXPECT_GT(t, 19.0f) << info.name;
        if (!powered) {
          EXPECT_LT(t, 25.0f) << info.name << ": a part without heat of its own";
        }
        EXPECT_EQ(info.materials[static_cast<size_t>(k)].temperature_c, t) << "the world shows the solution";
      }
      if (!info.fixture) {
        EXPECT_TRUE(std::isnan(t)) << info.name << " is no node";
      }
    }
  }
  EXPECT_GT(solved, 30) << "six tables and their chairs";
}

// A powered part (docs/models/room_objects.md) settles above the air by about P / (h·A): a 24"
// monitor's back (13 W over about 0.27 m²) some 5 K, its screen (4 W) a few K; a passive poster
// on the wall stays at the room's temperature.
TEST(RoomNetwork, APoweredMonitorWarmsAboveTheAirAndAPassivePosterStaysNearIt) {
  const Scene scene = PaperRoom({"room.hvac.enabled=false", "room.windows=[]",
                                 R"(objects=[{"asset": "monitor", "position_m": [3.5, 0.6, 0.0], "yaw_deg": 0},)"
                                 R"({"asset": "poster", "position_m": [5.0, 0.0, 1.1], "yaw_deg": 90}])"});
  World world(scene, Table());
  world.SetTime(0.0);
  const RoomNetwork& network = *world.room_network();
  auto temperature = [&](const std::string& instance, const std::string& region) {
    for (int i = 0; i < world.num_instances(); ++i) {
      const InstanceInfo& info = world.instance(i);
      if (info.name == instance) return network.InstanceTemperatureC(i, info.asset->MaterialIndex(region));
    }
    ADD_FAILURE() << "no " << instance;
    return std::nanf("");
  };
  const float back = temperature("monitor 0", "monitor_back"), screen = temperature("monitor 0", "monitor_screen");
  const float stand = temperature("monitor 0", "plastic"), poster = temperature("poster 1", "poster");
  // The air at the panel's height (about 0.3 m) is 22 − 0.8 K/m · 1.0 m ≈ 21.2 °C.
  EXPECT_GT(back, 24.5f);
  EXPECT_LT(back, 31.0f);
  EXPECT_GT(screen, 22.5f);
  EXPECT_LT(screen, back);
  EXPECT_LT(stand, 23.0f) << "the stand has no heat of its own";
  EXPECT_NEAR(poster, 22.0f, 1.0f);
}

TEST(RoomNetwork, EachPatchReflectsWhatItFacesNotItsMaterialsMean) {
  // The window alone: paper_room's radiator and pipes under it would warm the floor there.
  const Scene scene = PaperRoom({"room.hvac.enabled=false", "objects=[]"});
  World world(scene, Table());
  world.SetTime(0.0);
  const RoomNetwork& network = *world.room_network();
  // The floor in front of the cold window receives less than the floor across the room; the
  // field that the renderer reads gives each point its own patches' difference from the mean.
  const Eigen::Vector3f under(1.8f, 2.7f, 0.0f), across(5.5f, 0.3f, 0.0f);
  RoomNetwork::PatchState at_under_patch, at_across_patch;
  ASSERT_TRUE(network.RoomSurfaceAt(0, under, &at_under_patch));
  ASSERT_TRUE(network.RoomSurfaceAt(0, across, &at_across_patch));
  EXPECT_EQ(at_under_patch.temperature_c, network.RoomTemperatureC(0, under));
  const float l_under = at_under_patch.incident, l_across = at_across_patch.incident;
  // In band radiance: 8-14 µm radiance changes by about 0.6 % per kelvin near 22 °C.
  const float per_kelvin = Table().RadianceFromCelsius(22.5f) - Table().RadianceFromCelsius(21.5f);
  EXPECT_LT(l_under, l_across - 0.2f * per_kelvin) << "the window takes a share of the floor's view";
  const float mean = network.RoomMeanIncidentRadiance(0);
  const FieldSample at_under = world.room_surfaces().Sample(0, under);
  EXPECT_FLOAT_EQ(at_under.incident_offset, l_under - mean);
  EXPECT_LT(at_under.incident_offset, 0.0f);
  EXPECT_GT(world.room_surfaces().Sample(0, across).incident_offset, at_under.incident_offset);
  // Without the solution every point reflects the material's one environment.
  const Scene closed_form =
      LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json", {"room.thermal.enabled=false"});
  World plain(closed_form, Table());
  plain.SetTime(0.0);
  EXPECT_EQ(plain.room_surfaces().Sample(0, under).incident_offset, 0.0f);
}

TEST(RoomNetwork, APersonStandingByAWallWarmsThePatchTheyFaceAndAWalkerDoesNot) {
  // One person standing still 0.5 m from the west wall (chest to wall); no tables and no objects
  // (a picture on that wall would take the warmth), and the robot laps the east half.
  auto wall_by_them = [](const std::string& standing, const std::string& walkers) {
    const Scene scene = PaperRoom({"room.hvac.enabled=false", "tables=[]", "objects=[]",
                                   "route.waypoints_m=[[3.5, 0.5], [3.5, 2.5], [6.5, 2.5], [6.5, 0.5]]",
                                   "crowd.standing=" + standing, "crowd.walkers=" + walkers});
    test::PlannedWorld planned(scene);
    planned.world.SetTime(0.0);
    return planned.world.room_network()->RoomTemperatureC(2, Eigen::Vector3f(0.0f, 1.5f, 1.3f));
  };
  const float alone = wall_by_them("[]", "0");
  const float beside = wall_by_them(R"([{"position_m": [0.5, 1.5], "yaw_deg": 180}])", "0");
  ASSERT_FALSE(std::isnan(alone));
  // A body's clothing at 28 °C 0.5 m away fills a good share of the patch's view: a few tenths of
  // a kelvin to a couple of kelvin, against the wall's convection and its view of the rest.
  EXPECT_GT(beside - alone, 0.2f);
  EXPECT_LT(beside - alone, 3.0f);
  EXPECT_EQ(wall_by_them("[]", "2"), alone) << "walkers pass in seconds and are left out";
}

TEST(RoomNetwork, TheSunThroughTheWindowWarmsThePatchesItLightsAndEveryBeamLandsSomewhere) {
  // paper_room turned so that its window faces south, at noon on 20 January at 35.7° N; no
  // furniture, objects or blind in the beam.
  auto room = [](bool sun) {
    return PaperRoom({"room.hvac.enabled=false", "tables=[]", "objects=[]", "room.sun.north_wall_azimuth_deg=180",
                      "room.sun.time_of_day_h=12", std::string("room.sun.enabled=") + (sun ? "true" : "false")});
  };
  World lit(room(true), Table()), dark(room(false), Table());
  lit.SetTime(0.0);
  dark.SetTime(0.0);
  const RoomNetwork& network = *lit.room_network();
  const std::vector<float>& shares = network.sun_shares();
  ASSERT_EQ(static_cast<int>(shares.size()), network.num_nodes());
  // What the glass lets in, A·cos θ of the window's clear glass (1.6 × 1.3 m less a frame on
  // every side), lands on the room's surfaces: Σ A_i·share_i, up to the 16 keyed points per node.
  const SunInRoom sun = SunAt(room(true).room.sun, 0.0);
  ASSERT_GT(sun.irradiance_wm2, 300.0f);
  const double frame = room(true).room.surfaces.frame_width_m;
  const double beam_m2 = (1.6 - 2 * frame) * (1.3 - 2 * frame) * std::abs(sun.direction.y());
  double landed_m2 = 0;
  int brightest = 0;
  for (int i = 0; i < network.num_nodes(); ++i) {
    landed_m2 += network.network().node(i).area_m2 * shares[static_cast<size_t>(i)];
    if (shares[static_cast<size_t>(i)] > shares[static_cast<size_t>(brightest)]) brightest = i;
  }
  EXPECT_NEAR(landed_m2, beam_m2, 0.12 * beam_m2);
  // The brightest patch lies on the floor in front of the window, and the sun warms it by kelvins:
  // 0.6 · E · share absorbed against the floor's convection and radiation, with its heat capacity.
  std::vector<double> with_sun, without;
  network.network().TemperaturesAt(0.0, &with_sun);
  dark.room_network()->network().TemperaturesAt(0.0, &without);
  const double rise = with_sun[static_cast<size_t>(brightest)] - without[static_cast<size_t>(brightest)];
  EXPECT_GT(network.network().node(brightest).height_m, -0.01);
  EXPECT_LT(network.network().node(brightest).height_m, 0.01) << "a floor patch";
  EXPECT_GT(rise, 3.0);
  EXPECT_LT(rise, 30.0);
  // A patch the beam never reaches (the window's own wall) warms by far less: only through
  // what the lit patches send it.
  const Eigen::Vector3f beside_window(4.5f, 3.0f, 1.4f);
  EXPECT_LT(network.RoomTemperatureC(2, beside_window) - dark.room_network()->RoomTemperatureC(2, beside_window),
            0.5 * rise);
}

}  // namespace
}  // namespace hoilcd
