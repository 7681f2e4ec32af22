// Articulated people in the world: keypoints in the frames, motion of seated people and walkers,
// no body passing through furniture or another body, determinism.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <numeric>
#include <set>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/scene/scene_options.h"
#include "hoilcd/sim/world/world.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

Scene PaperRoom(const std::vector<std::string>& overrides) {
  return LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json", overrides);
}

// Standard deviation of a 3-D point cloud (root of the summed variances), m.
double Spread(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  double sum = 0;
  for (const auto& p : points) sum += (p - mean).squaredNorm();
  return std::sqrt(sum / static_cast<double>(points.size()));
}

TEST(People, InThirtySecondsMostSeatedPeopleMoveHeadOrHandAndWalkersSwingTheirAnkles) {
  const Scene scene = PaperRoom({"crowd.walkers=2"});
  const BandRadianceTable table;
  World world(scene, table);
  const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
  world.PlanCrowd(run.samples);
  std::map<int, std::array<std::vector<Eigen::Vector3d>, 3>> seated;  // nose, left and right wrist
  std::map<int, std::vector<double>> ankle_gap;                       // walkers: ankle to ankle, m
  for (int f = 0; f < 30 * 25; ++f) {
    world.SetTime(run.samples[f].time_s);
    for (const Person& p : world.people()) {
      if (!p.present) continue;
      if (p.seated) {
        for (int i = 0; i < 3; ++i) seated[p.person_id][i].push_back(p.keypoints_m[i == 0 ? 0 : 8 + i]);
      } else {
        ankle_gap[p.person_id].push_back((p.keypoints_m[kLeftAnkle] - p.keypoints_m[kRightAnkle]).norm());
      }
    }
  }
  int moving = 0;
  for (const auto& [id, tracks] : seated) {
    moving += Spread(tracks[0]) > 0.02 || Spread(tracks[1]) > 0.02 || Spread(tracks[2]) > 0.02;
  }
  ASSERT_EQ(seated.size(), 24u);
  EXPECT_GE(moving, static_cast<int>(0.8 * seated.size())) << moving << " of " << seated.size();
  ASSERT_EQ(ankle_gap.size(), 2u);
  for (const auto& [id, gaps] : ankle_gap) {
    const auto [lo, hi] = std::minmax_element(gaps.begin(), gaps.end());
    EXPECT_GT(*hi - *lo, 0.25) << "walker " << id;
  }
}

// Vertices of person `p` (all parts) in world coordinates, with their part's name.
std::vector<std::pair<Eigen::Vector3d, const char*>> BodyVertices(const World& world, const Person& p) {
  std::vector<std::pair<Eigen::Vector3d, const char*>> out;
  for (int part : p.parts) {
    const Eigen::Matrix4d m = world.caster().transform_of(part).cast<double>();
    for (const Eigen::Vector3f& v : world.instance(part).mesh->positions_m) {
      out.emplace_back(m.topLeftCorner<3, 3>() * v.cast<double>() + m.topRightCorner<3, 1>(),
                       world.instance(part).asset->part.c_str());
    }
  }
  return out;
}

// True if world point w lies inside the box (centre, half sizes, rotation) of an instance's frame.
bool InsideBox(const Eigen::Matrix4d& object_from_world, const Eigen::Vector3d& center, const Eigen::Matrix3d& axes,
               const Eigen::Vector3d& half, const Eigen::Vector3d& w, double shrink_m) {
  const Eigen::Vector3d local = object_from_world.topLeftCorner<3, 3>() * w + object_from_world.topRightCorner<3, 1>();
  const Eigen::Vector3d in_box = axes.transpose() * (local - center);
  return (in_box.cwiseAbs() - half).maxCoeff() < -shrink_m;
}

