#include "hoilcd/sim/sensor/radiometry.h"

#include <algorithm>
#include <cmath>

#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

// CODATA 2018 exact SI constants.
constexpr double kPlanckJs = 6.62607015e-34;
constexpr double kLightSpeedMps = 299792458.0;
constexpr double kBoltzmannJpK = 1.380649e-23;

// Table spacing: linear interpolation error ≈ step²/8 · L''/L ≈ 1e-7 relative at 250–350 K.
constexpr double kTableStepK = 0.05;
// Inverse bins per table segment; keeps the segment walk in CelsiusFromRadiance short.
constexpr int kInverseBinsPerSegment = 4;

// ∫_x^∞ t³/(eᵗ−1) dt by its series; converges geometrically for the x ≥ 1 of LWIR bands.
double PlanckTailIntegral(double x) {
  double sum = 0.0;
  for (int n = 1; n < 10000; ++n) {
    const double nd = n;
    const double term = std::exp(-nd * x) * (x * x * x / nd + 3.0 * x * x / (nd * nd) + 6.0 * x / (nd * nd * nd) +
                                             6.0 / (nd * nd * nd * nd));
    sum += term;
    if (term < 1e-18 * sum) break;
  }
  return sum;
}

void CheckBand(double temperature_k, double lambda_min_um, double lambda_max_um) {
  HOILCD_CHECK_MSG(temperature_k > 0.0, "temperature " << temperature_k << " K");
  HOILCD_CHECK_MSG(lambda_min_um > 0.0 && lambda_max_um > lambda_min_um,
                   "band [" << lambda_min_um << ", " << lambda_max_um << "] µm");
}

}  // namespace

double PlanckSpectral(double lambda_m, double temperature_k) {
  const double x = kPlanckJs * kLightSpeedMps / (lambda_m * kBoltzmannJpK * temperature_k);
  return 2.0 * kPlanckJs * kLightSpeedMps * kLightSpeedMps / std::pow(lambda_m, 5) / std::expm1(x);
}

double IntegratePlanckBand(double temperature_k, double lambda_min_um, double lambda_max_um, int steps) {
  CheckBand(temperature_k, lambda_min_um, lambda_max_um);
  HOILCD_CHECK(steps >= 2);
  const int n = steps + (steps % 2);
  const double a = lambda_min_um * 1e-6, b = lambda_max_um * 1e-6;
  const double h = (b - a) / n;
  double sum = PlanckSpectral(a, temperature_k) + PlanckSpectral(b, temperature_k);
  for (int i = 1; i < n; ++i) {
    sum += (i % 2 == 1 ? 4.0 : 2.0) * PlanckSpectral(a + i * h, temperature_k);
  }
  return sum * h / 3.0;
}

double PlanckBandSeries(double temperature_k, double lambda_min_um, double lambda_max_um) {
  CheckBand(temperature_k, lambda_min_um, lambda_max_um);
  const double kt = kBoltzmannJpK * temperature_k;
  const double hc_over_kt = kPlanckJs * kLightSpeedMps / kt;
  const double x_long = hc_over_kt / (lambda_max_um * 1e-6);
  const double x_short = hc_over_kt / (lambda_min_um * 1e-6);
  // B_λ dλ = 2k⁴T⁴/(h³c²) · x³/(eˣ−1) dx with x = hc/(λkT).
  const double scale = 2.0 * std::pow(kt, 4) / (std::pow(kPlanckJs, 3) * kLightSpeedMps * kLightSpeedMps);
  return scale * (PlanckTailIntegral(x_long) - PlanckTailIntegral(x_short));
}

BandRadianceTable::BandRadianceTable(double lambda_min_um, double lambda_max_um, double t_min_k, double t_max_k)
    : lambda_min_um_(lambda_min_um), lambda_max_um_(lambda_max_um), t_min_k_(t_min_k), t_max_k_(t_max_k) {
  CheckBand(t_min_k, lambda_min_um, lambda_max_um);
  HOILCD_CHECK_MSG(t_max_k > t_min_k, "table range [" << t_min_k << ", " << t_max_k << "] K");
  const int segments = std::max(1, static_cast<int>(std::lround((t_max_k - t_min_k) / kTableStepK)));
  step_k_ = (t_max_k - t_min_k) / segments;
  radiance_.resize(segments + 1);
  for (int i = 0; i <= segments; ++i) {
    radiance_[i] = PlanckBandSeries(t_min_k + i * step_k_, lambda_min_um, lambda_max_um);
  }
  const int bins = segments * kInverseBinsPerSegment;
  inverse_bin_ = (radiance_.back() - radiance_.front()) / bins;
  first_segment_.resize(bins);
  int segment = 0;
  for (int b = 0; b < bins; ++b) {
    const double lower = radiance_.front() + b * inverse_bin_;
    while (segment < segments - 1 && radiance_[segment + 1] <= lower) ++segment;
    first_segment_[b] = segment;
  }
}

