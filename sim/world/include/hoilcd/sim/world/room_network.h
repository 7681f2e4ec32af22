// The thermal solution of a world's static surfaces (docs/models/thermal_solution.md): walls,
// floor, ceiling and windows cut into patches of about room.thermal.patch_size_m, each material of
// each table, chair and object a node, with their view factors cast once against the static
// geometry alone, solved as a ThermalNetwork under the room's stratified air, the thermostat's
// cycle, the outdoor air through the envelope, the people who sit or stand still and the sun
// through the windows. The renderer reads each node's temperature, the band radiance it receives
// from its surroundings (what a diffuse surface reflects) and its sunlit share.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "hoilcd/sim/assets/instance.h"
#include "hoilcd/sim/scene/room_options.h"
#include "hoilcd/sim/sensor/radiometry.h"
#include "hoilcd/sim/world/room_thermal.h"
#include "hoilcd/sim/world/thermal_network.h"

namespace hoilcd {

// A planar rectangle of the room's mesh (corners in order), its material and the normal of the
// side that faces the room's air.
struct RoomQuad {
  std::array<Eigen::Vector3f, 4> corners;
  int material = 0;
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();
};

// The material temperature every asset declares for a part with no heat of its own ("room
// temperature", docs/models/room_objects.md): such parts are solved; others are held at theirs.
constexpr double kDeclaredRoomTemperatureC = 22.0;

// A person as the network sees them: a sphere of their radiating area at their clothing's
// surface temperature, in the room over [arrive_s, leave_s) (present all along before t = 0 when
// there at t = 0). The network does not hold people as nodes; each warms what faces them.
struct PersonSource {
  Eigen::Vector3f centre_m = Eigen::Vector3f::Zero();
  double radius_m = 0.32;
  double surface_c = 28;
  double emissivity = 0.95;
  double arrive_s = 0, leave_s = 1e30;
};

class RoomNetwork {
 public:
  // quads: the room mesh's rectangles (triangles 2q and 2q + 1 are quad q); instances: the world's
  // instances, of which those of role table, chair and object are nodes; room_instance: the
  // room's. The view factors are cast, and the spin-up to t = 0 solved, at the first SetTime: a
  // world that is only looked at (the generator's checks) never pays for them.
  RoomNetwork(const RoomOptions& room, const ThermalSolutionOptions& options, uint64_t seed, const RoomClimate& climate,
              const std::vector<RoomQuad>& quads, const std::vector<InstanceInfo>& instances, int room_instance,
              const std::array<bool, 4>& exterior_walls, const BandRadianceTable& table, int threads);
  ~RoomNetwork();

  // The people whose radiation the surfaces receive (none until set); the solution starts again.
  void SetPeople(const std::vector<PersonSource>& people);
  // Moves the solution to time t (stepping on from the last grid state when t lies beyond it;
  // the spin-up is solved at the first call).
  void SetTime(double time_s);

  // At the last SetTime: the temperature of the room's surface of `material` at world point p,
  // bilinear between patch centres (NaN when p lies on no patch of that material), °C.
  float RoomTemperatureC(int material, const Eigen::Vector3f& p) const;
  // At the last SetTime, at a world point on a patch of a room material, each bilinear between
  // patch centres.
  struct PatchState {
    float temperature_c = 0;  // °C
    float incident = 0;       // band radiance received from the surroundings, W·m⁻²·sr⁻¹
    float sun_share = 0;      // the patches' sunlit share times the sun's cosine on them
  };
  // False when p lies on no patch of that material.
  bool RoomSurfaceAt(int material, const Eigen::Vector3f& p, PatchState* state) const;
  // The area-weighted mean temperature of a room material, °C.
  float RoomMeanTemperatureC(int material) const;
  // The area-weighted mean band radiance a room material receives, W·m⁻²·sr⁻¹.
  float RoomMeanIncidentRadiance(int material) const;
  // The solved temperature of an instance's material, or NaN when it is no node (people, props,
  // parts held at their declared temperature).
  float InstanceTemperatureC(int instance, int material) const;
  // Band radiance arriving at an instance material (room materials: their area-weighted mean),
  // W·m⁻²·sr⁻¹; NaN when it is no node.
  float IncidentRadiance(int instance, int material) const;
  // The area-weighted mean of every node's incident band radiance.
  float MeanIncidentRadiance() const { return mean_incident_; }