TEST(People, BodiesNeverPassThroughTableTopsChairBacksOrEachOther) {
  const Scene scene = PaperRoom({"crowd.walkers=2", "crowd.posture_change_interval_s=8"});
  const BandRadianceTable table;
  World world(scene, table);
  const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
  world.PlanCrowd(run.samples);
  const Eigen::Matrix3d back_axes = Eigen::AngleAxisd(-8 * M_PI / 180, Eigen::Vector3d::UnitY()).toRotationMatrix();
  int checked = 0;
  for (int f = 0; f < 1500; f += 30) {
    world.SetTime(run.samples[f].time_s);
    std::vector<std::pair<const Person*, std::vector<std::pair<Eigen::Vector3d, const char*>>>> bodies;
    for (const Person& p : world.people()) {
      if (p.present) bodies.emplace_back(&p, BodyVertices(world, p));
    }
    for (int i = 0; i < world.num_instances(); ++i) {
      const InstanceInfo& info = world.instance(i);
      if (info.role != InstanceRole::kTable && info.role != InstanceRole::kChair) continue;
      const Eigen::Matrix4d m = world.caster().transform_of(i).cast<double>().inverse();
      for (const auto& [person, vertices] : bodies) {
        for (const auto& [v, part] : vertices) {
          // The table top slab; the chair's backrest (people sit on the seat, so not the seat).
          const bool inside =
              info.role == InstanceRole::kTable
                  ? InsideBox(m, {0, 0, 0.725}, Eigen::Matrix3d::Identity(), {0.45, 0.375, 0.015}, v, 0.003)
                  : InsideBox(m, {-0.235, 0, 0.72}, back_axes, {0.015, 0.20, 0.13}, v, 0.003);
          ASSERT_FALSE(inside) << "frame " << f << ": the " << part << " of person " << person->person_id << " ("
                               << person->posture << ", " << person->activity << ") in " << info.name;
        }
      }
    }
    // Between people: keypoints sit on the axes of limbs 7.5-12 cm thick, so bodies that do not
    // pass through each other keep them 7.5 cm apart. Arms are checked as limb segments in
    // People.NeighboursArmsNeverMeetOnCrowdedTablesWhileTheyTalkAndDrink, and seated neighbours'
    // meshes in People.SeatedNeighboursNeverPassThroughEachOther.
    for (size_t a = 0; a < bodies.size(); ++a) {
      for (size_t b = a + 1; b < bodies.size(); ++b) {
        for (int ia = 0; ia < kCocoKeypointCount; ++ia) {
          for (int ib = 0; ib < kCocoKeypointCount; ++ib) {
            const Eigen::Vector3d &ka = bodies[a].first->keypoints_m[ia], &kb = bodies[b].first->keypoints_m[ib];
            const Person &pa = *bodies[a].first, &pb = *bodies[b].first;
            const bool arms = (ia >= 7 && ia <= 10) || (ib >= 7 && ib <= 10);
            if (arms) continue;  // see above
            ASSERT_GT((ka - kb).norm(), 0.075)
                << "frame " << f << ": " << kCocoKeypointNames[ia] << " of person " << pa.person_id << " (seat "
                << pa.table << "." << pa.seat << ", " << pa.posture << ", " << pa.activity << ") and "
                << kCocoKeypointNames[ib] << " of person " << pb.person_id << " (seat " << pb.table << "." << pb.seat
                << ", " << pb.posture << ", " << pb.activity << ") " << (ka - kb).norm() << " m apart";
          }
        }
      }
    }
    ++checked;
  }
  EXPECT_EQ(checked, 50);
}

// Distance from point p to the segment ab, m.
double ToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double f = std::clamp((p - a).dot(d) / std::max(1e-12, d.squaredNorm()), 0.0, 1.0);
  return (a + f * d - p).norm();
}

// Distance between segments ab and cd, m (sampled along ab at 1 cm).
double SegmentToSegment(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                        const Eigen::Vector3d& d) {
  double best = 1e9;
  const int steps = std::max(1, static_cast<int>((b - a).norm() / 0.01));
  for (int i = 0; i <= steps; ++i) best = std::min(best, ToSegment(a + (b - a) * (double(i) / steps), c, d));
  return best;
}

