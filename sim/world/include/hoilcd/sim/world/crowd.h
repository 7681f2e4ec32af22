// The people of a scene over the whole sequence: seated people (seats, postures, activities,
// props, seat turnover and the warmth they leave on their chairs), people standing still and
// walkers (planned by walker_planner.h), posed at a time as articulated bodies. The World owns one Crowd
// and lends it the instance services of the ray caster through CrowdStage.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/random.h"
#include "hoilcd/sim/assets/asset.h"
#include "hoilcd/sim/assets/instance.h"
#include "hoilcd/sim/assets/skeleton.h"
#include "hoilcd/sim/people/crowd_motion.h"
#include "hoilcd/sim/people/crowd_options.h"
#include "hoilcd/sim/people/garments.h"
#include "hoilcd/sim/people/walker_planner.h"
#include "hoilcd/sim/robot/robot.h"
#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/world/contact_heat.h"

namespace hoilcd {

// One person over the whole sequence (ids are stable and never reused). A seated person sits
// on one seat from arrive_s to leave_s, changes posture from time to time (blending smoothly)
// and goes through activities (crowd_motion.h); a walker follows its plan (walker_planner.h).
// Every person is an articulated body: one instance per skeleton part, moved by
// per-part transforms. SetTime() updates `present`, `posture`, `activity`, the keypoints and
// contacts.
struct Person {
  int person_id = 0;
  bool seated = true;
  int table = -1, seat = -1;                              // seated people
  double arrive_s = 0, leave_s = 1e30;                    // present in [arrive_s, leave_s)
  std::vector<std::pair<double, std::string>> postures;   // (from time s, posture), ascending
  std::vector<ActivityEpisode> activities;                // seated: what the person does, in time order
  std::array<int, Skeleton::kPartCount> parts{};          // instance of each body part
  int instance = -1;                                      // the pelvis part: the person's id in the frames
  int cup = -1, laptop = -1;                              // instances of the person's cup and laptop, or -1
  Eigen::Vector3d cup_at_m = Eigen::Vector3d::Zero();     // cup's resting place, seat frame
  Eigen::Vector3d laptop_at_m = Eigen::Vector3d::Zero();  // laptop's place, seat frame
  Eigen::Matrix4f world_from_seat = Eigen::Matrix4f::Identity();
  Eigen::Matrix4d table_from_seat = Eigen::Matrix4d::Identity();  // seated: their table's frame
  std::array<double, 2> side_room_m{1, 1};                        // seated: the same on the left (+y) and on the right
  double table_edge_m = 0.30;                                     // seated: seat centre to the table's near edge, m
  bool at_table_top = true;  // seated: their hands reach a table top (not on a sofa)
  double height_scale = 1;
  double sway_phase_rad = 0, sway_period_s = 7, breathing_phase_rad = 0;
  double lead_s = 5, lead_amplitude_s = 1.5, lead_period_s = 20, lead_phase_rad = 0;  // walkers (< 0: stands still)
  double lateral_m = 0;                      // walkers: offset to the left of the route
  int walker = -1;                           // walkers: index of their plan (walker_planner.h)
  Ensemble ensemble;                         // what they wear (garments.h)
  std::vector<ClothingStep> clothing_steps;  // their garments' targets as their activity changes
  // State at the current time.
  bool present = false;
  std::string posture;                                            // base posture ("seated_upright", "walking", ...)
  std::string activity;                                           // seated: current activity ("idle", "drinking", ...)
  std::array<Eigen::Vector3d, kCocoKeypointCount> keypoints_m{};  // world frame
  std::vector<std::pair<std::string, Eigen::Vector3d>> contacts_m;  // world frame: seat, floor, table
};

// Seated body sizes are drawn in [kMinSeatedBodyScale, 1.2] and capped so that neighbours'
// shoulders keep kSeatedShoulderGapM apart at the scene's tightest seats.
constexpr double kMinSeatedBodyScale = 0.8;
constexpr double kSeatedShoulderGapM = 0.01;

// What the crowd asks of the world it lives in (the World implements it).
class CrowdStage {
 public:
  virtual ~CrowdStage() = default;
  // Adds an instance of `asset` and returns its id (ids are given in call order).
  virtual int Place(const Asset& asset, const Eigen::Matrix4f& world_from_object, InstanceRole role, std::string name,
                    double temperature_offset_c) = 0;
  virtual InstanceInfo& MutableInstance(int id) = 0;
  virtual void Move(int instance, const Eigen::Matrix4f& world_from_object) = 0;
  // Sets a material's band radiances from its temperatures.
  virtual void Finish(InstanceMaterial* material) const = 0;
};

class Crowd {
 public:
  // `assets` and `stage` must outlive the crowd.
  Crowd(const Scene& scene, AssetLibrary* assets, CrowdStage* stage);

