// The world as the renderer sees it: the room, furniture, people and objects of a Scene as
// Embree instances with per-instance thermal materials and class ids, the seated people with
// their seats and contact points, and the 2-D obstacles the robot must avoid.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "hoilcd/core/dataset.h"
#include "hoilcd/core/random.h"
#include "hoilcd/sim/asset.h"
#include "hoilcd/sim/crowd_motion.h"
#include "hoilcd/sim/radiometry.h"
#include "hoilcd/sim/ray_caster.h"
#include "hoilcd/sim/robot.h"
#include "hoilcd/sim/scene.h"
#include "hoilcd/sim/skeleton.h"
#include "hoilcd/sim/walker_planner.h"

namespace hoilcd {

// A material as one instance shows it this frame. Radiance is linear in height between the
// bottom and top values (walls are warmer near the ceiling); other materials have bottom == top.
struct InstanceMaterial {
  float temperature_c = 22;
  float temperature_top_c = 22;
  float emissivity = 0.9f;
  bool specular = false;
  int class_id = 0;            // class of pixels showing this material (the room has several)
  float blackbody_bottom = 0;  // band radiance at z = 0, W·m⁻²·sr⁻¹
  float blackbody_top = 0;     // band radiance at z = room height
};

enum class InstanceRole { kRoom, kTable, kChair, kPerson, kObject };

struct InstanceInfo {
  InstanceRole role = InstanceRole::kObject;
  std::string name;                     // "table 3", "person 7", "cup 2"
  int class_id = 0;                     // the instance's class (its materials may refine it)
  int person_id = -1;                   // stable id for people, else -1
  int label = -1;                       // id written to the frame's instance channel: the
                                        // instance itself, or a person's pelvis for every body part
  const Asset* asset = nullptr;         // null for the room
  std::vector<InstanceMaterial> materials;  // per prototype material
  const TriangleMesh* mesh = nullptr;   // the prototype's mesh (triangle -> material index)
};

// One person over the whole sequence (ids are stable and never reused). A seated person sits
// on one seat from arrive_s to leave_s, changes posture from time to time (blending smoothly)
// and goes through activities (crowd_motion.h); a walker follows its plan (walker_planner.h).
// Every person is an articulated body: one instance per skeleton part, moved by
// per-part transforms. SetTime() updates `present`, `posture`, `activity`, the keypoints and
// contacts.
struct Person {
  int person_id = 0;
  bool seated = true;
  int table = -1, seat = -1;                 // seated people
  double arrive_s = 0, leave_s = 1e30;       // present in [arrive_s, leave_s)
  std::vector<std::pair<double, std::string>> postures;  // (from time s, posture), ascending
  std::vector<ActivityEpisode> activities;   // seated: what the person does, in time order
  std::array<int, Skeleton::kPartCount> parts{};  // instance of each body part
  int instance = -1;                         // the pelvis part: the person's id in the frames
  int cup = -1, laptop = -1;                 // instances of the person's cup and laptop, or -1
  Eigen::Vector3d cup_at_m = Eigen::Vector3d::Zero();     // cup's resting place, seat frame
  Eigen::Vector3d laptop_at_m = Eigen::Vector3d::Zero();  // laptop's place, seat frame
  Eigen::Matrix4f world_from_seat = Eigen::Matrix4f::Identity();
  Eigen::Matrix4d table_from_seat = Eigen::Matrix4d::Identity();  // seated: their table's frame
  double elbow_room_m = 1;                   // seated: half the gap to the nearest seat beside them
  double table_edge_m = 0.30;                // seated: seat centre to the table's near edge, m
  double height_scale = 1;
  double sway_phase_rad = 0, sway_period_s = 7, breathing_phase_rad = 0;
  double lead_s = 5, lead_amplitude_s = 1.5, lead_period_s = 20, lead_phase_rad = 0;  // walkers (< 0: stands still)
  double lateral_m = 0;                      // walkers: offset to the left of the route
  int walker = -1;                           // walkers: index of their plan (walker_planner.h)
  // State at the current time.
  bool present = false;
  std::string posture;                       // base posture ("seated_upright", "walking", ...)
  std::string activity;                      // seated: current activity ("idle", "drinking", ...)
  std::array<Eigen::Vector3d, kCocoKeypointCount> keypoints_m{};  // world frame
  std::vector<std::pair<std::string, Eigen::Vector3d>> contacts_m;  // world frame: seat, floor, table
};

// For compatibility with code that thinks of everyone as seated.
using SeatedPerson = Person;

class World {
 public:
  World(const Scene& scene, const BandRadianceTable& table);

  // Plans what depends on the robot's run: seat turnover at each lap boundary (people leave,
  // arrive, change seats; events recorded) and the walkers' bouts around the robot. Call once,
  // before SetTime, with the run's per-frame samples. Throws InputError naming /route/waypoints_m
  // when walkers are asked for but a walker's body cannot follow the route clear of furniture.
  void PlanCrowd(const std::vector<RobotSample>& samples);