TEST(People, NeighboursArmsNeverMeetOnCrowdedTablesWhileTheyTalkAndDrink) {
  // Six to a table 0.45 m apart, talking and drinking often: the arms of neighbours (upper and
  // lower arm as segments shoulder-elbow-wrist) never meet.
  const Scene scene = LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/crowded_room.json",
                                {"crowd.activities.talking.weight=3", "crowd.activities.drinking.weight=2"});
  const BandRadianceTable table;
  World world(scene, table);
  const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
  world.PlanCrowd(run.samples);
  int pairs = 0;
  for (size_t f = 0; f < run.samples.size(); f += 10) {
    world.SetTime(run.samples[f].time_s);
    std::vector<const Person*> seated;
    for (const Person& p : world.people())
      if (p.present && p.seated) seated.push_back(&p);
    for (size_t a = 0; a < seated.size(); ++a) {
      for (size_t b = a + 1; b < seated.size(); ++b) {
        const Person &pa = *seated[a], &pb = *seated[b];
        if (pa.table != pb.table || (pa.seat < 3) != (pb.seat < 3)) continue;  // neighbours: same side of a table
        ++pairs;
        for (int sa = 0; sa < 2; ++sa) {
          for (int sb = 0; sb < 2; ++sb) {
            const auto& ka = pa.keypoints_m;
            const auto& kb = pb.keypoints_m;
            const double upper = SegmentToSegment(ka[5 + sa], ka[7 + sa], kb[5 + sb], kb[7 + sb]);
            const double lower = SegmentToSegment(ka[7 + sa], ka[9 + sa], kb[7 + sb], kb[9 + sb]);
            const double cross = std::min(SegmentToSegment(ka[5 + sa], ka[7 + sa], kb[7 + sb], kb[9 + sb]),
                                          SegmentToSegment(ka[7 + sa], ka[9 + sa], kb[5 + sb], kb[7 + sb]));
            // Upper and lower arms (3.5-4.5 cm radius) keep 7 cm between their axes.
            ASSERT_TRUE(std::min({upper, lower, cross}) > 0.07)
                << "frame " << f << ": " << (sa ? "right" : "left") << " arm of person " << pa.person_id << " (seat "
                << pa.table << "." << pa.seat << ", " << pa.posture << ", " << pa.activity << ") and "
                << (sb ? "right" : "left") << " arm of person " << pb.person_id << " (seat " << pb.table << "."
                << pb.seat << ", " << pb.posture << ", " << pb.activity << "): upper " << upper << ", lower " << lower
                << ", across " << cross << " m";
          }
        }
      }
    }
  }
  EXPECT_GT(pairs, 1000);
}

// An oriented box, world frame: its centre, and the map that takes it to [-1, 1]^3 (the inverse
// of its three half axes as columns).
struct OrientedBox {
  Eigen::Vector3d center;
  Eigen::Matrix3d unit_from_world;
};

// The box around a body part's mesh (its asset bounds, carried by its instance transform).
OrientedBox PartBox(const World& world, int instance) {
  const Eigen::Matrix4d m = world.caster().transform_of(instance).cast<double>();
  const Eigen::AlignedBox3d bounds = world.instance(instance).asset->bounds_m.cast<double>();
  const Eigen::Matrix3d half_axes = m.topLeftCorner<3, 3>() * (0.5 * bounds.sizes()).asDiagonal();
  return {m.topLeftCorner<3, 3>() * bounds.center() + m.topRightCorner<3, 1>(), half_axes.inverse()};
}

bool InsideBox(const OrientedBox& box, const Eigen::Vector3d& p) {
  return (box.unit_from_world * (p - box.center)).cwiseAbs().maxCoeff() <= 1;
}

// Does the ray o + t d (t > 0) cross triangle abc (Moller-Trumbore)?
bool RayCrosses(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a, h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-15) return false;
  const Eigen::Vector3d s = o - a;
  const double u = s.dot(h) / det;
  if (u < 0 || u > 1) return false;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < 0 || u + v > 1) return false;
  return e2.dot(q) / det > 0;
}

// True if world point w is inside the mesh of a body-part instance. A part is one or more closed
// surfaces (a loft and two shoulder caps, say) that may overlap, so the ray parity is counted per
// surface (connected set of triangles).
// `surfaces` caches each mesh's surface of every triangle, for one world's meshes only.
using SurfaceCache = std::map<const TriangleMesh*, std::vector<int>>;
bool InsidePart(const World& world, int instance, const Eigen::Vector3d& w, SurfaceCache* surfaces) {
  const TriangleMesh& mesh = *world.instance(instance).mesh;
  std::vector<int>& surface = (*surfaces)[&mesh];
  if (surface.empty()) {
    std::vector<int> root(mesh.positions_m.size());
    std::iota(root.begin(), root.end(), 0);
    const std::function<int(int)> find = [&](int i) { return root[i] == i ? i : root[i] = find(root[i]); };
    for (size_t t = 0; t < mesh.TriangleCount(); ++t) {
      for (int k = 1; k < 3; ++k) root[find(mesh.indices[3 * t + k])] = find(mesh.indices[3 * t]);
    }
    for (size_t t = 0; t < mesh.TriangleCount(); ++t) surface.push_back(find(mesh.indices[3 * t]));
  }
  const Eigen::Matrix4d m = world.caster().transform_of(instance).cast<double>();
  const Eigen::Vector3d local = m.inverse().topLeftCorner<3, 3>() * w + m.inverse().topRightCorner<3, 1>();
  const Eigen::Vector3d direction = Eigen::Vector3d(0.123, 0.271, 0.955).normalized();  // off every axis
  std::map<int, int> crossings;
  for (size_t t = 0; t < mesh.TriangleCount(); ++t) {
    const auto corner = [&](int k) { return mesh.positions_m[mesh.indices[3 * t + k]].cast<double>(); };
    if (RayCrosses(local, direction, corner(0), corner(1), corner(2))) ++crossings[surface[t]];
  }
  return std::any_of(crossings.begin(), crossings.end(), [](const auto& c) { return c.second % 2 == 1; });
}

