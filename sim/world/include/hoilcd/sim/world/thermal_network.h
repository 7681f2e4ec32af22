// The room's static surfaces as a lumped thermal network (docs/models/thermal_solution.md): each
// node (a patch of wall, floor or ceiling; a material of a piece of furniture) has an area, an
// emissivity, a heat capacity, convection with the air at its height, conduction to outdoors and
// heat of its own, and exchanges long-wave radiation with every node it sees through view
// factors cast once with Embree. The network is stepped with implicit Euler on a fixed time grid
// from a spin-up before t = 0, so the state at any time depends on the scene alone, never on
// which frames are rendered, in which order or on how many threads.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "hoilcd/core/util/random.h"
#include "hoilcd/sim/world/ray_caster.h"

namespace hoilcd {

// σ, W/(m²·K⁴).
constexpr double kStefanBoltzmann = 5.670374419e-8;

struct ThermalNode {
  double area_m2 = 0;
  double emissivity = 0.9;             // total hemispherical, for the long-wave exchange
  double convection_w_m2k = 2.5;       // h_c to the air at height_m
  double heat_capacity_j_k = 0;        // C of the node (0: it follows its balance at once)
  double height_m = 0;                 // where it meets the air (its centre)
  double outdoor_conductance_w_k = 0;  // from its surface through the envelope to outdoor air
  double power_w = 0;                  // heat released inside it
  bool fixed = false;                  // held at fixed_temperature_c (a boundary: radiator water)
  double fixed_temperature_c = 22;
};

// One triangle of a node's surface, world frame, with the normal of the side that faces the room.
struct ThermalTriangle {
  std::array<Eigen::Vector3f, 3> corners;
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();
};

// A point drawn uniformly on a triangle from two keyed draws (√u1 and u2, in that order).
Eigen::Vector3f UniformPointOn(const ThermalTriangle& t, Rng* rng);

// Points drawn uniformly by area over one node's triangles: a triangle by its share of the area
// (one draw), then a point on it (two draws). The view factors and the sun's lit shares sample a
// node with it.
class AreaSampler {
 public:
  explicit AreaSampler(const std::vector<ThermalTriangle>& triangles);
  // The triangle the next point lies on, and the point.
  const ThermalTriangle& Draw(Rng* rng, Eigen::Vector3f* point) const;

 private:
  const std::vector<ThermalTriangle>& triangles_;
  std::vector<double> cumulative_;
  double total_ = 0;
};

// F_ij, the share of what node i emits that first lands on node j: sparse rows, each summing to
// 1 (what escapes to no node is given to `open_share`, radiation to the air's temperature).
struct ViewFactors {
  std::vector<std::vector<std::pair<int, float>>> rows;
  std::vector<float> open_share;
};

// Casts `rays_per_node` cosine-weighted rays from area-sampled points of each node's triangles
// against `caster`; node_of_hit maps a hit (and its world point) to the node it lands on, or -1.
// Rows are made reciprocal (A_i F_ij = A_j F_ji) and then rescaled to sum to 1. Keyed by `seed`
// and the node, so the result does not depend on `threads`.
ViewFactors CastViewFactors(const RayCaster& caster, const std::vector<std::vector<ThermalTriangle>>& node_triangles,
                            const std::vector<double>& areas_m2,
                            const std::function<int(const RayHit&, const Eigen::Vector3f&)>& node_of_hit,
                            int rays_per_node, uint64_t seed, int threads);

// What drives the network at time t: the air at a height, the outdoor air, and heat absorbed per
// node (people, sun), W.
struct ThermalDrivers {
  std::function<double(double time_s, double height_m)> air_c;
  double outdoor_c = 5;
  std::function<void(double time_s, std::vector<double>* absorbed_w)> absorbed;  // may be empty
};

class ThermalNetwork {
 public:
  // Radiation is exact (σT⁴): each sweep of a step linearises a node's own emission about its
  // current value, a Newton step. Each sweep's nodes are shared among `threads`; every node is
  // computed from the last sweep's values alone, so the result does not depend on `threads`.
  ThermalNetwork(std::vector<ThermalNode> nodes, const ViewFactors& view_factors, int threads = 1);

  // Steps from t0 − spin_up_s (starting from the steady state of the drivers at that time) to t0
  // on the grid t0 + k·step_s, keeping the state at t0; AdvanceTo then steps on. The drivers are
  // kept (and what they refer to must outlive the network's use).
  void Start(ThermalDrivers drivers, double t0_s, double step_s, double spin_up_s);
  // Steps on until the grid covers time t (nothing when it does).
  void AdvanceTo(double time_s);
  // Start, then AdvanceTo(t1).
  void Solve(ThermalDrivers drivers, double t0_s, double t1_s, double step_s, double spin_up_s);
  // Node temperatures at time t, linear between grid states (clamped to the grid), °C.
  void TemperaturesAt(double time_s, std::vector<double>* temperatures_c) const;
  // Where time t lies on the grid: state k and the weight of state k + 1 (clamped to the grid).
  void GridPlace(double time_s, size_t* k, double* weight) const;
  size_t grid_size() const { return grid_c_.size(); }
  const std::vector<double>& GridState(size_t k) const { return grid_c_[k]; }
  double GridTime(size_t k) const { return t0_s_ + static_cast<double>(k) * step_s_; }
  // Steady state of the drivers at time t (no history), °C.
  std::vector<double> SteadyState(const ThermalDrivers& drivers, double time_s) const;
  // The radiance arriving at each node, averaged over its hemisphere by cosine (E_in/π), when
  // node j leaves emitted_j + reflectivity_j·(its own incident radiance) and the open share sees
  // `open` (any unit of radiance; the renderer uses the camera's band): the diffuse reflection's
  // source, solved by Jacobi sweeps (each reflection is a factor 1 − ε smaller).
  std::vector<float> IncidentRadiance(const std::vector<float>& emitted, const std::vector<float>& reflectivity,
                                      float open) const;

  int size() const { return static_cast<int>(nodes_.size()); }
  const ThermalNode& node(int i) const { return nodes_[static_cast<size_t>(i)]; }

 private:
  // One implicit step (capacity_over_dt: C/Δt per node, all zero for a steady state) from `prev`,
  // iterating the balance with the radiosities until the largest change is under 1e-4 K;
  // irradiance: each node's H, W/m², the last step's on entry (empty: start from σT⁴).
  void Step(const ThermalDrivers& drivers, double time_s, double step_s, const std::vector<double>& prev_c,
            std::vector<double>* next_c, std::vector<double>* irradiance) const;

  // Σ_k F_ik·value_k + open_share_i·open over node i's row.
  double Gather(size_t i, const std::vector<double>& value, double open) const;

  std::vector<ThermalNode> nodes_;
  // The view factors' rows, one after another (row i is [row_begin_[i], row_begin_[i + 1])):
  // a sweep reads them in order instead of chasing a vector per row.
  std::vector<size_t> row_begin_;
  std::vector<int> column_;
  std::vector<float> factor_;
  std::vector<float> open_share_;
  int threads_ = 1;
  ThermalDrivers drivers_;
  double t0_s_ = 0, step_s_ = 1;
  std::vector<std::vector<double>> grid_c_;  // per grid time, per node
  std::vector<double> irradiance_;           // H of the last step, W/m²: where the next starts
};

}  // namespace hoilcd
