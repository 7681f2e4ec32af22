#include "hoilcd/sim/world/thermal_network.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

constexpr double kKelvin = 273.15;
// Far below what a camera resolves (its NETD is tens of mK; radiometric frames hold 0.01 K).
constexpr double kToleranceK = 1e-4;
constexpr int kMaxSweeps = 20000;
// Nodes per chunk of a parallel sweep: a few hundred microseconds of work.
constexpr int64_t kNodesPerChunk = 512;

// A unit vector about `n`, cosine-weighted (Malley's method), from two uniforms.
Eigen::Vector3f CosineDirection(const Eigen::Vector3f& n, double u1, double u2) {
  const Eigen::Vector3f helper = std::abs(n.x()) < 0.9f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY();
  const Eigen::Vector3f t = n.cross(helper).normalized();
  const Eigen::Vector3f b = n.cross(t);
  const double r = std::sqrt(u1), phi = 2 * M_PI * u2;
  const auto x = static_cast<float>(r * std::cos(phi)), y = static_cast<float>(r * std::sin(phi));
  const auto z = static_cast<float>(std::sqrt(std::max(0.0, 1 - u1)));
  return (x * t + y * b + z * n).normalized();
}

}  // namespace

Eigen::Vector3f UniformPointOn(const ThermalTriangle& t, Rng* rng) {
  const double r1 = std::sqrt(rng->Uniform()), r2 = rng->Uniform();
  return static_cast<float>(1 - r1) * t.corners[0] + static_cast<float>(r1 * (1 - r2)) * t.corners[1] +
         static_cast<float>(r1 * r2) * t.corners[2];
}

AreaSampler::AreaSampler(const std::vector<ThermalTriangle>& triangles) : triangles_(triangles) {
  for (const ThermalTriangle& t : triangles) {
    total_ += 0.5 * (t.corners[1] - t.corners[0]).cross(t.corners[2] - t.corners[0]).norm();
    cumulative_.push_back(total_);
  }
}

const ThermalTriangle& AreaSampler::Draw(Rng* rng, Eigen::Vector3f* point) const {
  const double pick = rng->Uniform() * total_;
  const size_t which = std::min(
      static_cast<size_t>(std::lower_bound(cumulative_.begin(), cumulative_.end(), pick) - cumulative_.begin()),
      triangles_.size() - 1);
  const ThermalTriangle& t = triangles_[which];
  *point = UniformPointOn(t, rng);
  return t;
}

