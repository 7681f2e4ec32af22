#include "hoilcd/sim/world/crowd.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/random.h"
#include "hoilcd/sim/assets/skeleton.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/render/renderer.h"
#include "hoilcd/sim/render/visibility.h"
#include "hoilcd/sim/scene/scene_options.h"
#include "hoilcd/sim/world/world.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

Scene PaperRoom(const std::vector<std::string>& overrides) {
  return LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json", overrides);
}

int ChairInstance(const World& world, int table, int seat) {
  const std::string name = "chair " + std::to_string(table) + "." + std::to_string(seat);
  for (int i = 0; i < world.num_instances(); ++i)
    if (world.instance(i).name == name) return i;
  return -1;
}

// The seat's temperature where a sitter's print is (its centre, 3 cm forward; contact_heat.md).
float SeatTemperature(const World& world, int chair) {
  const InstanceInfo& info = world.instance(chair);
  const Eigen::Vector3f object_point(0.03f, 0, 0.45f);
  const Eigen::Vector3f world_point = (info.object_from_world.inverse() * object_point.homogeneous()).head<3>();
  for (const InstanceMaterial& m : info.materials)
    if (!m.specular) return m.temperature_c + (m.field ? m.field->OffsetK(object_point, world_point) : 0.0f);
  return 0;
}

TEST(Crowd, TalkersTurnToTheirNeighbourWhoeverSatDownFirst) {
  // Two people side by side at one table; the one on seat 0 is seated before seat 1's chair
  // exists. Talking (the only gaze at a neighbour, never at the robot) turns both heads to the other.
  const Scene scene = PaperRoom(
      {R"(crowd.seating=[{"table": 0, "seat": 0, "posture": "seated_upright"}, {"table": 0, "seat": 1, "posture": "seated_upright"}])",
       "crowd.activities.talking.weight=1000", "crowd.activities.head_turn.weight=0",
       "crowd.posture_change_interval_s=0"});
  const BandRadianceTable table;
  World world(scene, table);
  world.PlanCrowd(SimulateSceneRobot(scene, world.obstacles()).samples);
  std::map<int, int> toward, away;  // per seat: talking frames with the head turned to / from the other
  for (double t = 0; t < 60; t += 0.2) {
    world.SetTime(t);
    std::vector<const Person*> seated;
    for (const Person& p : world.people())
      if (p.seated && p.present) seated.push_back(&p);
    ASSERT_EQ(seated.size(), 2u);
    for (int i = 0; i < 2; ++i) {
      const Person& me = *seated[i];
      const Person& other = *seated[1 - i];
      const auto episode = std::find_if(me.activities.begin(), me.activities.end(),
                                        [&](const ActivityEpisode& e) { return e.start_s <= t && t < e.end_s; });
      ASSERT_NE(episode, me.activities.end());
      // Fully turned: past the ramp in, before the ramp out.
      if (episode->name != "talking" || t < episode->start_s + 1.0 || t > episode->end_s - 1.0) continue;
      const Eigen::Matrix4d seat_from_world = me.world_from_seat.cast<double>().inverse();
      auto in_seat = [&](const Eigen::Vector3d& w) {
        return (seat_from_world.topLeftCorner<3, 3>() * w + seat_from_world.topRightCorner<3, 1>()).eval();
      };
      const Eigen::Vector3d nose = in_seat(me.keypoints_m[kNose]);
      const Eigen::Vector3d neck = in_seat(0.5 * (me.keypoints_m[kLeftShoulder] + me.keypoints_m[kRightShoulder]));
      const Eigen::Vector3d them = in_seat(other.world_from_seat.cast<double>().topRightCorner<3, 1>());
      ((nose.y() - neck.y()) * them.y() > 0 ? toward : away)[me.seat] += 1;
    }
  }
  for (int seat : {0, 1}) {
    EXPECT_GT(toward[seat], 20) << "seat " << seat;
    EXPECT_EQ(away[seat], 0) << "seat " << seat;
  }
}