double BandRadianceTable::RadianceFromKelvin(double t_k) const {
  const int segments = static_cast<int>(radiance_.size()) - 1;
  const double u = std::clamp((t_k - t_min_k_) / step_k_, 0.0, static_cast<double>(segments));
  const int i = std::min(static_cast<int>(u), segments - 1);
  const double f = u - i;
  return radiance_[i] + f * (radiance_[i + 1] - radiance_[i]);
}

namespace {

// The inversion of KelvinFromRadiance, inlined into both of its forms.
[[gnu::always_inline]] inline double InvertTable(double radiance, const double* table, int segments,
                                                 const int* first_segment, int bins, double inverse_bin, double t_min_k,
                                                 double step_k) {
  const double l = std::clamp(radiance, table[0], table[segments]);
  const int bin = std::min(static_cast<int>((l - table[0]) / inverse_bin), bins - 1);
  int i = first_segment[bin];
  while (i < segments - 1 && table[i + 1] <= l) ++i;
  const double f = (l - table[i]) / (table[i + 1] - table[i]);
  return t_min_k + (i + f) * step_k;
}

}  // namespace

double BandRadianceTable::KelvinFromRadiance(double radiance) const {
  return InvertTable(radiance, radiance_.data(), static_cast<int>(radiance_.size()) - 1, first_segment_.data(),
                     static_cast<int>(first_segment_.size()), inverse_bin_, t_min_k_, step_k_);
}

namespace {

// InvertTable over an array, in vector lanes: the bin look-up and the first kLaneSteps steps of
// the segment walk are branch-free gathers; a value whose walk is longer (rare: bins are
// narrower than segments above ~230 K) is marked in `unfinished` for the caller to redo one by
// one. Same operations on the same segment, so the same bits as InvertTable. No FMA in either
// clone, so both give the same doubles.
constexpr int kLaneSteps = 2;

__attribute__((target_clones("avx2", "default"))) void InvertTableLanes(const double* __restrict radiance, int count,
                                                                        const double* __restrict table, int segments,
                                                                        const int* __restrict first_segment, int bins,
                                                                        double inverse_bin, double t_min_k,
                                                                        double step_k, double* __restrict kelvin,
                                                                        unsigned char* __restrict unfinished) {
  for (int k = 0; k < count; ++k) {
    const double l = std::clamp(radiance[k], table[0], table[segments]);
    const int bin = std::min(static_cast<int>((l - table[0]) / inverse_bin), bins - 1);
    int i = first_segment[bin];
    for (int step = 0; step < kLaneSteps; ++step) i += (i < segments - 1) & (table[i + 1] <= l);
    unfinished[k] = (i < segments - 1) & (table[i + 1] <= l);
    const double f = (l - table[i]) / (table[i + 1] - table[i]);
    kelvin[k] = t_min_k + (i + f) * step_k;
  }
}

}  // namespace

void BandRadianceTable::KelvinFromRadiance(const double* radiance, int count, double* kelvin) const {
  const int segments = static_cast<int>(radiance_.size()) - 1;
  const int bins = static_cast<int>(first_segment_.size());
  constexpr int kBatch = 256;
  double in[kBatch];
  unsigned char unfinished[kBatch];
  for (int begin = 0; begin < count; begin += kBatch) {
    const int n = std::min(kBatch, count - begin);
    std::copy(radiance + begin, radiance + begin + n, in);  // kelvin may be radiance
    InvertTableLanes(in, n, radiance_.data(), segments, first_segment_.data(), bins, inverse_bin_, t_min_k_, step_k_,
                     kelvin + begin, unfinished);
    for (int k = 0; k < n; ++k) {
      if (unfinished[k]) {
        kelvin[begin + k] = InvertTable(in[k], radiance_.data(), segments, first_segment_.data(), bins, inverse_bin_,
                                        t_min_k_, step_k_);
      }
    }
  }
}

float BandRadianceTable::RadianceFromCelsius(float temperature_c) const {
  return static_cast<float>(RadianceFromKelvin(temperature_c + kZeroCelsiusK));
}

float BandRadianceTable::CelsiusFromRadiance(float radiance) const {
  return static_cast<float>(KelvinFromRadiance(radiance) - kZeroCelsiusK);
}

double BandRadianceTable::SlopeFromKelvin(double t_k) const {
  constexpr double kHalfStepK = 0.01;
  const double t = std::clamp(t_k, t_min_k_ + kHalfStepK, t_max_k_ - kHalfStepK);
  return (PlanckBandSeries(t + kHalfStepK, lambda_min_um_, lambda_max_um_) -
          PlanckBandSeries(t - kHalfStepK, lambda_min_um_, lambda_max_um_)) /
         (2.0 * kHalfStepK);
}

}  // namespace hoilcd