  // Who sits where at the start: the scene's list, or people_per_table random seats per table
  // (of SeatsOf: seats 0..per_side-1 on one side, 3..3+per_side-1 on the other, for both_sides).
  static std::vector<SeatingSpec> InitialSeating(const Scene& scene, int per_side);

  // The furniture as the World places it, in order: a table (its frame, its asset's bounds with
  // the top at max z, how it seats people, its instance), then its seats (chair_instance -1: a
  // sofa's place).
  void AddTable(const Eigen::Matrix4d& world_from_table, const Eigen::AlignedBox3f& table_bounds_m,
                SeatArrangement seats, int table_instance);
  void AddSeat(int table, int seat, int chair_instance, const Eigen::Matrix4f& world_from_seat);
  // Adds a seated person (instances for every posture they will take) and returns its index.
  // person_id < 0: a new person; else that person (same appearance) on another seat.
  size_t AddSeatedPerson(int table, int seat, const std::string& posture, double arrive_s, double leave_s,
                         int person_id = -1);
  // The scene's people standing still (chatting by a wall); returns their obstacles.
  std::vector<Obstacle2D> AddStandingPeople(const Scene& scene);

  // Plans what depends on the robot's run: seat turnover at each lap boundary (people leave,
  // arrive, change seats; events recorded) and the walkers' bouts in the free space the
  // obstacles leave (InputError naming /route/waypoints_m if a walker cannot follow the route,
  // /room/doors/N if furniture stands in a doorway).
  void Plan(const std::vector<RobotSample>& samples, const std::vector<Obstacle2D>& obstacles);

  // Moves people (posture, breathing, sway, walking) and warms and cools seats, to time t.
  void SetTime(double time_s);

  const std::vector<Person>& people() const { return people_; }
  // Every seat (occupied or not) as placed: its frame (x: the way a sitter faces) and whether it
  // is a chair (else a place on a sofa).
  struct SeatPlace {
    int table = 0, seat = 0;
    Eigen::Matrix4f world_from_seat = Eigen::Matrix4f::Identity();
    bool chair = true;
  };
  std::vector<SeatPlace> SeatPlaces() const;
  const std::vector<DatasetEvent>& events() const { return events_; }
  // What Plan could not give the scene (walkers with no room to walk), one sentence each.
  const std::vector<std::string>& warnings() const { return warnings_; }
  const Skeleton& skeleton() const { return *skeleton_; }

 private:
  struct Seat {
    int table = 0, seat = 0;
    int chair_instance = -1;
    Eigen::Matrix4f world_from_seat = Eigen::Matrix4f::Identity();
    std::vector<InstanceMaterial> chair_materials;  // at room temperature
  };

