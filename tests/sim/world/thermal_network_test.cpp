// The room's thermal network (thermal_network.h) against closed forms: view factors of a cube,
// an isothermal enclosure, two parallel plates, a powered object's rise, the cooling a cold
// window casts on a patch facing it, and an outside wall's inner surface temperature.
#include "hoilcd/sim/world/thermal_network.h"

#include <cmath>

#include <gtest/gtest.h>

#include "hoilcd/sim/assets/asset.h"

namespace hoilcd {
namespace {

constexpr double kKelvin = 273.15;

double Emission(double t_c) {
  const double t = t_c + kKelvin;
  return kStefanBoltzmann * t * t * t * t;
}

// Root of a decreasing function on [lo, hi] by bisection.
double Bisect(const std::function<double(double)>& f, double lo, double hi) {
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// A node per quad: two triangles with the given facing normal.
std::vector<ThermalTriangle> Quad(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c,
                                  const Eigen::Vector3f& d, const Eigen::Vector3f& normal) {
  return {ThermalTriangle{{a, b, c}, normal}, ThermalTriangle{{a, c, d}, normal}};
}

// The six inside faces of the unit cube (−x, +x, −y, +y, −z, +z), each a node facing inwards,
// as one mesh in a ray caster (triangle t belongs to face t / 2).
struct Cube {
  TriangleMesh mesh;
  std::vector<std::vector<ThermalTriangle>> faces;
  RayCaster caster;
  Cube() {
    using V = Eigen::Vector3f;
    auto add = [&](V a, V b, V c, V d, V n) {
      const auto base = static_cast<uint32_t>(mesh.positions_m.size());
      for (const V& p : {a, b, c, d}) mesh.positions_m.push_back(p);
      for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(base + i);
      mesh.triangle_material.push_back(0);
      mesh.triangle_material.push_back(0);
      faces.push_back(Quad(a, b, c, d, n));
    };
    add(V(0, 0, 0), V(0, 1, 0), V(0, 1, 1), V(0, 0, 1), V(1, 0, 0));
    add(V(1, 0, 0), V(1, 0, 1), V(1, 1, 1), V(1, 1, 0), V(-1, 0, 0));
    add(V(0, 0, 0), V(0, 0, 1), V(1, 0, 1), V(1, 0, 0), V(0, 1, 0));
    add(V(0, 1, 0), V(1, 1, 0), V(1, 1, 1), V(0, 1, 1), V(0, -1, 0));
    add(V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0), V(0, 0, 1));
    add(V(0, 0, 1), V(0, 1, 1), V(1, 1, 1), V(1, 0, 1), V(0, 0, -1));
    caster.AddInstance(caster.AddPrototype(mesh), Eigen::Matrix4f::Identity());
    caster.Commit();
  }
  ViewFactors Cast(int rays, int threads) const {
    return CastViewFactors(
        caster, faces, std::vector<double>(6, 1.0),
        [](const RayHit& hit, const Eigen::Vector3f&) { return hit.triangle / 2; }, rays, 7, threads);
  }
};

double Factor(const ViewFactors& f, int i, int j) {
  for (const auto& [k, value] : f.rows[static_cast<size_t>(i)]) {
    if (k == j) return value;
  }
  return 0;
}

ThermalDrivers UniformAir(double air_c, double outdoor_c = 5) {
  ThermalDrivers d;
  d.air_c = [air_c](double, double) { return air_c; };
  d.outdoor_c = outdoor_c;
  return d;
}

TEST(ThermalNetwork, CubeViewFactorsMatchTheClosedFormAndDoNotDependOnThreads) {
  const Cube cube;
  const ViewFactors f = cube.Cast(20000, 1);
  // Opposite faces of a cube: 0.19982; adjacent: 0.20004 (Hottel's crossed-strings tables).
  EXPECT_NEAR(Factor(f, 0, 1), 0.19982, 0.01);
  EXPECT_NEAR(Factor(f, 4, 5), 0.19982, 0.01);
  EXPECT_NEAR(Factor(f, 0, 2), 0.20004, 0.01);
  EXPECT_NEAR(Factor(f, 0, 0), 0.0, 1e-9);
  for (int i = 0; i < 6; ++i) {
    double sum = f.open_share[static_cast<size_t>(i)];
    for (const auto& entry : f.rows[static_cast<size_t>(i)]) sum += entry.second;
    EXPECT_NEAR(sum, 1.0, 1e-5) << "row " << i;
    EXPECT_EQ(f.open_share[static_cast<size_t>(i)], 0.0f) << "a closed cube lets nothing out";
  }
  const ViewFactors g = cube.Cast(20000, 2);
  EXPECT_EQ(f.rows, g.rows);
}

TEST(ThermalNetwork, AnEnclosureAtOneTemperatureStaysIsothermalWhateverTheEmissivities) {
  const Cube cube;
  std::vector<ThermalNode> nodes(6);
  const double emissivities[6] = {0.95, 0.1, 0.5, 0.9, 0.3, 0.7};
  for (int i = 0; i < 6; ++i) {
    nodes[static_cast<size_t>(i)].area_m2 = 1;
    nodes[static_cast<size_t>(i)].emissivity = emissivities[i];
    nodes[static_cast<size_t>(i)].heat_capacity_j_k = 1e4;
    nodes[static_cast<size_t>(i)].height_m = 0.5;
  }
  ThermalNetwork network(nodes, cube.Cast(2000, 2));
  network.Solve(UniformAir(19.0), 0, 600, 60, 3600);
  std::vector<double> t;
  network.TemperaturesAt(300, &t);
  for (double value : t) EXPECT_NEAR(value, 19.0, 1e-4);
}

// Two infinite parallel plates (F = 1 both ways): plate 0 held at 40 °C, plate 1 losing only
// through a conductance to 0 °C outdoor air, no convection. Its balance with the exact exchange
// σ(T₀⁴ − T₁⁴)/(1/ε₀ + 1/ε₁ − 1) gives its temperature.
TEST(ThermalNetwork, ParallelPlatesExchangeAsTheClosedFormSays) {
  const double e0 = 0.8, e1 = 0.6, conductance = 3.0;
  std::vector<ThermalNode> nodes(2);
  nodes[0].area_m2 = nodes[1].area_m2 = 1;
  nodes[0].emissivity = e0;
  nodes[1].emissivity = e1;
  nodes[0].fixed = true;
  nodes[0].fixed_temperature_c = 40;
  nodes[1].convection_w_m2k = 0;
  nodes[1].outdoor_conductance_w_k = conductance;
  ViewFactors f;
  f.rows = {{{1, 1.0f}}, {{0, 1.0f}}};
  f.open_share = {0, 0};
  ThermalNetwork network(nodes, f);
  network.Solve(UniformAir(20.0, 0.0), 0, 0, 60, 0);
  std::vector<double> t;
  network.TemperaturesAt(0, &t);
  const double expected = Bisect(
      [&](double t1) { return (Emission(40) - Emission(t1)) / (1 / e0 + 1 / e1 - 1) - conductance * t1; }, 0, 40);
  EXPECT_NEAR(t[1], expected, 0.01);
  EXPECT_DOUBLE_EQ(t[0], 40.0);
}

// An object that sees only black surroundings at the air's temperature rises above them by
// P / (h·A) at steady state, h = h_c + the radiative coefficient; solved exactly here with σT⁴.
TEST(ThermalNetwork, APoweredObjectRisesByItsPowerOverItsConductance) {
  const double power = 25, area = 0.7, h_c = 3, emissivity = 0.94, air = 22;
  std::vector<ThermalNode> nodes(2);
  nodes[0].area_m2 = area;
  nodes[0].emissivity = emissivity;
  nodes[0].convection_w_m2k = h_c;
  nodes[0].power_w = power;
  nodes[0].heat_capacity_j_k = 2000;
  nodes[1].area_m2 = 100;
  nodes[1].emissivity = 1;
  nodes[1].fixed = true;
  nodes[1].fixed_temperature_c = air;
  ViewFactors f;
  f.rows = {{{1, 1.0f}}, {{0, static_cast<float>(area / 100)}}};
  f.open_share = {0, static_cast<float>(1 - area / 100)};
  ThermalNetwork network(nodes, f);
  network.Solve(UniformAir(air), 0, 0, 60, 6 * 3600);
  std::vector<double> t;
  network.TemperaturesAt(0, &t);
  const double expected = Bisect(
      [&](double t0) { return power - h_c * area * (t0 - air) - emissivity * area * (Emission(t0) - Emission(air)); },
      air, air + 100);
  EXPECT_NEAR(t[0], expected, 0.01);
  const double h_r = emissivity * 4 * kStefanBoltzmann * std::pow(air + kKelvin, 3);
  EXPECT_NEAR(t[0] - air, power / ((h_c + h_r) * area), 0.1) << "the linear estimate P / (h A)";
}

// A floor patch under a cold window (a parallel square 1 m above it), the rest of its view open
// to black surroundings at the air's temperature: its cooling follows from the view factor of
// two coaxial parallel squares (Hottel) and its exact balance.
TEST(ThermalNetwork, AColdWindowCoolsThePatchFacingItByTheComputedAmount) {
  using V = Eigen::Vector3f;
  TriangleMesh mesh;
  for (const V& p : {V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0), V(0, 0, 1), V(0, 1, 1), V(1, 1, 1), V(1, 0, 1)}) {
    mesh.positions_m.push_back(p);
  }
  mesh.indices = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
  mesh.triangle_material = {0, 0, 0, 0};
  RayCaster caster;
  caster.AddInstance(caster.AddPrototype(mesh), Eigen::Matrix4f::Identity());
  caster.Commit();
  const std::vector<std::vector<ThermalTriangle>> triangles = {
      Quad(V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0), V(0, 0, 1)),
      Quad(V(0, 0, 1), V(0, 1, 1), V(1, 1, 1), V(1, 0, 1), V(0, 0, -1))};
  const ViewFactors f = CastViewFactors(
      caster, triangles, {1.0, 1.0}, [](const RayHit& hit, const Eigen::Vector3f&) { return hit.triangle / 2; }, 40000,
      3, 2);
  // Coaxial parallel squares of side 1 at distance 1: F = 0.19982.
  const double x = 1.0;
  const double hottel = 2 / (M_PI * x * x) *
                        (std::log(std::sqrt((1 + x * x) * (1 + x * x) / (1 + 2 * x * x))) +
                         2 * x * std::sqrt(1 + x * x) * std::atan(x / std::sqrt(1 + x * x)) - 2 * x * std::atan(x));
  ASSERT_NEAR(hottel, 0.19982, 1e-4);
  EXPECT_NEAR(Factor(f, 0, 1), hottel, 0.006);

