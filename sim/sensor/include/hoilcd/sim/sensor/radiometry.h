// LWIR radiometry: Planck's law integrated over the camera band (8–14 µm by default), a fast
// two-way table between temperature and band radiance, and the radiance a surface sends to the
// camera (emitted plus reflected). Radiance is in W·m⁻²·sr⁻¹ throughout.
#pragma once

#include <cmath>
#include <vector>

#include "hoilcd/core/util/units.h"

namespace hoilcd {

// Spectral radiance B_λ(T) of a black body, W·m⁻²·sr⁻¹·m⁻¹ (λ in metres).
double PlanckSpectral(double lambda_m, double temperature_k);

// Planck spectral radiance integrated over [lambda_min_um, lambda_max_um], by composite Simpson
// integration with `steps` intervals (rounded up to even). The reference: accurate, slow.
double IntegratePlanckBand(double temperature_k, double lambda_min_um = 8.0, double lambda_max_um = 14.0,
                           int steps = 20000);

// The same band radiance from the closed-form series of the Planck integral
// (∫ x³/(eˣ−1) dx = Σₙ e^{−nx}(x³/n + 3x²/n² + 6x/n³ + 6/n⁴)); exact to double precision
// and ~1000× faster than IntegratePlanckBand. Used to fill BandRadianceTable.
double PlanckBandSeries(double temperature_k, double lambda_min_um = 8.0, double lambda_max_um = 14.0);

// Band radiance vs temperature on a 0.05 K grid with linear interpolation (relative error
// below 1e-6 against direct integration at 250–350 K), and its exact inverse: the inverse
// inverts the same piecewise-linear curve, so CelsiusFromRadiance(RadianceFromCelsius(t)) == t
// up to float rounding. Temperatures outside [t_min_k, t_max_k] are clamped.
class BandRadianceTable {
 public:
  explicit BandRadianceTable(double lambda_min_um = 8.0, double lambda_max_um = 14.0, double t_min_k = 200.0,
                             double t_max_k = 500.0);

  float RadianceFromCelsius(float temperature_c) const;  // fast, per pixel
  float CelsiusFromRadiance(float radiance) const;       // fast inverse, per pixel
  double RadianceFromKelvin(double t_k) const;
  double KelvinFromRadiance(double radiance) const;
  // kelvin[i] = KelvinFromRadiance(radiance[i]) for i < count, without a call per value.
  void KelvinFromRadiance(const double* radiance, int count, double* kelvin) const;
  // dL/dT at t_k (W·m⁻²·sr⁻¹·K⁻¹), from the series by central difference: the camera's
  // responsivity, which converts figures given in kelvin (NETD, offsets) to radiance.
  double SlopeFromKelvin(double t_k) const;

  double lambda_min_um() const { return lambda_min_um_; }
  double lambda_max_um() const { return lambda_max_um_; }
  double t_min_k() const { return t_min_k_; }
  double t_max_k() const { return t_max_k_; }

 private:
  double lambda_min_um_, lambda_max_um_, t_min_k_, t_max_k_;
  double step_k_;                   // temperature grid spacing
  std::vector<double> radiance_;    // radiance_[i] = L(t_min_k_ + i·step_k_)
  double inverse_bin_;              // radiance width of one inverse bin
  std::vector<int> first_segment_;  // per radiance bin: the segment holding its lower edge
};

// Radiance leaving a surface towards the camera: L = ε·B(T) + (1−ε)·L_env. L_env is the room's
// ambient radiance for diffuse surfaces, or the radiance of one traced reflection ray for
// specular ones; the renderer supplies it.
inline float SurfaceRadiance(float emissivity, float blackbody_radiance, float environment_radiance) {
  return emissivity * blackbody_radiance + (1.0f - emissivity) * environment_radiance;
}

// The share of a rough surface's reflection that stays mirror-like (specular), by the scalar
// scattering theory of Davies (1954) / Bennett & Porteus (1961): exp(−(4π·σ·cos θ / λ)²) for rms
// roughness σ, incidence angle θ from the normal and the band's centre wavelength λ (10 µm for
// 8–14 µm). σ = 0 gives exactly 1 (a perfect mirror); the rest of the reflection is diffuse.
inline float MirrorShare(float roughness_um, float cos_incidence, float wavelength_um = 10.0f) {
  const float k = 4.0f * 3.14159265f * roughness_um * cos_incidence / wavelength_um;
  return std::exp(-k * k);
}

}  // namespace hoilcd