// Seated neighbours (same table and side) never pass through each other: no vertex of one lies
// inside a body part of the other, at the paper room's 0.45 m seats with a wide spread of body
// sizes, and six to a table in the crowded room (tight seats cap body size: Crowd::Plan).
TEST(People, SeatedNeighboursNeverPassThroughEachOther) {
  const std::string scenes = std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/";
  int pairs = 0, near_vertices = 0;
  for (const auto& [file, overrides] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"paper_room.json", {"crowd.height_scale_sd=0.1", "crowd.posture_change_interval_s=8"}},
           {"crowded_room.json", {"crowd.activities.talking.weight=3", "crowd.activities.drinking.weight=2"}}}) {
    const Scene scene = LoadScene(scenes + file, overrides);
    const BandRadianceTable table;
    World world(scene, table);
    const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
    world.PlanCrowd(run.samples);
    SurfaceCache surfaces;  // keyed by mesh address: never kept past this world
    for (size_t f = 0; f < run.samples.size(); f += 40) {
      world.SetTime(run.samples[f].time_s);
      std::vector<const Person*> seated;
      for (const Person& p : world.people())
        if (p.present && p.seated) seated.push_back(&p);
      for (const Person* pa : seated) {
        for (const Person* pb : seated) {
          if (pa == pb || pa->table != pb->table || (pa->seat < 3) != (pb->seat < 3)) continue;
          ++pairs;
          const auto vertices = BodyVertices(world, *pa);
          for (int part : pb->parts) {
            const OrientedBox box = PartBox(world, part);
            for (const auto& [v, name] : vertices) {
              if (!InsideBox(box, v)) continue;
              ++near_vertices;
              ASSERT_FALSE(InsidePart(world, part, v, &surfaces))
                  << file << " frame " << f << ": the " << name << " of person " << pa->person_id << " (seat "
                  << pa->table << "." << pa->seat << ", scale " << pa->height_scale << ", " << pa->activity
                  << ") is inside the " << world.instance(part).asset->part << " of person " << pb->person_id
                  << " (seat " << pb->table << "." << pb->seat << ", scale " << pb->height_scale << ", " << pb->activity
                  << ")";
            }
          }
        }
      }
    }
  }
  EXPECT_GT(pairs, 1000);
  EXPECT_GT(near_vertices, 0);  // the check had something to check
}

TEST(People, SeatsTooCloseForAnyBodyAreRefusedAtTheirJsonPath) {
  const Scene scene = PaperRoom({"crowd.people_per_table=6", "furniture.seat_spacing_6_m=0.3"});
  const BandRadianceTable table;
  try {
    World world(scene, table);
    FAIL() << "seats 0.3 m apart were accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("paper_room.json"), std::string::npos) << message;
    EXPECT_NE(message.find("/furniture/seat_spacing_6_m: seats 0.3 m apart leave no room for a seated person"),
              std::string::npos)
        << message;
  }
}

TEST(People, VisibleKeypointsLandOnTheirPersonsInstanceInTheExr) {
  const Scene scene = PaperRoom({"crowd.walkers=2"});
  const test::TestDir temp;
  const std::string dir = temp / "keypoints";
  SequenceOptions options;
  options.output_dir = dir;
  options.frames = 40;
  RenderSequence(scene, options);
  // The person -> instance label map of the same scene.
  const BandRadianceTable table;
  World world(scene, table);
  world.PlanCrowd(SimulateSceneRobot(scene, world.obstacles()).samples);
  std::map<int, int> instance_of;
  for (const Person& p : world.people()) instance_of[p.person_id] = p.instance;

  const Dataset dataset = Dataset::Open(dir);
  int visible = 0, on_person = 0, listed = 0;
  for (const FramePersons& frame : dataset.persons()) {
    cv::Mat ids;
    for (const auto& [name, channel] : ReadDatasetExr(dataset, frame.frame)) {
      if (name == "id") channel.convertTo(ids, CV_32S);
    }
    ASSERT_FALSE(ids.empty());
    for (const PersonRecord& person : frame.persons) {
      ASSERT_EQ(person.keypoints.size(), 17u);
      EXPECT_EQ(person.keypoints[kNose].name, "nose");
      EXPECT_EQ(person.keypoints[kRightAnkle].name, "right_ankle");
      ++listed;
      for (const KeypointRecord& k : person.keypoints) {
        if (!k.visible) continue;
        ++visible;
        const int u = static_cast<int>(std::lround(k.u_px)), v = static_cast<int>(std::lround(k.v_px));
        on_person += ids.at<int>(v, u) == instance_of.at(person.id);
      }
    }
  }
  ASSERT_GT(listed, 40);
  ASSERT_GT(visible, 200);
  EXPECT_GE(on_person, 0.95 * visible) << on_person << " of " << visible;
}