  const double air = 21, window = 8, h_c = 0.7, emissivity = 0.93;
  std::vector<ThermalNode> nodes(2);
  nodes[0].area_m2 = 1;
  nodes[0].emissivity = emissivity;
  nodes[0].convection_w_m2k = h_c;
  nodes[1].area_m2 = 1;
  nodes[1].emissivity = 1;
  nodes[1].fixed = true;
  nodes[1].fixed_temperature_c = window;
  ThermalNetwork network(nodes, f);
  network.Solve(UniformAir(air), 0, 0, 60, 0);
  std::vector<double> t;
  network.TemperaturesAt(0, &t);
  const double seen = Factor(f, 0, 1);
  const double expected = Bisect(
      [&](double tp) {
        const double irradiance = seen * Emission(window) + (1 - seen) * Emission(air);
        return h_c * (air - tp) + emissivity * (irradiance - Emission(tp));
      },
      window, air);
  EXPECT_NEAR(t[0], expected, 0.02);
  EXPECT_LT(t[0], air - 1.5) << "the window cools it by kelvins";
}

// An outside wall in an enclosure at the inside temperature: its inner surface settles at
// T_si = T_i − U·R_si·(T_i − T_e) (ISO 6946), with R_si = 1/(h_c + h_r) and the conductance
// through the wall to outdoor air 1/(1/U − R_si).
TEST(ThermalNetwork, AnOutsideWallsInnerSurfaceFollowsItsUValue) {
  const double inside = 21, outdoor = -5, u = 0.6, emissivity = 0.92;
  const double h_r = emissivity * 4 * kStefanBoltzmann * std::pow(inside - 0.5 + kKelvin, 3);
  const double h_c = 2.5, r_si = 1 / (h_c + h_r);
  std::vector<ThermalNode> nodes(2);
  nodes[0].area_m2 = 10;
  nodes[0].emissivity = emissivity;
  nodes[0].convection_w_m2k = h_c;
  nodes[0].heat_capacity_j_k = 10 * 30000;
  nodes[0].outdoor_conductance_w_k = 10 / (1 / u - r_si);
  nodes[1].area_m2 = 1000;
  nodes[1].emissivity = 1;
  nodes[1].fixed = true;
  nodes[1].fixed_temperature_c = inside;
  ViewFactors f;
  f.rows = {{{1, 1.0f}}, {{0, 0.01f}}};
  f.open_share = {0, 0.99f};
  ThermalNetwork network(nodes, f);
  network.Solve(UniformAir(inside, outdoor), 0, 0, 300, 48 * 3600);
  std::vector<double> t;
  network.TemperaturesAt(0, &t);
  EXPECT_NEAR(t[0], inside - u * r_si * (inside - outdoor), 0.02);
}