  // Adds a person standing (walker or standing still) with varied size and temperatures.
  Person& AddStandingPerson(const std::string& kind, Rng* rng);
  // Places the body parts of a person (hidden until SetTime) with their temperatures.
  std::array<int, Skeleton::kPartCount> AddBody(int person_id, const std::string& name, double skin_c,
                                                double clothing_c, double hair_c);
  void SetPersonTemperatures(int instance, const Asset& body, double skin_c, double clothing_c, double hair_c);
  // Keeps a seated person out of their table's top: arms are lifted onto it, the trunk leans
  // less where it would meet the edge (the chairs stand irregularly, so fixed poses cannot).
  void KeepClearOfTable(const Person& p, BodyPose* pose) const;
  // Keeps a seated person's elbows and wrists within their own half of the gap to the seat
  // beside them on each side (so neighbours' arms never meet), and gestures with the hand on the
  // roomier side.
  void KeepOwnElbowRoom(const Person& p, BodyPose* pose) const;
  // The pose (person frame) and world_from_person of a present person at time t.
  BodyPose PoseOf(const Person& p, double time_s, Eigen::Matrix4d* world_from_person) const;
  // PoseOf with the current activity overlaid and the table and neighbours kept clear: the pose
  // SetTime shows; also the cup's pose (seat frame) and the activity's name ("" for none).
  BodyPose PoseAt(const Person& p, double time_s, Eigen::Matrix4d* world_from_person, Eigen::Matrix4d* seat_from_cup,
                  std::string* activity) const;
  // The steps of Plan: seat turnover at each lap boundary; each seated body's elbow room and the
  // scene's cap on body size between seats; glances at table neighbours; the walkers' bouts (and
  // a warning for walkers with little time in the room).
  void PlanTurnover(const std::vector<RobotSample>& samples);
  void FitSeatedBodies();
  void AimGlances();
  void PlanWalkers(const std::vector<RobotSample>& samples, const std::vector<Obstacle2D>& obstacles);
  // The free space of walker `walker`; InputError when a door or the route leaves it no room.
  std::shared_ptr<const FreeSpace> WalkerSpace(const std::vector<RobotSample>& samples,
                                               const std::vector<Obstacle2D>& obstacles, double radius_m) const;
  void WarnIdleWalkers();
  // The id a new person gets: one past the largest so far (0 for the first).
  int NextPersonId() const;
  // Contact heat (crowd_contacts.cpp): prints planned from the seats, postures and activities
  // of the plan, cups' pouring and laptops' opening times; applied to the instances at time t.
  void PlanContactHeat();
  // The steps of PlanContactHeat: a person's postures on their seat with the times they hold them
  // (the arms lifted or put down halfway through a blend); the body resting in a posture a moment
  // after it was taken (`still`: the person without activities); an instance's print field (made
  // on first use); the prints of seat and backrest, of forearms on the table top and of typing
  // hands on the laptop; a person's cup and laptop warming and cooling, and the hand on the cup's
  // handle (first_s: when the person first sat down).
  using PostureSpans = std::vector<std::pair<ContactInterval, std::string>>;
  PostureSpans PostureSpansOf(const Person& p) const;
  BodyPose RestPose(const Person& still, const ContactInterval& c) const;
  PrintField& PrintsOn(int instance);
  void PlanSeatPrints(const Person& p, const Person& still, const PostureSpans& postures);
  void PlanTablePrints(const Person& p, const Person& still, const PostureSpans& postures);
  void PlanKeyboardPrints(const Person& p);
  void PlanProps(const Person& p);
  void PlanCupHeat(const Person& p, double first_s, double drink_age_s);
  // Whether a seated person's forearm rests on their table top, by its wrist (seat frame).
  static bool ForearmOnTable(const Person& p, const Eigen::Vector3d& wrist);
  void UpdateContactHeat(double time_s);
  struct PropHeat {
    int instance = -1;
    bool cup = false;
    double from_s = 0, to_s = 0;  // cup: poured at from_s; laptop: open from from_s to to_s
    std::vector<InstanceMaterial>
        steady;  // the asset's materials (a laptop in use, a cup as poured at the asset's drink temperature)
  };
  // crowd_clothing.cpp: draws a person's garments and gives their parts' materials the garment
  // and skin fields (crowd.garments); sets their garments' temperatures at a time.
  void Dress(Person* person);
  void UpdateClothing(const Person& person, double time_s);

  AssetLibrary& assets_;
  CrowdStage& stage_;
  std::unique_ptr<Skeleton> skeleton_;
  std::vector<Eigen::Matrix4d> world_from_table_;    // per table
  std::vector<int> table_instance_;                  // per table: its instance
  std::vector<Eigen::AlignedBox3f> table_bounds_m_;  // per table: its asset's bounds (top at max z)
  std::vector<SeatArrangement> table_seats_;         // per table: how it seats people
  std::vector<Person> people_;
  std::vector<Seat> seats_;
  RobotTrack robot_;  // the robot's run (Plan)
  std::vector<DatasetEvent> events_;
  std::vector<std::string> warnings_;
  std::vector<WalkerPlan> walker_plans_;
  std::vector<Doorway> doors_;  // the room's doors (walkers come and go by them)
  uint64_t seed_ = 1;
  double frame_rate_hz_ = 25, duration_s_ = 80;
  CrowdOptions options_;
  double seat_warmth_c_ = 2;
  double room_c_ = 22;                                 // the room's air, °C: what cups and laptops cool toward
  std::map<int, std::unique_ptr<PrintField>> prints_;  // contact prints by instance
  std::vector<PropHeat> prop_heat_;
  double sway_amplitude_rad_ = 0;
  std::string scene_file_;                             // named in errors found by Plan
  ThermalEnvironment thermal_environment_;             // the room as the garments' heat balance sees it
  std::vector<std::unique_ptr<SurfaceField>> fields_;  // garment and skin fields the materials point to
};

// An open box in a table's frame, m: the table top slab a seated person's parts keep out of.
struct TableSlab {
  double x_min, x_max, y_min, y_max, z_min, z_max;
};

// How deep `part`'s mesh, moved by table_from_part, reaches into `slab` from above: the largest
// z_max - z over the moved vertices strictly inside it, 0 when none is. A part whose moved
// bounding box is clear of the slab gets 0 without its vertices being moved.
double DepthIntoSlab(const Asset& part, const Eigen::Matrix4d& table_from_part, const TableSlab& slab);

}  // namespace hoilcd