TEST(Crowd, TurnoverAtLapBoundariesLeavesCoolingHeatPrints) {
  const Scene scene = PaperRoom({"crowd.turnover_probability=0.4"});
  const BandRadianceTable table;
  World world(scene, table);
  const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
  world.PlanCrowd(run.samples);
  ASSERT_FALSE(world.events().empty());
  int leaves = 0, arrivals = 0;
  for (const DatasetEvent& e : world.events()) {
    // Every event happens on the frame the robot starts a new lap.
    const RobotSample& s = run.samples.at(e.frame);
    EXPECT_GE(s.lap, 1.0);
    EXPECT_LT(run.samples.at(e.frame - 1).lap, std::floor(s.lap)) << e.type;
    leaves += e.type == "leave";
    arrivals += e.type == "arrive";
  }
  EXPECT_GT(leaves, 0);
  EXPECT_GT(arrivals, 0);
  // A seat that someone left and nobody took is warmer than the room right after, and cools.
  bool checked = false;
  for (const DatasetEvent& e : world.events()) {
    if (e.type != "leave") continue;
    const double t = run.samples[e.frame].time_s;
    const int table_index = std::stoi(e.seat), seat = std::stoi(e.seat.substr(e.seat.find('.') + 1));
    bool retaken = false;
    for (const Person& p : world.people())
      retaken |= p.seated && p.table == table_index && p.seat == seat && p.arrive_s >= t;
    if (retaken) continue;
    const int chair = ChairInstance(world, table_index, seat);
    world.SetTime(t - 0.1);
    const float occupied = SeatTemperature(world, chair);
    world.SetTime(t + 1.0);
    const float just_left = SeatTemperature(world, chair);
    world.SetTime(t + 600.0);
    const float later = SeatTemperature(world, chair);
    EXPECT_GT(occupied, 23.5f);
    EXPECT_GT(just_left, 23.5f);
    EXPECT_LT(later, just_left - 1.5f);
    checked = true;
    break;
  }
  EXPECT_TRUE(checked) << "no left seat stayed free";
}

TEST(Crowd, SeatedPeopleChangePostureButKeepTheirIdAndSeat) {
  const Scene scene = PaperRoom({"crowd.posture_change_interval_s=5"});
  const BandRadianceTable table;
  World world(scene, table);
  std::map<int, std::set<std::string>> postures;
  std::map<int, std::pair<int, int>> seat_of;
  for (double t = 0; t < 60; t += 1.0) {
    world.SetTime(t);
    for (const Person& p : world.people()) {
      if (!p.present) continue;
      postures[p.person_id].insert(p.posture);
      EXPECT_EQ(world.instance(p.instance).person_id, p.person_id);
      const auto seat = std::make_pair(p.table, p.seat);
      EXPECT_EQ(seat_of.emplace(p.person_id, seat).first->second, seat);
    }
  }
  EXPECT_EQ(postures.size(), 24u);
  int changed = 0;
  for (const auto& [id, set] : postures) changed += set.size() > 1;
  EXPECT_GT(changed, 12);
}

// True if p lies strictly inside rectangle o (shrunk by 1 mm, so touching does not count).
bool InsideRectangle(const Eigen::Vector2d& p, const Obstacle2D& o) {
  const Eigen::Vector2d local = Eigen::Rotation2Dd(-o.yaw_rad) * (p - o.center_m);
  return std::abs(local.x()) < o.half_size_m.x() - 1e-3 && std::abs(local.y()) < o.half_size_m.y() - 1e-3;
}

TEST(Crowd, IrregularChairsNeverOverlapEachOtherAndAreReallyIrregular) {
  const BandRadianceTable table;
  for (const char* room : {"paper_room", "crowded_room"}) {
    for (int seed = 1; seed <= 4; ++seed) {
      const Scene scene = LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/" + room + ".json",
                                    {"seed=" + std::to_string(seed), "frames=10"});
      World world(scene, table);
      std::vector<Obstacle2D> chairs;
      for (const Obstacle2D& o : world.obstacles()) {
        if (o.name.rfind("chair", 0) == 0) chairs.push_back(o);
      }
      ASSERT_GE(chairs.size(), 24u) << room;
      int turned = 0;
      for (size_t i = 0; i < chairs.size(); ++i) {
        const double off_axis = std::remainder(chairs[i].yaw_rad, M_PI / 2);
        turned += std::abs(off_axis) > 1 * M_PI / 180 ? 1 : 0;
        // A 9 x 9 lattice of points over chair i must stay out of every other chair.
        for (int a = 0; a <= 8; ++a) {
          for (int b = 0; b <= 8; ++b) {
            const Eigen::Vector2d local((a / 4.0 - 1) * chairs[i].half_size_m.x(),
                                        (b / 4.0 - 1) * chairs[i].half_size_m.y());
            const Eigen::Vector2d p = chairs[i].center_m + Eigen::Rotation2Dd(chairs[i].yaw_rad) * local;
            for (size_t j = 0; j < chairs.size(); ++j) {
              if (j == i) continue;
              ASSERT_FALSE(InsideRectangle(p, chairs[j]))
                  << room << " seed " << seed << ": " << chairs[i].name << " in " << chairs[j].name;
            }
          }
        }
      }
      EXPECT_GT(turned, static_cast<int>(chairs.size()) / 2) << room << " seed " << seed;
    }
  }
}

