// The world as the renderer sees it: the room, furniture and objects of a Scene as Embree
// instances with per-instance thermal materials and class ids, the crowd (crowd.h) placed among
// them, and the 2-D obstacles the robot must avoid.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/sim/assets/asset.h"
#include "hoilcd/sim/assets/instance.h"
#include "hoilcd/sim/robot/robot.h"
#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/sensor/radiometry.h"
#include "hoilcd/sim/world/crowd.h"
#include "hoilcd/sim/world/ray_caster.h"
#include "hoilcd/sim/world/room_network.h"
#include "hoilcd/sim/world/room_thermal.h"

namespace hoilcd {

class World : private CrowdStage {
 public:
  // `threads` share the room's thermal solution (its view factors and time steps); the world is
  // the same at any count.
  World(const Scene& scene, const BandRadianceTable& table, int threads = 1);

  // Plans what depends on the robot's run: seat turnover at each lap boundary (people leave,
  // arrive, change seats; events recorded) and the walkers' bouts around the robot. Call once,
  // before SetTime, with the run's per-frame samples. Throws InputError naming /route/waypoints_m
  // when walkers are asked for but a walker's body cannot follow the route clear of furniture.
  // With the room's thermal solution, the seated people then warm what faces them.
  void PlanCrowd(const std::vector<RobotSample>& samples);

  // Moves people (posture, breathing, sway, walking), warms and cools seats, to time t, and
  // recommits the ray caster.
  void SetTime(double time_s);

  // arrive / leave / swap events of PlanCrowd, in frame order.
  const std::vector<DatasetEvent>& events() const { return crowd_->events(); }
  // What PlanCrowd could not give the scene (Crowd::warnings).
  const std::vector<std::string>& warnings() const { return crowd_->warnings(); }

  const RayCaster& caster() const { return *caster_; }
  const InstanceInfo& instance(int id) const { return instances_[id]; }
  int num_instances() const { return static_cast<int>(instances_.size()); }
  const std::map<std::string, int>& classes() const { return classes_; }
  // Everyone who appears in the sequence; `present` says who is in the room at the current time.
  const std::vector<Person>& people() const { return crowd_->people(); }
  const std::vector<Obstacle2D>& obstacles() const { return obstacles_; }
  std::vector<Crowd::SeatPlace> seat_places() const { return crowd_->SeatPlaces(); }
  const Skeleton& skeleton() const { return crowd_->skeleton(); }
  double room_height_m() const { return room_size_m_.z(); }
  // Band radiance of the room's surroundings, for diffuse reflection (L_env), at the current time
  // (it follows the surfaces through the HVAC cycle).
  float environment_radiance() const { return environment_radiance_; }
  // The room's air temperature at time t (the thermostat's cycle, room_thermal.h), C.
  double AirTemperatureC(double time_s) const { return room_surfaces_->climate().AirTemperatureC(time_s); }
  const RoomSurfaces& room_surfaces() const { return *room_surfaces_; }
  // The thermal solution of the static surfaces (room.thermal.enabled), else null.
  const RoomNetwork* room_network() const { return room_network_.get(); }
  int room_instance() const { return room_instance_; }
  const BandRadianceTable& radiance_table() const { return table_; }

 private:
  int ClassId(const std::string& name);
  // CrowdStage: the crowd's people and props are instances like any other.
  int Place(const Asset& asset, const Eigen::Matrix4f& world_from_object, InstanceRole role, std::string name,
            double temperature_offset_c) override;
  InstanceInfo& MutableInstance(int id) override { return instances_[id]; }
  void Move(int instance, const Eigen::Matrix4f& world_from_object) override;
  void Finish(InstanceMaterial* m) const override;
  void BuildRoom(const Scene& scene);
  // The room mesh's rectangles, each with the normal of its side that faces the room's air.
  std::vector<RoomQuad> RoomQuads(const Scene& scene) const;
  // Sets the fixtures' solved temperatures and every node's reflected surroundings.
  void ApplyRoomNetwork();
  // SetTime; without `solve`, the room's thermal solution is left as it is.
  void MoveTo(double time_s, bool solve);
  void BuildFurnitureAndPeople(const Scene& scene);

  const BandRadianceTable& table_;
  AssetLibrary assets_;
  std::unique_ptr<RayCaster> caster_;
  std::unique_ptr<Crowd> crowd_;
  std::map<const Asset*, int> prototype_of_asset_;
  std::vector<InstanceInfo> instances_;
  TriangleMesh room_mesh_;
  int room_instance_ = -1;
  std::unique_ptr<RoomSurfaces> room_surfaces_;
  std::unique_ptr<RoomNetwork> room_network_;
  std::map<std::string, int> classes_;
  std::vector<Obstacle2D> obstacles_;
  Eigen::Vector3d room_size_m_;
  float environment_radiance_ = 0;
};

}  // namespace hoilcd