ViewFactors CastViewFactors(const RayCaster& caster, const std::vector<std::vector<ThermalTriangle>>& node_triangles,
                            const std::vector<double>& areas_m2,
                            const std::function<int(const RayHit&, const Eigen::Vector3f&)>& node_of_hit,
                            int rays_per_node, uint64_t seed, int threads) {
  HOILCD_CHECK_MSG(node_triangles.size() == areas_m2.size(), "one area per node");
  HOILCD_CHECK_MSG(rays_per_node > 0, "rays_per_node must be positive");
  const int n = static_cast<int>(node_triangles.size());
  std::vector<std::vector<std::pair<int, float>>> hits(static_cast<size_t>(n));
  std::vector<float> open(static_cast<size_t>(n), 0.0f);
  ParallelForChunks(n, 16, threads, [&](int64_t begin, int64_t end, int /*worker*/) {
    std::vector<int> counts;
    Eigen::Vector3f origins[kRayPacketSize], directions[kRayPacketSize];
    RayHitPacket packet;
    for (int64_t i = begin; i < end; ++i) {
      const std::vector<ThermalTriangle>& triangles = node_triangles[static_cast<size_t>(i)];
      if (triangles.empty()) continue;
      const AreaSampler sampler(triangles);
      counts.assign(static_cast<size_t>(n), 0);
      int missed = 0;
      Rng rng = KeyedRng(seed, "thermal.view_factors", static_cast<uint64_t>(i));
      for (int first = 0; first < rays_per_node; first += kRayPacketSize) {
        const int count = std::min(kRayPacketSize, rays_per_node - first);
        for (int k = 0; k < count; ++k) {
          Eigen::Vector3f p;
          const ThermalTriangle& t = sampler.Draw(&rng, &p);
          origins[k] = p + 1e-4f * t.normal;
          const double u1 = rng.Uniform(), u2 = rng.Uniform();
          directions[k] = CosineDirection(t.normal, u1, u2);
        }
        caster.IntersectPacket(origins, directions, count, &packet);
        for (int k = 0; k < count; ++k) {
          RayHit hit;
          hit.instance = packet.instance[k];
          hit.triangle = packet.triangle[k];
          hit.distance_m = packet.distance_m[k];
          const int j = hit.hit() ? node_of_hit(hit, origins[k] + hit.distance_m * directions[k]) : -1;
          if (j < 0) {
            ++missed;
          } else {
            ++counts[static_cast<size_t>(j)];
          }
        }
      }
      auto& row = hits[static_cast<size_t>(i)];
      for (int j = 0; j < n; ++j) {
        if (counts[static_cast<size_t>(j)] > 0)
          row.emplace_back(j, static_cast<float>(counts[static_cast<size_t>(j)]) / rays_per_node);
      }
      open[static_cast<size_t>(i)] = static_cast<float>(missed) / rays_per_node;
    }
  });
  // Reciprocity: A_i F_ij and A_j F_ji are two estimates of one exchange area; take their mean.
  struct Entry {
    int i, j;
    double exchange_m2;
  };
  std::vector<Entry> entries;
  for (int i = 0; i < n; ++i) {
    for (const auto& [j, f] : hits[static_cast<size_t>(i)]) {
      const double g = 0.5 * areas_m2[static_cast<size_t>(i)] * f;
      entries.push_back({i, j, g});
      entries.push_back({j, i, g});
    }
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.i != b.i ? a.i < b.i : a.j < b.j; });
  ViewFactors result;
  result.rows.resize(static_cast<size_t>(n));
  result.open_share = open;
  for (size_t k = 0; k < entries.size();) {
    const int i = entries[k].i, j = entries[k].j;
    double sum = 0;
    for (; k < entries.size() && entries[k].i == i && entries[k].j == j; ++k) sum += entries[k].exchange_m2;
    result.rows[static_cast<size_t>(i)].emplace_back(j, static_cast<float>(sum / areas_m2[static_cast<size_t>(i)]));
  }
  // Each row then sums to 1 with its open share, so an isothermal enclosure exchanges nothing.
  for (int i = 0; i < n; ++i) {
    auto& row = result.rows[static_cast<size_t>(i)];
    double seen = 0;
    for (const auto& entry : row) seen += entry.second;
    const double target = 1.0 - open[static_cast<size_t>(i)];
    if (seen <= 0) continue;
    const double scale = target / seen;
    for (auto& entry : row) entry.second = static_cast<float>(entry.second * scale);
  }
  return result;
}

ThermalNetwork::ThermalNetwork(std::vector<ThermalNode> nodes, const ViewFactors& view_factors, int threads)
    : nodes_(std::move(nodes)), open_share_(view_factors.open_share), threads_(threads) {
  HOILCD_CHECK_MSG(view_factors.rows.size() == nodes_.size() && view_factors.open_share.size() == nodes_.size(),
                   "one view-factor row per node");
  row_begin_.reserve(nodes_.size() + 1);
  row_begin_.push_back(0);
  for (const auto& row : view_factors.rows) {
    for (const auto& [k, f] : row) {
      column_.push_back(k);
      factor_.push_back(f);
    }
    row_begin_.push_back(column_.size());
  }
}

double ThermalNetwork::Gather(size_t i, const std::vector<double>& value, double open) const {
  double sum = open_share_[i] * open;
  for (size_t e = row_begin_[i]; e < row_begin_[i + 1]; ++e) sum += factor_[e] * value[static_cast<size_t>(column_[e])];
  return sum;
}

