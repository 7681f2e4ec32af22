// The room's surfaces (room_thermal.h) against the figures of docs/models/room_surfaces.md: cool
// edges of outside walls, glass from its U-value, the plume above a radiator, sun patches, the
// thermostat's cycle and the surfaces' lag; everything off gives the plain scene values.
#include "hoilcd/sim/world/room_thermal.h"

#include <cmath>

#include <gtest/gtest.h>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/world/world.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

Scene PaperRoom(const std::vector<std::string>& overrides = {}) {
  return LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json", overrides);
}

// The paper room's options with only the effect under test left on.
RoomOptions QuietRoom() {
  RoomOptions room;
  room.surfaces.thermal_bridges = false;
  room.surfaces.radiator_plume = false;
  room.surfaces.glass_from_u_value = false;
  room.surfaces.window_frames = false;
  room.surfaces.texture = false;
  room.sun.enabled = false;
  room.hvac.enabled = false;
  return room;
}

std::vector<InstanceMaterial> Materials(const RoomOptions& room) {
  return std::vector<InstanceMaterial>(3 + room.windows.size());
}

TEST(RoomThermal, GlassTemperatureFollowsItsUValue) {
  // T_si = T_i − U·R_si·(T_i − T_e): old double glazing (2.8) at 22 °C in, 5 °C out.
  EXPECT_NEAR(InsideSurfaceTemperatureC(2.8, 22, 5), 22 - 2.8 * 0.13 * 17, 1e-12);
  EXPECT_NEAR(InsideSurfaceTemperatureC(2.8, 22, 5), 15.81, 0.01);
  RoomOptions room = QuietRoom();
  room.surfaces.glass_from_u_value = true;
  room.windows[0].u_value_w_m2k = 5.8;  // single glazing
  RoomSurfaces surfaces(room, 1, {});
  std::vector<InstanceMaterial> m = Materials(room);
  surfaces.SetTime(0, &m);
  EXPECT_NEAR(m[3].temperature_c, 22 - 5.8 * 0.13 * 17, 1e-4);
  EXPECT_NEAR(m[3].temperature_c, 9.18, 0.01);
}

TEST(RoomThermal, AFrameSitsBetweenGlassAndWall) {
  RoomOptions room = QuietRoom();
  room.surfaces.glass_from_u_value = true;
  room.surfaces.window_frames = true;
  RoomSurfaces surfaces(room, 1, {});
  std::vector<InstanceMaterial> m = Materials(room);
  surfaces.SetTime(0, &m);
  const WindowSpec& w = room.windows[0];  // north wall, x 1.0..2.6, z 0.9..2.2
  const float y = static_cast<float>(room.size_m.y());
  const float glass = m[3].temperature_c;
  const float frame = glass + surfaces.OffsetK(3, Eigen::Vector3f(static_cast<float>(w.center_m), y, 0.93f));
  EXPECT_NEAR(surfaces.OffsetK(3, Eigen::Vector3f(static_cast<float>(w.center_m), y, 1.5f)), 0.0f, 1e-6);
  EXPECT_NEAR(frame, 22 - 1.8 * 0.13 * 17, 1e-3);  // 18.0 °C: PVC frame, U 1.8
  EXPECT_GT(frame, glass);
  EXPECT_LT(frame,
            room.walls.temperature_bottom_c + 0.5 * (room.walls.temperature_top_c - room.walls.temperature_bottom_c));
}

TEST(RoomThermal, ACornerOfAnOutsideWallIsCoolerThanMidWallByTheDocumentedAmount) {
  RoomOptions room = QuietRoom();
  room.surfaces.thermal_bridges = true;
  RoomSurfaces surfaces(room, 1, {});
  std::vector<InstanceMaterial> m = Materials(room);
  surfaces.SetTime(0, &m);
  // Edge cooling (f_wall − f_Rsi)·(T_i − T_e) = (1 − 0.6·0.13 − 0.80)·(22 − 5) = 2.07 K.
  const double edge_k = (1 - 0.6 * 0.13 - 0.8) * 17;
  const float y = static_cast<float>(room.size_m.y());
  const float mid = surfaces.OffsetK(2, Eigen::Vector3f(5.5f, y, 1.3f));
  const float corner = surfaces.OffsetK(2, Eigen::Vector3f(0.01f, y, 1.3f));  // north wall by the west wall
  EXPECT_NEAR(mid, 0.0f, 0.01f);
  EXPECT_NEAR(corner - mid, -edge_k * std::exp(-0.01 / 0.15), 0.01);
  // 30 cm from the edge: e^-2 of it.
  EXPECT_NEAR(surfaces.OffsetK(2, Eigen::Vector3f(0.3f, y, 1.3f)) - mid, -edge_k * std::exp(-2.0), 0.01);
  // The west wall meets the outside north wall there too; the south wall's middle is inside.
  EXPECT_LT(surfaces.OffsetK(2, Eigen::Vector3f(0.0f, y - 0.01f, 1.3f)), -1.5f);
  EXPECT_NEAR(surfaces.OffsetK(2, Eigen::Vector3f(3.5f, 0.0f, 1.3f)), 0.0f, 1e-6);
  // The top corner (two walls and the ceiling) is capped at 1.5 edges.
  EXPECT_NEAR(surfaces.OffsetK(2, Eigen::Vector3f(0.0f, y, static_cast<float>(room.size_m.z()))), -1.5 * edge_k, 1e-3);
}