TEST(People, MotionIsTheSameForTheSameSeedAndDiffersForAnother) {
  auto nose_track = [](const std::string& seed) {
    const Scene scene = PaperRoom({"seed=" + seed, "crowd.walkers=1"});
    const BandRadianceTable table;
    World world(scene, table);
    world.PlanCrowd(SimulateSceneRobot(scene, world.obstacles()).samples);
    std::vector<double> out;
    for (double t = 0; t < 20; t += 0.5) {
      world.SetTime(t);
      for (const Person& p : world.people()) {
        if (p.present) out.push_back(p.keypoints_m[kNose].x() + p.keypoints_m[kLeftWrist].z());
      }
    }
    return out;
  };
  const std::vector<double> a = nose_track("5"), b = nose_track("5"), c = nose_track("6");
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(People, UnknownActivitiesAndOutOfRangeDwellTimesAreErrorsNamingThePath) {
  try {
    PaperRoom({"crowd.activities.juggling={\"weight\": 1}"});
    FAIL() << "an unknown activity was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/crowd/activities"), std::string::npos) << e.what();
  }
  try {
    PaperRoom({"crowd.activities.drinking.dwell_s=0.2"});
    FAIL() << "a dwell time under 1.5 s was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/crowd/activities/drinking/dwell_s"), std::string::npos) << e.what();
  }
  ActivityOptions options = PaperRoom({}).crowd.activity;
  EXPECT_EQ(options.Check(), "");
  options.activities["juggling"] = {1, 5};
  EXPECT_EQ(options.Check().rfind("activities: unknown activity 'juggling'", 0), 0u) << options.Check();
}

}  // namespace
}  // namespace hoilcd

namespace hoilcd {
namespace {

TEST(People, WalkersKeepPaceWalkAwayApproachAndStopWithoutMeetingTheRobotOrEachOther) {
  // Two walkers (approaching through a busier lane clashes with others: those bouts become "gone").
  const Scene scene =
      PaperRoom({"crowd.walkers=2", "crowd.walker_behaviours.approach=3", "crowd.walker_behaviours.stop_to_chat=1"});
  const BandRadianceTable table;
  World world(scene, table);
  const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
  world.PlanCrowd(run.samples);
  std::set<std::string> seen;
  bool faced_robot = false;
  for (size_t f = 0; f < run.samples.size(); f += 5) {
    world.SetTime(run.samples[f].time_s);
    const Eigen::Vector2d robot(run.samples[f].base.x_m, run.samples[f].base.y_m);
    std::vector<Eigen::Vector2d> at;
    for (const Person& p : world.people()) {
      if (p.seated || !p.present) continue;
      seen.insert(p.posture);
      const Eigen::Vector2d hips = 0.5 * (p.keypoints_m[kLeftHip] + p.keypoints_m[kRightHip]).head<2>();
      EXPECT_GT((hips - robot).norm(), 0.6) << "frame " << f << ": " << p.posture;
      for (const Eigen::Vector2d& other : at) EXPECT_GT((hips - other).norm(), 0.4) << "frame " << f;
      at.push_back(hips);
      if (p.posture == "approach") {
        // Facing the robot: the nose is on the robot's side of the hips.
        const Eigen::Vector2d nose = p.keypoints_m[kNose].head<2>();
        faced_robot |= (nose - hips).dot(robot - hips) > 0;
      }
    }
  }
  for (const char* behaviour : {"ahead", "away", "approach", "stop_to_chat"})
    EXPECT_TRUE(seen.count(behaviour)) << behaviour;
  EXPECT_TRUE(faced_robot);
}

}  // namespace
}  // namespace hoilcd