  int num_nodes() const { return static_cast<int>(nodes_.size()); }
  // Each node's sunlit share times the sun's cosine on it at the last SetTime (empty when the sun
  // cannot enter: off, or no window).
  const std::vector<float>& sun_shares() const { return sun_share_; }
  // The solved network; after the first SetTime.
  const ThermalNetwork& network() const { return *network_; }

 private:
  struct Patches;  // a room quad's grid of patches
  int NodeOfHit(const RayHit& hit, const Eigen::Vector3f& point) const;
  int NodeOf(int instance, int material) const;  // -1: no node
  // Casts the view factors and makes the network, the first time it is called.
  void CastViewFactorsOnce();
  // The band radiance each node receives at grid state k (solved once, kept while frames need it).
  const std::vector<float>& IncidentOfState(size_t k);
  // What the people present at t send each node, W (the drivers' absorbed heat).
  void PeopleHeat(double time_s, std::vector<double>* absorbed_w) const;
  // What the sun through the windows gives each node at t, W (the drivers' absorbed heat).
  void SolarHeat(double time_s, std::vector<double>* absorbed_w);
  // Each node's sunlit share times the sun's cosine on it at t, linear between the sun's grid
  // times (every kSunStepS; each cast once, kept while the solution needs it); empty without sun.
  std::vector<float> SunShares(double time_s);
  const std::vector<float>& SunSharesOfKey(int64_t key);
  // Whether the ray from p (on a surface facing along n) towards the sun leaves through a window's
  // glass, clear of its frame, missing every wall and fixture.
  bool SunlitThroughWindow(const Eigen::Vector3f& p, const Eigen::Vector3f& n, const Eigen::Vector3f& sun) const;

  const BandRadianceTable& table_;
  double room_height_m_;
  std::vector<RoomQuad> quads_;
  std::vector<Patches> patches_;                     // per quad
  std::vector<std::vector<int>> quads_of_material_;  // room material -> quads
  std::vector<std::vector<int>> node_of_material_;   // instance -> material -> node (-1: none)
  std::vector<const TriangleMesh*> mesh_of_;         // instance -> its mesh (fixtures only)
  std::vector<float> node_area_;
  std::vector<ThermalNode> nodes_;
  std::vector<int> world_instance_of_;  // caster instance -> world instance
  int threads_ = 1;
  std::unique_ptr<ThermalNetwork> network_;              // from CastViewFactorsOnce
  std::unique_ptr<RayCaster> caster_;                    // the static geometry: room and fixtures
  std::vector<std::vector<ThermalTriangle>> triangles_;  // per node
  // Per person, the nodes they warm: (node, A_i·F_i→person·ε_i·ε_person), m².
  std::vector<std::vector<std::pair<int, double>>> person_coupling_;
  std::vector<PersonSource> people_;
  ThermalSolutionOptions options_;
  uint64_t seed_ = 0;
  bool started_ = false;
  ThermalDrivers drivers_;
  double solved_until_s_ = 0;
  std::vector<double> temperature_c_;                       // per node, at the last SetTime
  std::vector<float> incident_;                             // per node, at the last SetTime
  std::map<size_t, std::vector<float>> incident_of_state_;  // per grid state, as asked
  std::vector<float> room_mean_c_, room_incident_;          // per room material
  SunOptions sun_;
  bool sun_can_enter_ = false;                               // the sun is on and the room has windows
  double frame_width_m_ = 0;                                 // of each window's frame (0: none)
  int window_count_ = 0;                                     // room materials 3 .. 3 + window_count_ − 1
  std::vector<float> solar_absorptance_;                     // per node
  std::map<int64_t, std::vector<float>> sun_shares_of_key_;  // per sun grid time, as asked
  std::vector<float> sun_share_;                             // per node, at the last SetTime
  float mean_incident_ = 0;
  int room_instance_ = -1;
};

}  // namespace hoilcd