TEST(RoomThermal, TheWallAboveARadiatorIsWarmerFallingWithHeightAndSideways) {
  Scene scene = PaperRoom({"room.surfaces.texture=false", "room.surfaces.thermal_bridges=false"});
  const BandRadianceTable table;
  World world(scene, table);
  const RoomSurfaces& surfaces = world.room_surfaces();
  // The paper room's radiator: 1.0 m wide, 0.75 m high, its bottom 0.12 m up, centred at x 3.4 on
  // the north wall: its top at 0.87 m.
  const float y = 3.0f, top = 0.87f;
  const float above = surfaces.OffsetK(2, Eigen::Vector3f(3.4f, y, top + 0.1f));
  EXPECT_NEAR(above, 4.0 * std::exp(-0.1 / 0.6), 0.01);
  EXPECT_NEAR(surfaces.OffsetK(2, Eigen::Vector3f(3.4f, y, top + 0.7f)), 4.0 * std::exp(-0.7 / 0.6), 0.01);
  EXPECT_LT(surfaces.OffsetK(2, Eigen::Vector3f(4.3f, y, top + 0.1f)), 0.5 * above);  // 0.4 m beside its end
  EXPECT_NEAR(surfaces.OffsetK(2, Eigen::Vector3f(5.5f, y, top + 0.1f)), 0.0f, 1e-3);
  EXPECT_NEAR(surfaces.OffsetK(2, Eigen::Vector3f(3.4f, 0.0f, top + 0.1f)), 0.0f, 1e-6);  // the opposite wall
}

// The lit floor's centroid (x, y) and its largest warming; (NaN, NaN) when unlit.
Eigen::Vector3f SunPatch(const RoomSurfaces& surfaces, const RoomOptions& room) {
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  float weight = 0, peak = 0;
  for (float x = 0.025f; x < room.size_m.x(); x += 0.05f) {
    for (float y = 0.025f; y < room.size_m.y(); y += 0.05f) {
      const float k = surfaces.OffsetK(0, Eigen::Vector3f(x, y, 0));
      sum += k * Eigen::Vector3f(x, y, 0);
      weight += k;
      peak = std::max(peak, k);
    }
  }
  if (weight <= 0) return Eigen::Vector3f(NAN, NAN, 0);
  Eigen::Vector3f c = sum / weight;
  c.z() = peak;
  return c;
}

TEST(RoomThermal, TheSunPatchMovesWithTheTimeOfDayAndIsAbsentAtNight) {
  RoomOptions room = QuietRoom();
  room.sun.enabled = true;
  room.windows[0].wall = "south";  // facing the winter sun at 35.7° N
  room.windows[0].center_m = 3.5;
  std::vector<InstanceMaterial> m = Materials(room);
  room.sun.time_of_day_h = 10;
  RoomSurfaces morning(room, 1, {});
  morning.SetTime(0, &m);
  room.sun.time_of_day_h = 14;
  RoomSurfaces afternoon(room, 1, {});
  afternoon.SetTime(0, &m);
  room.sun.time_of_day_h = 22;
  RoomSurfaces night(room, 1, {});
  night.SetTime(0, &m);
  const Eigen::Vector3f a = SunPatch(morning, room), b = SunPatch(afternoon, room);
  ASSERT_FALSE(std::isnan(a.x()));
  ASSERT_FALSE(std::isnan(b.x()));
  // In the morning the sun is in the south-east, so its patch lies west of the window; in the
  // afternoon east of it. Symmetric about solar noon.
  EXPECT_LT(a.x(), 3.5f - 0.3f);
  EXPECT_GT(b.x(), 3.5f + 0.3f);
  EXPECT_NEAR(a.x() + b.x(), 7.0f, 0.05f);
  // A few kelvin: 12 K per kW/m² of the transmitted clear-sky sun.
  EXPECT_GT(a.z(), 2.0f);
  EXPECT_LT(a.z(), 10.0f);
  EXPECT_TRUE(std::isnan(SunPatch(night, room).x()));
  // The paper room's north window gets no direct sun in January.
  RoomOptions north = QuietRoom();
  north.sun.enabled = true;
  RoomSurfaces shaded(north, 1, {});
  shaded.SetTime(0, &m);
  EXPECT_TRUE(std::isnan(SunPatch(shaded, north).x()));
}