void ThermalNetwork::Step(const ThermalDrivers& drivers, double time_s, double step_s,
                          const std::vector<double>& prev_c, std::vector<double>* next_c,
                          std::vector<double>* irradiance) const {
  const size_t n = nodes_.size();
  std::vector<double> absorbed(n, 0.0);
  if (drivers.absorbed) drivers.absorbed(time_s, &absorbed);
  const double outdoor_k = drivers.outdoor_c + kKelvin;
  // What each free node's balance holds apart from its radiation: T·diagonal = rhs + Aε(H − σT⁴).
  std::vector<double> rhs(n, 0.0), diagonal(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    const ThermalNode& node = nodes_[i];
    if (node.fixed) continue;
    const double capacity = step_s > 0 ? node.heat_capacity_j_k / step_s : 0.0;
    const double convection = node.convection_w_m2k * node.area_m2;
    const double air_k = drivers.air_c(time_s, node.height_m) + kKelvin;
    rhs[i] = capacity * (prev_c[i] + kKelvin) + convection * air_k + node.outdoor_conductance_w_k * outdoor_k +
             node.power_w + absorbed[i];
    diagonal[i] = capacity + convection + node.outdoor_conductance_w_k;
    HOILCD_CHECK_MSG(diagonal[i] + node.area_m2 * node.emissivity > 0,
                     "thermal node " + std::to_string(i) + " has no way to exchange heat");
  }
  // The open share sees a black body at the air's mid-height temperature.
  const double open_k = drivers.air_c(time_s, 1.0) + kKelvin;
  const double open_emission = kStefanBoltzmann * open_k * open_k * open_k * open_k;
  std::vector<double> t_k(n), j(n);
  std::vector<double>& h = *irradiance;  // starts from the last step's, or from σT⁴
  auto emission = [](double t) { return kStefanBoltzmann * t * t * t * t; };
  const bool warm = h.size() == n;
  h.resize(n);
  for (size_t i = 0; i < n; ++i) {
    t_k[i] = (nodes_[i].fixed ? nodes_[i].fixed_temperature_c : prev_c[i]) + kKelvin;
    if (!warm) h[i] = emission(t_k[i]);
  }
  // Each sweep in two passes over the nodes, each node from the last pass's values alone.
  const int workers = ResolveThreadCount(threads_);
  std::vector<double> change_of_worker(static_cast<size_t>(workers));
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    ParallelForChunks(static_cast<int64_t>(n), kNodesPerChunk, threads_, [&](int64_t begin, int64_t end, int) {
      for (auto i = static_cast<size_t>(begin); i < static_cast<size_t>(end); ++i) {
        j[i] = nodes_[i].emissivity * emission(t_k[i]) + (1 - nodes_[i].emissivity) * h[i];
      }
    });
    // Each free node from its balance, its own emission linearised about its current value (a
    // Newton step, so the sweeps converge to the exact σT⁴ balance).
    std::fill(change_of_worker.begin(), change_of_worker.end(), 0.0);
    ParallelForChunks(static_cast<int64_t>(n), kNodesPerChunk, threads_, [&](int64_t begin, int64_t end, int worker) {
      double& change = change_of_worker[static_cast<size_t>(worker)];
      for (auto i = static_cast<size_t>(begin); i < static_cast<size_t>(end); ++i) {
        h[i] = Gather(i, j, open_emission);
        const ThermalNode& node = nodes_[i];
        if (node.fixed) continue;
        const double t0 = t_k[i];
        const double b = 4 * kStefanBoltzmann * t0 * t0 * t0, a = emission(t0) - b * t0;
        const double exchange = node.area_m2 * node.emissivity;
        const double t = (rhs[i] + exchange * (h[i] - a)) / (diagonal[i] + exchange * b);
        change = std::max(change, std::abs(t - t0));
        t_k[i] = t;
      }
    });
    if (*std::max_element(change_of_worker.begin(), change_of_worker.end()) < kToleranceK) break;
  }
  next_c->resize(n);
  for (size_t i = 0; i < n; ++i) (*next_c)[i] = t_k[i] - kKelvin;
}

std::vector<double> ThermalNetwork::SteadyState(const ThermalDrivers& drivers, double time_s) const {
  std::vector<double> guess(nodes_.size(), drivers.air_c(time_s, 1.0)), result, irradiance;
  Step(drivers, time_s, 0.0, guess, &result, &irradiance);
  return result;
}