TEST(Crowd, WalkersStayOnTheRouteAheadOfTheRobotAndClearOfFurniture) {
  // Walkers follow the robot's true path; on the route itself (an ideal robot) it keeps 0.3 m
  // from the furniture, which the drifting default robot does not (tests/sim/robot_test.cpp).
  const Scene scene = PaperRoom({"crowd.walkers=6", "robot.navigation=ground_truth"});
  const BandRadianceTable table;
  World world(scene, table);
  const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
  world.PlanCrowd(run.samples);
  int walkers = 0;
  for (size_t f = 0; f < run.samples.size(); f += 25) {
    world.SetTime(run.samples[f].time_s);
    for (const Person& p : world.people()) {
      if (p.seated || !p.present) continue;
      const Eigen::Vector2d at = world.caster().transform_of(p.instance).topRightCorner<2, 1>().cast<double>();
      // On the route 0.3 m; walking in or out round the furniture's corners, the body's radius.
      const bool door_walk = p.posture == "enter" || p.posture == "leave";
      const double needed_m = door_walk ? kWalkerRadiusM * p.height_scale - 0.005 : 0.3;
      for (const Obstacle2D& o : world.obstacles()) {
        if (o.name.rfind("chair", 0) != 0 && o.name.rfind("table", 0) != 0) continue;
        EXPECT_GT(DistanceToObstacle(at, o), needed_m) << o.name << " at frame " << f << " (" << p.posture << ")";
      }
      const Eigen::Vector2d robot(run.samples[f].base.x_m, run.samples[f].base.y_m);
      if (f + 200 < run.samples.size()) {
        EXPECT_GT((at - robot).norm(), 0.6) << "frame " << f;
      }
      ++walkers;
    }
  }
  EXPECT_GT(walkers, 0);
}

// Occlusion fraction of each seated person in view, by (frame, person id), every 4th frame of the
// whole run (walkers come and go).
std::map<std::pair<size_t, int>, double> SeatedOcclusion(const std::vector<std::string>& overrides) {
  const Scene scene = PaperRoom(overrides);
  const BandRadianceTable table;
  World world(scene, table);
  const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
  world.PlanCrowd(run.samples);
  const CameraIntrinsics intrinsics = IntrinsicsFromScene(scene);
  FrameRenderer renderer(world, intrinsics, RenderOptionsFromScene(scene, 0));
  std::map<std::pair<size_t, int>, double> occlusion;
  for (size_t f = 0; f < run.samples.size(); f += 4) {
    world.SetTime(run.samples[f].time_s);
    const FrameBuffers frame = renderer.Render(run.samples[f].camera);
    for (const PersonRecord& p :
         VisiblePersons(world, intrinsics, run.samples[f].camera, frame.instance, frame.depth_m)) {
      if (p.seated) occlusion[{f, p.id}] = p.occlusion_fraction;
    }
  }
  return occlusion;
}

TEST(Crowd, WalkersWithNoRoomToWalkAreAWarningNamingThemNotASilentlySmallerCrowd) {
  auto warnings = [](int walkers) {
    const Scene scene = PaperRoom({"crowd.walkers=" + std::to_string(walkers)});
    const BandRadianceTable table;
    World world(scene, table);
    world.PlanCrowd(SimulateSceneRobot(scene, world.obstacles()).samples);
    return world.warnings();
  };
  EXPECT_TRUE(warnings(2).empty());
  // The paper room's 0.7 m aisles: walkers after the first few find no clear time to walk.
  const std::vector<std::string> crowded = warnings(8);
  ASSERT_EQ(crowded.size(), 1u);
  EXPECT_NE(crowded[0].find("paper_room.json: crowd.walkers is 8, but walker"), std::string::npos) << crowded[0];
  EXPECT_NE(crowded[0].find(" in the room for less than 5 % of the run"), std::string::npos) << crowded[0];
}

