// Contact heat (docs/models/contact_heat.md): the closed-form response, prints only where and
// after people touch, seat and posture dependence, cups and laptops, resume and thread
// independence, and the must-show: a left seat's print fitted from rendered T_true frames.
#include "hoilcd/sim/world/contact_heat.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hoilcd/sim/render/renderer.h"
#include "hoilcd/sim/scene/scene_options.h"
#include "hoilcd/sim/sensor/sensor.h"
#include "hoilcd/sim/world/world.h"

namespace hoilcd {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The prints are measured against the assets' declared 22 °C, so the room's thermal solution
// (which gives chairs and tables temperatures of their own) is off: each test sees the contact
// model alone.
Scene LoadTestScene(const std::string& name, std::vector<std::string> overrides = {}) {
  overrides.insert(overrides.begin(), "room.thermal.enabled=false");
  return LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/" + name, overrides);
}

int InstanceNamed(const World& world, const std::string& name) {
  for (int i = 0; i < world.num_instances(); ++i)
    if (world.instance(i).name == name) return i;
  return -1;
}

// The material temperature plus the field's offset at a world point of an instance.
float SurfaceC(const World& world, int instance, const Eigen::Vector3f& world_point) {
  const InstanceInfo& info = world.instance(instance);
  for (const InstanceMaterial& m : info.materials) {
    if (m.specular) continue;
    const Eigen::Vector3f object_point = (info.object_from_world * world_point.homogeneous()).head<3>();
    return m.temperature_c + (m.field ? m.field->OffsetK(object_point, world_point) : 0.0f);
  }
  return NAN;
}

Eigen::Vector3f SeatPoint(const World& world, int table, int seat, const Eigen::Vector3f& in_seat) {
  for (const Crowd::SeatPlace& s : world.seat_places())
    if (s.table == table && s.seat == seat) return (s.world_from_seat * in_seat.homogeneous()).head<3>();
  ADD_FAILURE() << "no seat " << table << "." << seat;
  return Eigen::Vector3f::Zero();
}

TEST(ContactHeat, ClosedFormFollowsTheFirstOrderEquation) {
  // dE/dt = (steady − E)/warm in contact, −E/cool out of it, integrated in small steps.
  const ContactResponse r{3.0, 20.0, 45.0};
  const std::vector<ContactInterval> contacts = {{5, 40}, {40, 55}, {90, 100}, {130, kInf}};
  double e = 0;
  const double dt = 1e-3;
  for (double t = 0; t < 200; t += dt) {
    bool in = false;
    for (const ContactInterval& c : contacts) in |= t >= c.start_s && t < c.end_s;
    e += dt * (in ? (r.steady_k - e) / r.warm_s : -e / r.cool_s);
    if (std::fmod(t + dt / 2, 10.0) < dt) {
      EXPECT_NEAR(ContactExcessK(contacts, r, t + dt), e, 2e-3) << t;
    }
  }
  // From −∞: steady at once; before any contact: nothing.
  EXPECT_DOUBLE_EQ(ContactExcessK({{-kInf, 10}}, r, 0), 3.0);
  EXPECT_NEAR(ContactExcessK({{-kInf, 10}}, r, 10 + 45), 3.0 * std::exp(-1.0), 1e-12);
  EXPECT_EQ(ContactExcessK(contacts, r, 4.9), 0.0);
}

TEST(ContactHeat, PrintIsAnEllipseOnTheTouchedSurfaceOnly) {
  PrintField field(7);
  Print p;
  p.shape.center_m = Eigen::Vector3f(0, 0, 0.45f);
  p.shape.half_m = Eigen::Vector3f(0.17f, 0.15f, 0.02f);
  p.response = {2.0, 10.0, 100.0};
  p.intervals = {{0, 50}};
  field.Add(p);
  field.SetTime(200);
  const Eigen::Vector3f w = Eigen::Vector3f::Zero();
  const float centre = field.OffsetK({0, 0, 0.45f}, w);
  EXPECT_NEAR(centre, 2.0 * std::exp(-1.5), 0.15 * 2.0 * std::exp(-1.5) + 1e-6);
  EXPECT_EQ(field.OffsetK({0.18f, 0, 0.45f}, w), 0.0f);  // beyond the ellipse
  EXPECT_EQ(field.OffsetK({0, 0, 0.42f}, w), 0.0f);      // the seat's underside band
  EXPECT_GT(field.OffsetK({0.1f, 0, 0.45f}, w), 0.0f);
  EXPECT_LT(field.OffsetK({0.15f, 0, 0.45f}, w), centre);  // a soft rim
  field.SetTime(-1);
  EXPECT_EQ(field.OffsetK({0, 0, 0.45f}, w), 0.0f);  // not before the contact
}

TEST(ContactHeat, PrintsFollowTheSeatAndThePosture) {
  // Seat 0 upright (back on the backrest, hands off the table), seat 1 with forearms on the table.
  const Scene scene = LoadTestScene(
      "paper_room.json",
      {R"(crowd.seating=[{"table": 0, "seat": 0, "posture": "seated_upright"}, {"table": 0, "seat": 1, "posture": "seated_arms_on_table"}])",
       "crowd.posture_change_interval_s=0", "crowd.activities.drinking.weight=0", "crowd.activities.talking.weight=0",
       "crowd.activity_blend_s=0.5"});
  const BandRadianceTable table;
  World world(scene, table);
  world.PlanCrowd(SimulateSceneRobot(scene, world.obstacles()).samples);
  world.SetTime(30.0);
  const int chair0 = InstanceNamed(world, "chair 0.0"), chair1 = InstanceNamed(world, "chair 0.1"),
            chair2 = InstanceNamed(world, "chair 0.2"), table0 = InstanceNamed(world, "table 0");
  const float room = 22.0f;
  // Both seats are warm where sat on, an empty chair is not; the seat's front edge is not.
  EXPECT_GT(SurfaceC(world, chair0, SeatPoint(world, 0, 0, {0.03f, 0, 0.45f})), room + 1.5f);
  EXPECT_GT(SurfaceC(world, chair1, SeatPoint(world, 0, 1, {0.03f, 0, 0.45f})), room + 1.5f);
  EXPECT_FLOAT_EQ(SurfaceC(world, chair0, SeatPoint(world, 0, 0, {0.03f, 0.3f, 0.45f})), room);
  if (chair2 >= 0) {
    EXPECT_FLOAT_EQ(SurfaceC(world, chair2, SeatPoint(world, 0, 2, {0.03f, 0, 0.45f})), room);
  }
  // The backrest of the upright sitter only.
  float back0 = 0, back1 = 0;
  for (float x = -0.3f; x < -0.15f; x += 0.005f) {
    back0 = std::max(back0, SurfaceC(world, chair0, SeatPoint(world, 0, 0, {x, 0, 0.66f})) - room);
    back1 = std::max(back1, SurfaceC(world, chair1, SeatPoint(world, 0, 1, {x, 0, 0.66f})) - room);
  }
  EXPECT_GT(back0, 0.8f * scene.crowd.contact_heat.back_excess_k);
  EXPECT_EQ(back1, 0.0f);
  // The table is warm under the arms-on-table sitter's forearms (the crowd's table contacts),
  // and nowhere near the upright one's.
  int table_contacts = 0;
  for (const Person& p : world.people()) {
    for (const auto& [name, at] : p.contacts_m) {
      if (name != "table") continue;
      ++table_contacts;
      EXPECT_EQ(p.seat, 1);
      EXPECT_GT(SurfaceC(world, table0, at.cast<float>()), room + 1.0f) << p.seat;
    }
  }
  EXPECT_EQ(table_contacts, 2);
  EXPECT_FLOAT_EQ(SurfaceC(world, table0, SeatPoint(world, 0, 0, {0.45f, 0, 0.74f})), room);
}

TEST(ContactHeat, ASofaShowsThePrintOfThePlaceSatOnOnly) {
  nlohmann::json doc = {
      {"name", "sofa"},
      {"frames", 50},
      {"room", {{"size_m", {9.0, 6.0, 2.6}}}},
      {"objects", nlohmann::json::array()},
      {"tables", {{{"center_m", {7.0, 2.0}}, {"asset", "sofa"}, {"seats", "sofa"}, {"yaw_deg", 90}}}},
      {"crowd",
       {{"seating", {{{"table", 0}, {"seat", 2}, {"posture", "seated_upright"}}}}, {"posture_change_interval_s", 0}}},
      {"route", {{"waypoints_m", {{0.4, 0.4}, {0.4, 5.6}, {8.6, 5.6}, {8.6, 0.4}}}}}};
  const Scene scene = SceneFromJson(doc, "sofa.json");
  const BandRadianceTable table;
  World world(scene, table);
  world.PlanCrowd(SimulateSceneRobot(scene, world.obstacles()).samples);
  world.SetTime(10.0);
  const int sofa = InstanceNamed(world, "table 0");
  const float cushion_c = world.instance(sofa).materials.front().temperature_c;
  EXPECT_GT(SurfaceC(world, sofa, SeatPoint(world, 0, 2, {0.03f, 0, 0.45f})), cushion_c + 1.5f);
  EXPECT_FLOAT_EQ(SurfaceC(world, sofa, SeatPoint(world, 0, 0, {0.03f, 0, 0.45f})), cushion_c);
}

TEST(ContactHeat, NewcomersPrintsCupsAndLaptopsStartAtTheirArrival) {
  const Scene scene = LoadTestScene("turnover_room.json", {"crowd.cup_fraction=1", "crowd.laptop_fraction=1"});
  const BandRadianceTable table;
  World world(scene, table);
  const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
  world.PlanCrowd(run.samples);
  const ContactHeatOptions& o = scene.crowd.contact_heat;
  int checked = 0;
  for (const DatasetEvent& e : world.events()) {
    if (e.type != "arrive") continue;
    const double t = run.samples.at(e.frame).time_s;
    const Person* newcomer = nullptr;
    for (const Person& p : world.people())
      if (p.person_id == e.person) newcomer = &p;
    ASSERT_NE(newcomer, nullptr);
    const int chair = InstanceNamed(world, "chair " + e.seat);
    const Eigen::Vector3f seat = SeatPoint(world, newcomer->table, newcomer->seat, {0.03f, 0, 0.45f});
    // Was the seat free since the start? Then nothing is warm before the arrival.
    bool sat_before = false;
    for (const Person& p : world.people())
      sat_before |= p.person_id != e.person && p.table == newcomer->table && p.seat == newcomer->seat;
    world.SetTime(t - 0.2);
    if (!sat_before) {
      EXPECT_FLOAT_EQ(SurfaceC(world, chair, seat), 22.0f) << e.seat;
    }
    world.SetTime(t + 0.5 * o.seat_warm_time_constant_s);
    if (!sat_before) {
      // Warming toward furniture.seat_warmth_c with its time constant (±15 % texture).
      const double expected = scene.furniture.seat_warmth_c * (1 - std::exp(-0.5));
      EXPECT_NEAR(SurfaceC(world, chair, seat) - 22.0, expected, 0.16 * expected) << e.seat;
    }
    if (newcomer->cup >= 0 && newcomer->laptop >= 0) {
      auto material_c = [&](int instance, const std::string& region) {
        const Asset& asset = *world.instance(instance).asset;
        return world.instance(instance).materials.at(asset.MaterialIndex(region)).temperature_c;
      };
      for (const double dt : {0.0, 100.0, 400.0}) {
        world.SetTime(t + dt);
        // A fresh cup cools by Newton's law from cup_fill_c; the laptop warms from the room.
        EXPECT_NEAR(material_c(newcomer->cup, "coffee"),
                    22.0 + (o.cup_fill_c - 22.0) * std::exp(-dt / o.cup_time_constant_s), 1e-3);
        EXPECT_NEAR(material_c(newcomer->laptop, "laptop_base"),
                    22.0 + 10.0 * (1 - std::exp(-dt / o.laptop_warm_time_constant_s)), 1e-3);
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 0) << "no newcomer with a cup and a laptop";
}

// Temperatures of every material and the fields at a few points on every touched instance.
std::vector<float> ThermalState(const World& world) {
  std::vector<float> state;
  for (int i = 0; i < world.num_instances(); ++i) {
    const InstanceInfo& info = world.instance(i);
    for (const InstanceMaterial& m : info.materials) {
      state.push_back(m.temperature_c);
      if (m.field == nullptr) continue;
      for (float x = -0.4f; x <= 0.4f; x += 0.05f)
        for (float y = -0.4f; y <= 0.4f; y += 0.05f)
          for (const float z : {0.018f, 0.045f, 0.45f, 0.66f, 0.74f})
            state.push_back(m.field->OffsetK({x, y, z}, {0, 0, 0}));
    }
  }
  return state;
}

TEST(ContactHeat, StateAtATimeIsTheSameWhateverCameBeforeAndAtAnyThreadCount) {
  const Scene scene = LoadTestScene("turnover_room.json", {"crowd.cup_fraction=1", "crowd.laptop_fraction=1"});
  const BandRadianceTable table;
  World walked(scene, table), jumped(scene, table);
  const RobotRun run = SimulateSceneRobot(scene, walked.obstacles());
  walked.PlanCrowd(run.samples);
  jumped.PlanCrowd(run.samples);
  const double t = run.samples.at(1100).time_s;
  for (int f = 900; f <= 1100; f += 4) walked.SetTime(run.samples.at(f).time_s);
  walked.SetTime(t);
  jumped.SetTime(t);
  EXPECT_EQ(ThermalState(walked), ThermalState(jumped));
  // Rendered at one and two threads: the same radiance.
  CameraPose pose;
  pose.x_m = 0.4, pose.y_m = 1.5, pose.z_m = 1.4, pose.pitch_rad = 25.0 * M_PI / 180.0;
  const cv::Mat one =
      FrameRenderer(walked, IntrinsicsFromScene(scene), RenderOptionsFromScene(scene, 1)).Render(pose).radiance;
  const cv::Mat two =
      FrameRenderer(jumped, IntrinsicsFromScene(scene), RenderOptionsFromScene(scene, 2)).Render(pose).radiance;
  EXPECT_EQ(cv::norm(one, two, cv::NORM_INF), 0.0);
}

TEST(ContactHeat, ALeftSeatsPrintDecaysWithTheDocumentedTimeConstantInTrueTemperature) {
  // turnover_room: a seat left at a lap boundary and not taken again, seen from above through
  // the renderer and the ideal camera (the EXR's T_true); its excess over the same pixels long
  // after (the room's own reading of that seat) is fitted as A·exp(−t/τ).
  const Scene scene = LoadTestScene("turnover_room.json");
  const BandRadianceTable table;
  World world(scene, table);
  const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
  world.PlanCrowd(run.samples);
  const DatasetEvent* left = nullptr;
  for (const DatasetEvent& e : world.events()) {
    if (e.type != "leave") continue;
    bool retaken = false;
    for (const DatasetEvent& later : world.events())
      retaken |= (later.type == "arrive" || later.type == "swap") && later.seat == e.seat;
    if (!retaken) left = &e;
    if (left) break;
  }
  ASSERT_NE(left, nullptr) << "no seat left free in turnover_room";
  const int table_index = std::stoi(left->seat), seat = std::stoi(left->seat.substr(left->seat.find('.') + 1));
  const double t_leave = run.samples.at(left->frame).time_s;
  // The camera 1.05 m above the seat, looking down at it (tilted 7° back from straight down).
  Eigen::Matrix4f world_from_seat = Eigen::Matrix4f::Identity();
  for (const Crowd::SeatPlace& s : world.seat_places())
    if (s.table == table_index && s.seat == seat) world_from_seat = s.world_from_seat;
  const Eigen::Vector3f eye = (world_from_seat * Eigen::Vector4f(0.15f, 0, 1.50f, 1)).head<3>();
  const Eigen::Vector3f forward = world_from_seat.block<3, 1>(0, 0);
  CameraPose pose;
  pose.x_m = eye.x(), pose.y_m = eye.y(), pose.z_m = eye.z();
  pose.yaw_rad = std::atan2(-forward.y(), -forward.x());
  pose.pitch_rad = std::atan2(1.05, 0.12);
  const CameraIntrinsics intrinsics = IntrinsicsFromScene(scene);
  const FrameRenderer renderer(world, intrinsics, RenderOptionsFromScene(scene, 2));
  SensorModel sensor(SensorOptionsFromScene(scene), intrinsics.width, intrinsics.height, scene.frame_rate_hz,
                     scene.seed, &table, 2);
  const int chair_class = world.classes().at("chair");
  // The median T_true of the chair pixels in the central 9×9 pixels at time t.
  auto seat_c = [&](double t) {
    world.SetTime(t);
    const FrameBuffers frame = renderer.Render(pose);
    const cv::Mat t_true = sensor.IdealTemperature(frame.radiance);
    std::vector<float> values;
    for (int v = intrinsics.height / 2 - 4; v <= intrinsics.height / 2 + 4; ++v)
      for (int u = intrinsics.width / 2 - 4; u <= intrinsics.width / 2 + 4; ++u)
        if (frame.class_id.at<int>(v, u) == chair_class) values.push_back(t_true.at<float>(v, u));
    EXPECT_GE(values.size(), 60u) << "the seat is not in view: class "
                                  << frame.class_id.at<int>(intrinsics.height / 2, intrinsics.width / 2) << " at depth "
                                  << frame.depth_m.at<float>(intrinsics.height / 2, intrinsics.width / 2);
    if (values.empty()) return std::nan("");
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return static_cast<double>(values[values.size() / 2]);
  };
  const double tau = scene.crowd.heat_print_time_constant_s;
  const double ambient = seat_c(t_leave + 40 * tau);
  std::vector<double> ts, logs;
  for (const double since : {0.5, 5.0, 20.0, 60.0, 120.0, 180.0}) {
    const double excess = seat_c(t_leave + since) - ambient;
    if (since <= 5.0) {
      EXPECT_GE(excess, 1.0) << "the left seat is not 1 K warm " << since << " s after";
    }
    ASSERT_GT(excess, 0.05) << since;
    ts.push_back(since);
    logs.push_back(std::log(excess));
  }
  double mt = 0, my = 0, stt = 0, sty = 0;
  for (size_t i = 0; i < ts.size(); ++i) mt += ts[i] / ts.size(), my += logs[i] / ts.size();
  for (size_t i = 0; i < ts.size(); ++i) stt += (ts[i] - mt) * (ts[i] - mt), sty += (ts[i] - mt) * (logs[i] - my);
  const double fitted_tau = -stt / sty;
  // Tolerance 3 %: radiance is not linear in temperature, the rest is exact.
  EXPECT_NEAR(fitted_tau, tau, 0.03 * tau) << "fitted " << fitted_tau << " s, documented " << tau << " s";
  std::printf("left seat %s: excess at leave %.3f K, fitted tau %.2f s (documented %.1f s)\n", left->seat.c_str(),
              std::exp(my - (sty / stt) * mt), fitted_tau, tau);
}

}  // namespace
}  // namespace hoilcd