  // Moves people (posture, breathing, sway, walking), warms and cools seats, to time t, and
  // recommits the ray caster.
  void SetTime(double time_s);

  // arrive / leave / swap events of PlanCrowd, in frame order.
  const std::vector<DatasetEvent>& events() const { return events_; }

  const RayCaster& caster() const { return *caster_; }
  const InstanceInfo& instance(int id) const { return instances_[id]; }
  int num_instances() const { return static_cast<int>(instances_.size()); }
  const std::map<std::string, int>& classes() const { return classes_; }
  // Everyone who appears in the sequence; `present` says who is in the room at the current time.
  const std::vector<Person>& people() const { return people_; }
  const std::vector<Obstacle2D>& obstacles() const { return obstacles_; }
  const Skeleton& skeleton() const { return *skeleton_; }
  double room_height_m() const { return room_size_m_.z(); }
  // Band radiance of the room's surroundings, for diffuse reflection (L_env).
  float environment_radiance() const { return environment_radiance_; }
  const BandRadianceTable& radiance_table() const { return table_; }

 private:
  int ClassId(const std::string& name);
  int Place(const Asset& asset, const Eigen::Matrix4f& world_from_object, InstanceRole role,
            std::string name, double temperature_offset_c);
  void BuildRoom(const Scene& scene);
  void BuildFurnitureAndPeople(const Scene& scene);
  void Finish(InstanceMaterial* m) const;
  // Adds a seated person (instances for every posture they will take) and returns its index.
  // person_id < 0: a new person; else that person (same appearance) on another seat.
  size_t AddSeatedPerson(int table, int seat, const std::string& posture, double arrive_s, double leave_s,
                         int person_id = -1);
  // Adds a person standing (walker or standing still) with varied size and temperatures.
  Person& AddStandingPerson(const std::string& kind, Rng* rng);
  // Places the body parts of a person (hidden until SetTime) with their temperatures.
  std::array<int, Skeleton::kPartCount> AddBody(int person_id, const std::string& name, double skin_c,
                                                 double clothing_c, double hair_c);
  // Keeps a seated person out of their table's top: arms are lifted onto it, the trunk leans
  // less where it would meet the edge (the chairs stand irregularly, so fixed poses cannot).
  void KeepClearOfTable(const Person& p, BodyPose* pose) const;
  // The pose (person frame) and world_from_person of a present person at time t.
  BodyPose PoseOf(const Person& p, double time_s, Eigen::Matrix4d* world_from_person) const;
  // The id a new person gets: one past the largest so far (0 for the first).
  int NextPersonId() const;
  void SetPersonTemperatures(int instance, const Asset& body, double skin_c, double clothing_c, double hair_c);
  void UpdateSeatWarmth(double time_s);

  struct Seat {
    int table = 0, seat = 0;
    int chair_instance = -1;
    Eigen::Matrix4f world_from_seat = Eigen::Matrix4f::Identity();
    std::vector<InstanceMaterial> chair_materials;  // at room temperature
  };

  const BandRadianceTable& table_;
  AssetLibrary assets_;
  std::unique_ptr<Skeleton> skeleton_;
  std::vector<Eigen::Matrix4d> world_from_table_;  // per table
  Eigen::AlignedBox3f table_bounds_m_;             // the table asset's bounds (top at max z)
  ActivityOptions activity_options_;
  std::unique_ptr<RayCaster> caster_;
  std::map<const Asset*, int> prototype_of_asset_;
  std::vector<InstanceInfo> instances_;
  TriangleMesh room_mesh_;
  std::map<std::string, int> classes_;
  std::vector<Person> people_;
  std::vector<Seat> seats_;
  RobotTrack robot_;                          // the robot's run (PlanCrowd)
  std::vector<DatasetEvent> events_;
  std::vector<WalkerPlan> walker_plans_;
  uint64_t seed_ = 1;
  double frame_rate_hz_ = 25, duration_s_ = 80;
  nlohmann::json crowd_;
  double seat_warmth_c_ = 2, heat_print_tau_s_ = 120, posture_interval_s_ = 0;
  std::vector<Obstacle2D> obstacles_;
  Eigen::Vector3d room_size_m_;
  float environment_radiance_ = 0;
  double breathing_amplitude_m_ = 0, breathing_period_s_ = 4, sway_amplitude_rad_ = 0;
  std::string scene_file_;         // named in errors found by PlanCrowd
};

// World transform of an asset placed at position with a yaw about z (and uniform scale).
Eigen::Matrix4f PlacementTransform(const Eigen::Vector3d& position_m, double yaw_rad,
                                   double scale = 1.0);

}  // namespace hoilcd