TEST(Crowd, WalkersHideSeatedPeopleAndNeverUncoverThem) {
  // The robot's run and the seated crowd do not depend on the walkers, so each seated person in
  // each frame is compared with and without them: walkers can only add occlusion. Seated people
  // hide each other and sit behind chair backs (~0.8 without walkers); walkers keep 1.6 m or more
  // ahead of the camera in the paper room's 0.7 m aisles, so they hide a seated person in only a
  // small share of views, and more walkers never fewer.
  const auto none = SeatedOcclusion({"crowd.walkers=0"});
  auto more_hidden = [&](int walkers) {
    const auto with = SeatedOcclusion({"crowd.walkers=" + std::to_string(walkers)});
    EXPECT_EQ(with.size(), none.size()) << walkers << " walkers";
    int hidden = 0;
    for (const auto& [key, fraction] : none) {
      const auto it = with.find(key);
      if (it == with.end()) continue;
      EXPECT_GE(it->second, fraction - 1e-12) << "frame " << key.first << ", person " << key.second;
      hidden += it->second > fraction + 0.05;
    }
    return hidden;
  };
  const int some = more_hidden(4), many = more_hidden(8);
  EXPECT_GE(some, 5) << "of " << none.size() << " seated views";
  EXPECT_GE(many, some);
  std::printf("seated views hidden more by walkers (of %zu): 4 walkers %d, 8 walkers %d\n", none.size(), some, many);
}

}  // namespace
}  // namespace hoilcd

namespace hoilcd {
namespace {

TEST(Crowd, PaperRouteDrivesTwoClockwiseLapsClearOfTheRealFurniture) {
  // The route's clearance, driven by an ideal robot; the drifting default robot comes closer.
  const Scene scene = PaperRoom({"robot.navigation=ground_truth"});
  const BandRadianceTable table;
  World world(scene, table);
  const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
  for (size_t i = 0; i < world.obstacles().size(); ++i) {
    const std::string& name = world.obstacles()[i].name;
    if (name.rfind("chair", 0) != 0 && name.rfind("table", 0) != 0) continue;
    EXPECT_GE(run.obstacle_distance_m[i], 0.3) << name;
  }
  // The scene's own route and robot (not the robot module's defaults): about two clockwise laps
  // in 1996 frames, inside the room, within the steering limit.
  ASSERT_EQ(run.samples.size(), 1996u);
  EXPECT_GE(run.laps, 1.8);
  EXPECT_LE(run.laps, 2.2);
  EXPECT_LT(run.heading_change_rad, -1.5 * 2 * M_PI);
  const TricycleOptions robot = TricycleOptionsFromScene(scene);
  EXPECT_LE(run.max_curvature_per_m, std::tan(robot.max_steer_deg * M_PI / 180) / robot.wheelbase_m + 1e-9);
  for (const RobotSample& s : run.samples) {
    EXPECT_GT(s.base.x_m, 0.2);
    EXPECT_LT(s.base.x_m, 6.8);
    EXPECT_GT(s.base.y_m, 0.2);
    EXPECT_LT(s.base.y_m, 2.8);
  }
}

}  // namespace
}  // namespace hoilcd