TEST(ThermalNetwork, ThermalMassLagsAStepInTheAirByItsTimeConstant) {
  std::vector<ThermalNode> nodes(2);
  nodes[0].area_m2 = 1;
  nodes[0].emissivity = 0.01;  // nearly all convection: the lag is C / (h A)
  nodes[0].convection_w_m2k = 5;
  nodes[0].heat_capacity_j_k = 5 * 1000;
  nodes[1].area_m2 = 1;
  nodes[1].emissivity = 0.9;
  nodes[1].fixed = true;
  nodes[1].fixed_temperature_c = 20;
  ViewFactors f;
  f.rows = {{}, {}};
  f.open_share = {1, 1};
  ThermalNetwork network(nodes, f);
  ThermalDrivers d;
  d.air_c = [](double time_s, double) { return time_s < 0 ? 20.0 : 30.0; };
  network.Solve(d, 0, 3000, 1, 600);
  std::vector<double> t;
  // The open share sees the air too, so the node relaxes to the air with h_c + its small h_r.
  const double h = 5 + 0.01 * 4 * kStefanBoltzmann * std::pow(25 + kKelvin, 3);
  network.TemperaturesAt(1000, &t);
  EXPECT_NEAR(t[0], 30 - 10 * std::exp(-1000 * h / 5000), 0.02);
  std::vector<double> between;
  network.TemperaturesAt(1000.5, &between);
  std::vector<double> after;
  network.TemperaturesAt(1001, &after);
  EXPECT_NEAR(between[0], 0.5 * (t[0] + after[0]), 1e-9) << "linear between grid states";
}

TEST(ThermalNetwork, IncidentRadianceOfAClosedCubeAtOneRadianceIsThatRadiance) {
  const Cube cube;
  ThermalNetwork network(std::vector<ThermalNode>(6, ThermalNode{1, 0.9, 2.5, 1, 0.5, 0, 0, false, 22}),
                         cube.Cast(2000, 1));
  const std::vector<float> emitted(6, 0.9f * 40.0f), reflectivity(6, 0.1f);
  for (float value : network.IncidentRadiance(emitted, reflectivity, 0)) EXPECT_NEAR(value, 40.0f, 1e-3);
}

}  // namespace
}  // namespace hoilcd