TEST(RoomThermal, SolarPositionAtNoonOnTheEquinox) {
  // Day 80 (21 March): declination about 0, so the noon elevation is 90° − latitude, due south.
  const SunPosition noon = SolarPosition(35.7, 80, 12.0);
  EXPECT_NEAR(noon.elevation_rad * 180 / M_PI, 90 - 35.7, 0.5);
  EXPECT_NEAR(noon.azimuth_rad * 180 / M_PI, 180, 0.5);
  EXPECT_LT(SolarPosition(35.7, 80, 0.0).elevation_rad, 0);
  EXPECT_EQ(ClearSkyDirectNormalWm2(-0.1), 0);
  EXPECT_NEAR(ClearSkyDirectNormalWm2(M_PI / 2), 1353 * std::pow(0.7, 1.0), 15);
}

TEST(RoomThermal, TheAirFollowsTheThermostatCycleAndSurfacesLagBehind) {
  RoomOptions room;
  room.hvac.enabled = true;
  room.hvac.deadband_k = 1.0;
  room.hvac.period_s = 900;
  room.hvac.surface_lag_s = 600;
  const RoomClimate climate(room, 7);
  double air_lo = 1e9, air_hi = -1e9, surface_lo = 1e9, surface_hi = -1e9, t_air_hi = 0, t_surface_hi = 0;
  for (double t = 0; t < 900; t += 0.5) {
    const double air = climate.AirTemperatureC(t), surface = climate.SurfaceOffsetK(t);
    EXPECT_NEAR(climate.AirTemperatureC(t + 900), air, 1e-9);
    EXPECT_NEAR(climate.SurfaceOffsetK(t + 3 * 900), surface, 1e-9);
    if (air > air_hi) air_hi = air, t_air_hi = t;
    if (surface > surface_hi) surface_hi = surface, t_surface_hi = t;
    air_lo = std::min(air_lo, air);
    surface_lo = std::min(surface_lo, surface);
  }
  EXPECT_NEAR(air_lo, 22 - 0.5, 0.01);
  EXPECT_NEAR(air_hi, 22 + 0.5, 0.01);
  EXPECT_LT(surface_hi - surface_lo, 0.5 * (air_hi - air_lo));  // damped
  EXPECT_GT(surface_hi - surface_lo, 0.05);
  // The surfaces peak after the air (mod the period).
  const double lag_s = std::fmod(t_surface_hi - t_air_hi + 900, 900);
  EXPECT_GT(lag_s, 30);
  EXPECT_LT(lag_s, 450);
  // The closed form solves y' = (air − y)/τ: integrate it from the closed form's value at 0.
  double y = climate.SurfaceOffsetK(0);
  const double dt = 0.01;
  for (double t = 0; t < 1000 - 1e-9; t += dt) {
    const double mid = climate.AirOffsetK(t + 0.5 * dt);
    y += dt * (mid - y) / 600;
  }
  EXPECT_NEAR(y, climate.SurfaceOffsetK(1000), 1e-3);
}

TEST(RoomThermal, WithEveryEffectOffTheRoomKeepsItsSceneValuesAndHasNoFields) {
  const RoomOptions room = QuietRoom();
  RoomSurfaces surfaces(room, 1,
                        {Eigen::AlignedBox3f(Eigen::Vector3f(2.9f, 2.9f, 0.12f), Eigen::Vector3f(3.9f, 3.0f, 0.87f))});
  std::vector<InstanceMaterial> m = Materials(room);
  surfaces.SetTime(12.3, &m);
  for (int k = 0; k < static_cast<int>(m.size()); ++k) EXPECT_EQ(m[static_cast<size_t>(k)].field, nullptr) << k;
  EXPECT_EQ(m[0].temperature_c, static_cast<float>(room.floor.temperature_c));
  EXPECT_EQ(m[1].temperature_c, static_cast<float>(room.ceiling.temperature_c));
  EXPECT_EQ(m[2].temperature_c, static_cast<float>(room.walls.temperature_bottom_c));
  EXPECT_EQ(m[2].temperature_top_c, static_cast<float>(room.walls.temperature_top_c));
  EXPECT_EQ(m[3].temperature_c, static_cast<float>(room.windows[0].surface.temperature_c));
  EXPECT_EQ(surfaces.EnvironmentTemperatureC(12.3), room.environment_temperature_c);
  // The ideal room turns every effect off.
  const Scene ideal = LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/ideal_room.json");
  const BandRadianceTable table;
  const World world(ideal, table);
  for (const InstanceMaterial& material : world.instance(0).materials) EXPECT_EQ(material.field, nullptr);
  EXPECT_EQ(world.environment_radiance(), table.RadianceFromCelsius(22.0f));
}

TEST(RoomThermal, ASunlitRoomRendersTheSameBytesAtOneAndTwoThreads) {
  test::TestDir dir;
  const Scene scene =
      PaperRoom({"room.windows.0.wall=south", "room.windows.0.center_m=3.5", "room.sun.time_of_day_h=14"});
  auto render = [&](const std::string& name, int threads) {
    SequenceOptions options;
    options.output_dir = dir / name;
    options.frames = 3;
    options.threads = threads;
    RenderSequence(scene, options);
    return Dataset::Open(dir / name).manifest().files;
  };
  EXPECT_EQ(render("one", 1), render("two", 2));
}

}  // namespace
}  // namespace hoilcd