namespace hoilcd {
namespace {

TEST(Crowd, StandingPeopleAreSeenAndTheRobotMustNotRunIntoThem) {
  // A deeper room leaves space by the north wall for two people chatting.
  const Scene scene = PaperRoom({"room.size_m=[7.0, 4.0, 2.6]",
                                 "crowd.standing=[{\"position_m\": [3.0, 3.5], \"yaw_deg\": 0},"
                                 " {\"position_m\": [3.6, 3.5], \"yaw_deg\": 180}]"});
  const BandRadianceTable table;
  World world(scene, table);
  const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
  const CameraIntrinsics intrinsics = IntrinsicsFromScene(scene);
  FrameRenderer renderer(world, intrinsics, RenderOptionsFromScene(scene, 0));
  std::set<int> standing_seen;
  for (size_t f = 0; f < run.samples.size(); f += 20) {  // the whole run: walkers come and go
    world.SetTime(run.samples[f].time_s);
    const FrameBuffers frame = renderer.Render(run.samples[f].camera);
    for (const PersonRecord& p :
         VisiblePersons(world, intrinsics, run.samples[f].camera, frame.instance, frame.depth_m)) {
      if (!p.seated && p.visible_fraction > 0.5) {
        EXPECT_EQ(p.posture, "standing");
        standing_seen.insert(p.id);
      }
    }
  }
  EXPECT_EQ(standing_seen.size(), 2u);
  // Standing on the route is a collision the robot simulation reports by name.
  const Scene blocked = PaperRoom({"crowd.standing=[{\"position_m\": [3.0, 2.62]}]"});
  World blocked_world(blocked, table);
  try {
    SimulateSceneRobot(blocked, blocked_world.obstacles());
    FAIL() << "the robot drove through a standing person";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("standing person"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hoilcd

namespace hoilcd {
namespace {

TEST(Crowd, SomePeopleShowSkinWhereOthersHaveHair) {
  const Scene scene = PaperRoom({"crowd.bald_fraction=0.5"});
  const BandRadianceTable table;
  const World world(scene, table);
  int bald = 0, haired = 0;
  for (const Person& p : world.people()) {
    const InstanceInfo& info = world.instance(p.parts[3]);  // the head
    const int hair = info.asset->MaterialIndex("hair"), skin = info.asset->MaterialIndex("skin");
    ASSERT_GE(hair, 0);
    const float difference = info.materials[skin].temperature_c - info.materials[hair].temperature_c;
    (std::abs(difference - 1.0f) < 1e-3f ? bald : haired) += 1;
  }
  EXPECT_GT(bald, 3);
  EXPECT_GT(haired, 3);
}

}  // namespace
}  // namespace hoilcd

namespace hoilcd {
namespace {

// DepthIntoSlab answers from the part's moved bounding box only when no vertex can be in the
// slab: over random placements of every body part in and around a table-top slab, it equals the
// deepest vertex found one by one, and both the box's answer and the vertices' are exercised.
TEST(Crowd, DepthIntoSlabEqualsTheDeepestVertexAndSkipsOnlyPartsClearOfTheSlab) {
  AssetLibrary assets(ShippedAssetDir());
  const Skeleton skeleton(assets);
  const TableSlab slab{-0.004, 0.904, -0.004, 0.754, 0.706, 0.744};  // paper_room's table, grown 4 mm
  Rng rng = KeyedRng(3, "test.slab");
  int deep = 0, box_clear = 0;
  for (int trial = 0; trial < 8000; ++trial) {
    const Asset& part = skeleton.part(trial % Skeleton::kPartCount);
    const Eigen::Vector3d axis = Eigen::Vector3d(rng.Normal(0, 1), rng.Normal(0, 1), rng.Normal(0, 1)).normalized();
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.topLeftCorner<3, 3>() = Eigen::AngleAxisd(rng.Uniform(-M_PI, M_PI), axis).toRotationMatrix();
    m.topRightCorner<3, 1>() = Eigen::Vector3d(rng.Uniform(-0.2, 1.1), rng.Uniform(-0.2, 0.95), rng.Uniform(0.45, 1.0));
    double deepest = 0;
    Eigen::AlignedBox3d moved;
    for (const Eigen::Vector3f& v : part.mesh.positions_m) {
      const Eigen::Vector3d q = m.topLeftCorner<3, 3>() * v.cast<double>() + m.topRightCorner<3, 1>();
      moved.extend(q);
      if (q.x() > slab.x_min && q.x() < slab.x_max && q.y() > slab.y_min && q.y() < slab.y_max && q.z() > slab.z_min &&
          q.z() < slab.z_max) {
        deepest = std::max(deepest, slab.z_max - q.z());
      }
    }
    ASSERT_EQ(DepthIntoSlab(part, m, slab), deepest) << "trial " << trial << ", part " << part.part;
    deep += deepest > 0;
    const Eigen::AlignedBox3d slab_box(Eigen::Vector3d(slab.x_min, slab.y_min, slab.z_min),
                                       Eigen::Vector3d(slab.x_max, slab.y_max, slab.z_max));
    box_clear += !moved.intersects(slab_box);
  }
  EXPECT_GT(deep, 250) << box_clear;
  EXPECT_GT(box_clear, 250) << deep;
}

}  // namespace
}  // namespace hoilcd