void ThermalNetwork::Start(ThermalDrivers drivers, double t0_s, double step_s, double spin_up_s) {
  HOILCD_CHECK_MSG(step_s > 0 && spin_up_s >= 0 && drivers.air_c, "thermal grid: step > 0, spin-up >= 0, an air");
  drivers_ = std::move(drivers);
  t0_s_ = t0_s;
  step_s_ = step_s;
  const auto spin_steps = static_cast<int64_t>(std::ceil(spin_up_s / step_s));
  double time = t0_s - static_cast<double>(spin_steps) * step_s;
  std::vector<double> state = SteadyState(drivers_, time);
  std::vector<double> next;
  irradiance_.clear();
  for (int64_t k = 0; k < spin_steps; ++k) {
    time = t0_s - static_cast<double>(spin_steps - k - 1) * step_s;
    Step(drivers_, time, step_s, state, &next, &irradiance_);
    state.swap(next);
  }
  grid_c_.clear();
  grid_c_.push_back(std::move(state));
}

void ThermalNetwork::AdvanceTo(double time_s) {
  HOILCD_CHECK_MSG(!grid_c_.empty(), "ThermalNetwork::AdvanceTo before Start");
  std::vector<double> next;
  while (t0_s_ + static_cast<double>(grid_c_.size() - 1) * step_s_ < time_s) {
    Step(drivers_, t0_s_ + static_cast<double>(grid_c_.size()) * step_s_, step_s_, grid_c_.back(), &next, &irradiance_);
    grid_c_.push_back(next);
  }
}

void ThermalNetwork::Solve(ThermalDrivers drivers, double t0_s, double t1_s, double step_s, double spin_up_s) {
  Start(std::move(drivers), t0_s, step_s, spin_up_s);
  AdvanceTo(t1_s);
}

void ThermalNetwork::GridPlace(double time_s, size_t* k, double* weight) const {
  HOILCD_CHECK_MSG(!grid_c_.empty(), "ThermalNetwork asked for a state before Start");
  const double u = std::clamp((time_s - t0_s_) / step_s_, 0.0, static_cast<double>(grid_c_.size() - 1));
  *k = std::min(static_cast<size_t>(u), grid_c_.size() - 1);
  *weight = u - static_cast<double>(*k);
}

void ThermalNetwork::TemperaturesAt(double time_s, std::vector<double>* temperatures_c) const {
  size_t k = 0;
  double w = 0;
  GridPlace(time_s, &k, &w);
  const size_t k1 = std::min(k + 1, grid_c_.size() - 1);
  temperatures_c->resize(nodes_.size());
  for (size_t i = 0; i < nodes_.size(); ++i) (*temperatures_c)[i] = (1 - w) * grid_c_[k][i] + w * grid_c_[k1][i];
}

std::vector<float> ThermalNetwork::IncidentRadiance(const std::vector<float>& emitted,
                                                    const std::vector<float>& reflectivity, float open) const {
  const size_t n = nodes_.size();
  std::vector<float> incident(n, 0.0f), next(n);
  const int workers = ResolveThreadCount(threads_);
  std::vector<float> change_of_worker(static_cast<size_t>(workers));
  for (int sweep = 0; sweep < 100; ++sweep) {
    std::fill(change_of_worker.begin(), change_of_worker.end(), 0.0f);
    ParallelForChunks(static_cast<int64_t>(n), kNodesPerChunk, threads_, [&](int64_t begin, int64_t end, int worker) {
      float& change = change_of_worker[static_cast<size_t>(worker)];
      for (auto i = static_cast<size_t>(begin); i < static_cast<size_t>(end); ++i) {
        float sum = open_share_[i] * open;
        for (size_t e = row_begin_[i]; e < row_begin_[i + 1]; ++e) {
          const auto j = static_cast<size_t>(column_[e]);
          sum += factor_[e] * (emitted[j] + reflectivity[j] * incident[j]);
        }
        next[i] = sum;
        change = std::max(change, std::abs(sum - incident[i]));
      }
    });
    incident.swap(next);
    if (*std::max_element(change_of_worker.begin(), change_of_worker.end()) <= 1e-6f * std::max(1.0f, open)) break;
  }
  return incident;
}

}  // namespace hoilcd
