// The room's surfaces over time (docs/models/room_surfaces.md): the air's thermostat cycle and the
// surfaces' lagged response (RoomClimate), the sun's position, and the temperature fields of the
// walls, ceiling, floor and windows (RoomSurfaces): cooler edges of outside walls, a warm plume
// above each radiator, cold glass and its frame, sun patches and a small texture. Every value is a
// closed-form function of (scene, seed, time), so frames come out the same at any thread count.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "hoilcd/sim/assets/instance.h"
#include "hoilcd/sim/scene/room_options.h"

namespace hoilcd {

class RoomNetwork;

// R_si, m²·K/W: the inside surface resistance of ISO 6946 / ISO 13788 (horizontal heat flow).
constexpr double kInsideSurfaceResistance = 0.13;

// Inside surface temperature of an element with U-value u between inside air t_in and outdoors
// t_out: T_si = T_i − U·R_si·(T_i − T_e).
double InsideSurfaceTemperatureC(double u_value_w_m2k, double t_in_c, double t_out_c);

// The sun seen from the room's latitude: elevation above the horizon and azimuth clockwise from
// true north, rad (Cooper's declination, the hour angle of local solar time).
struct SunPosition {
  double elevation_rad = 0;
  double azimuth_rad = 0;
};
SunPosition SolarPosition(double latitude_deg, int day_of_year, double solar_hour);
// Clear-sky direct normal irradiance, W/m² (Meinel and Meinel with Kasten–Young air mass); 0 at night.
double ClearSkyDirectNormalWm2(double elevation_rad);

// The sun as the room sees it at time t of the sequence (room.sun; its clock starts at
// time_of_day_h): the unit vector towards it in the room's frame and the direct irradiance the
// glazing transmits, W/m² normal to the beam (0 at night or with the sun off).
struct SunInRoom {
  Eigen::Vector3f direction = Eigen::Vector3f::UnitZ();
  float irradiance_wm2 = 0;
};
SunInRoom SunAt(const SunOptions& sun, double time_s);

// The air's thermostat cycle and how the surfaces follow it. Anyone may build one from the scene
// (it holds no state but the scene's): the garments' model asks it for the air at time t.
class RoomClimate {
 public:
  // clock_offset_s: how long the cycle has run before t = 0 beyond its keyed phase (a recording
  // run's start after the first run's: the thermostat ran on in between).
  RoomClimate(const RoomOptions& room, uint64_t seed, double clock_offset_s = 0);
  // Air temperature at time t: environment_temperature_c plus the thermostat's triangle cycle
  // (rising for heating_fraction of each period through the deadband, then falling), a phase
  // keyed by the seed. Without hvac: environment_temperature_c.
  double AirTemperatureC(double time_s) const;
  // The cycle's part of the air temperature (AirTemperatureC minus its mean), K.
  double AirOffsetK(double time_s) const;
  // The first-order lag of AirOffsetK with surface_lag_s, in its periodic steady state (closed
  // form, piecewise exponential), K: what walls, floor, ceiling and the room's reflections add.
  double SurfaceOffsetK(double time_s) const;

 private:
  double CycleTimeS(double time_s) const;  // time into the thermostat's cycle, [0, period_s)
  HvacOptions hvac_;
  double mean_c_;
  double phase_s_;      // time into the cycle at t = 0
  double lag_start_k_;  // SurfaceOffsetK at the start of a heating phase
};

// World-frame boxes of the instances of class `radiator_class` (the radiators a scene placed).
std::vector<Eigen::AlignedBox3f> RadiatorBoxes(const std::vector<InstanceInfo>& instances, int radiator_class);

// The fields of the room's materials (0 floor, 1 ceiling, 2 walls, 3 + i window i, then the
// interior walls of a building floor when there are any) and their base temperatures at time t.
// Radiators are given as world-frame boxes (those of the scene's objects whose class is
// "radiator"); interior walls as their footprints: they are inside walls (no thermal bridges, no
// sun of their own; texture only) and they shade the sun from what lies behind them.
class RoomSurfaces {
 public:
  RoomSurfaces(const RoomOptions& room, uint64_t seed, const std::vector<Eigen::AlignedBox3f>& radiators,
               const std::vector<Eigen::AlignedBox2f>& interior_walls = {}, double clock_offset_s = 0);
  ~RoomSurfaces();

  // The field of room material k, or null when none of its effects is on (the uniform fast path).
  const SurfaceField* FieldOf(int material) const;
  // Moves the climate and the sun to time t and sets each room material's base temperatures
  // (its scene values plus the surfaces' HVAC offset; glass from its U-value). The caller then
  // recomputes the materials' radiances. Call between frames only: fields read this state.
  void SetTime(double time_s, std::vector<InstanceMaterial>* materials);
  // The temperature the room's diffuse surfaces reflect at t (the environment's plus the
  // surfaces' HVAC offset), C.
  double EnvironmentTemperatureC(double time_s) const;
  // Field offset of material k at world point p at the last SetTime, K (0 without a field).
  float OffsetK(int material, const Eigen::Vector3f& p) const { return Sample(material, p).offset_k; }
  // The same, with what the solution's patch at p receives about the material's mean (what its
  // environment_radiance holds), W·m⁻²·sr⁻¹ (0 without the solution).
  FieldSample Sample(int material, const Eigen::Vector3f& p) const;

  const RoomClimate& climate() const { return climate_; }
  // Which walls face outdoors: south, north, west, east.
  const std::array<bool, 4>& exterior_walls() const { return exterior_; }
  // With the room's thermal solution, the materials' temperatures are its patches' (SetTime
  // moves them only after the network's SetTime): it replaces the walls' gradient, the HVAC lag
  // and the glass's closed form; bridges, plumes, sun patches, frames and texture stay on top.
  // Not owned; it must outlive this.
  void AttachNetwork(const RoomNetwork* network);

 private:
  class Field;
  struct Radiator {
    int wall;          // 0 south (y = 0), 1 north, 2 west (x = 0), 3 east
    float lo_m, hi_m;  // extent along the wall
    float top_m, bottom_m;
  };
  int WallAt(const Eigen::Vector3f& p) const;
  float BridgeK(int material, const Eigen::Vector3f& p) const;
  float PlumeK(const Eigen::Vector3f& p) const;
  float SunK(int material, const Eigen::Vector3f& p) const;
  float FrameK(int window, const Eigen::Vector3f& p) const;
  float TextureK(int material, const Eigen::Vector3f& p) const;

  RoomOptions room_;
  uint64_t seed_;
  const RoomNetwork* network_ = nullptr;
  RoomClimate climate_;
  Eigen::Vector3f size_m_;
  std::array<bool, 4> exterior_{};  // south, north, west, east
  std::vector<Radiator> radiators_;
  std::vector<Eigen::AlignedBox2f> interior_walls_;
  int interior_material_ = -1;                  // -1: no interior walls
  std::vector<std::unique_ptr<Field>> fields_;  // per material, null where none
  // State at the last SetTime.
  float bridge_k_ = 0;                                       // edge cooling at an edge, K
  std::vector<float> frame_minus_glass_k_;                   // per window
  Eigen::Vector3f sun_direction_ = Eigen::Vector3f::Zero();  // towards the sun, room frame
  float sun_irradiance_wm2_ = 0;                             // transmitted direct normal irradiance, W/m²
};

}  // namespace hoilcd
