#include "hoilcd/sim/sensor/sensor.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

constexpr int64_t kRowsPerChunk = 16;

// std::round (halves away from zero) in vector lanes: beyond 2^52 (and for NaN and ±inf) every
// double is its own rounding; below, the truncation and the remainder are exact.
inline double RoundHalfAway(double x) {
  const bool small = std::abs(x) < 4503599627370496.0;
  const double v = small ? x : 0.0;
  const double t = std::trunc(v);
  const double rest = v - t;
  // Selects rather than branches (the remainder is random per pixel); exact as t is an integer
  // below 2^52. copysign: round gives −0 for x in (−0.5, −0].
  const double up = rest >= 0.5 ? 1.0 : 0.0, down = rest <= -0.5 ? 1.0 : 0.0;
  return small ? std::copysign(t + up - down, v) : x;
}

// The camera's emissivity setting undone: the signal of a grey surface of that emissivity,
// reflecting the assumed reflected temperature, to the radiance of a black body (step 6).
struct EmissivityCorrection {
  bool grey;  // emissivity setting below 1 (else the identity)
  double emissivity, reflected_part;
  double operator()(double s) const { return grey ? (s - reflected_part) / emissivity : s; }
};

EmissivityCorrection CorrectionOf(const SensorOptions& options, double reflected_radiance) {
  return {options.emissivity_setting < 1.0, options.emissivity_setting,
          (1.0 - options.emissivity_setting) * reflected_radiance};
}

// What Apply adds to a pixel's signal between the blur and the table inversion (steps 2-6).
struct SignalEffects {
  bool time_constant, fixed_pattern, temporal_noise;
  float blend;
  double shutter_radiance, drift_signal, shading_signal, noise_signal;
  EmissivityCorrection correct;
};

// Steps 2-6 for one row, branch-free per pixel so that the loop runs in vector lanes; the AVX2
// clone has no FMA, so both clones give the same doubles.
__attribute__((target_clones("avx2", "default"))) void SignalRow(
    const SignalEffects& e, int width, const float* __restrict now, const float* __restrict before,
    const float* __restrict gain, const float* __restrict offset, const float* __restrict shading,
    const float* __restrict noise, double* __restrict signal) {
  for (int x = 0; x < width; ++x) {
    double s = now[x];
    if (e.time_constant) s = e.blend * now[x] + (1.0f - e.blend) * before[x];
    if (e.fixed_pattern) s += gain[x] * (s - e.shutter_radiance) + offset[x];
    s += e.drift_signal + e.shading_signal * shading[x];
    if (e.temporal_noise) s += e.noise_signal * noise[x];
    signal[x] = e.correct(s);
  }
}

// Step 8's rounding: `t_c` to the nearest multiple of `step_k` (halves away from zero) when
// `step_k` > 0, else itself.
inline float Quantised(float t_c, double step_k) {
  return step_k > 0 ? static_cast<float>(RoundHalfAway(t_c / step_k) * step_k) : t_c;
}

// Step 8: kelvin to °C, quantised.
__attribute__((target_clones("avx2", "default"))) void CelsiusRow(int width, const double* __restrict kelvin,
                                                                  double step_k, float* __restrict out) {
  for (int x = 0; x < width; ++x) out[x] = Quantised(static_cast<float>(kelvin[x] - kZeroCelsiusK), step_k);
}

// Step 8 after the in-camera filter: °C quantised.
void QuantiseRow(int width, const float* in_c, double step_k, float* out_c) {
  for (int x = 0; x < width; ++x) out_c[x] = Quantised(in_c[x], step_k);
}

}  // namespace

PixelResponse PixelResponseOf(const SensorOptions& options, const BandRadianceTable& table) {
  return {options.f_number,
          options.pixel_pitch_um,
          options.pixel_fill_factor,
          options.aberration_sigma_px,
          table.lambda_min_um(),
          table.lambda_max_um(),
          options.reference_temperature_c + kZeroCelsiusK};
}

SensorOptions::SensorOptions() { Table().FillDefaults(this); }

const OptionTable<SensorOptions>& SensorOptions::Table() {
  using O = SensorOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("optics_blur", &O::optics_blur, true,
               "the camera's pixel response on the radiance: lens diffraction × pixel area")
          .Add("f_number", &O::f_number, 1.1, "", R::Closed(0.5, 8), "the lens's working f-number (diffraction)")
          .Add("pixel_pitch_um", &O::pixel_pitch_um, 12.0, "µm", R::Closed(2, 50), "detector pixel pitch")
          .Add("pixel_fill_factor", &O::pixel_fill_factor, 1.0, "", R().Above(0).AtMost(1),
               "share of each pixel's area that absorbs (a centred square)")
          .Add("aberration_sigma_px", &O::aberration_sigma_px, 0.0, "px", R::Closed(0, 5),
               "Gaussian 1-sigma of lens aberrations and defocus on top of diffraction (0: diffraction-limited)")
          .Add("temporal_noise", &O::temporal_noise, true, "white noise, new every frame")
          .Add("netd_k", &O::netd_k, 0.040, "K", R::Closed(0, 1), "noise-equivalent temperature difference (1-sigma)")
          .Add("fixed_pattern", &O::fixed_pattern, true, "residual non-uniformity after factory calibration")
          .Add("fpn_offset_k", &O::fpn_offset_k, 0.05, "K", R::Closed(0, 2), "per-pixel offset (1-sigma)")
          .Add("fpn_gain_sigma", &O::fpn_gain_sigma, 0.002, "", R::Closed(0, 0.2),
               "per-pixel relative gain error (1-sigma)")
          .Add("column_stripe_k", &O::column_stripe_k, 0.03, "K", R::Closed(0, 2), "per-column offset (1-sigma)")
          .Add("shutter_temperature_c", &O::shutter_temperature_c, 25.0, "°C", R::Closed(-50, 150),
               "FFC shutter temperature: gain errors vanish there")
          .CodeOnly()
          .Add("drift", &O::drift, true, "global offset ramp between flat-field corrections")
          .Add("drift_k_per_min", &O::drift_k_per_min, 0.2, "K/min", R::Closed(0, 10),
               "1-sigma of the ramp's random slope per FFC interval")
          .Add("ffc_interval_s", &O::ffc_interval_s, 60.0, "s", R::Closed(0, 86400),
               "time between flat-field corrections (0: never, unless ffc_temperature_delta_k triggers them)")
          .Rule("ffc_interval_s",
                [](const O& o) {
                  return o.ffc_interval_s == 0 || o.ffc_interval_s >= 1 ? "" : "must be 0 (never) or at least 1 s";
                })
          .Add("ffc_temperature_delta_k", &O::ffc_temperature_delta_k, 0.0, "K", R::Closed(0, 20),
               "an FFC also once the housing has warmed this much since the last one (0: off)")
          .Optional()
          .Rule("ffc_temperature_delta_k",
                [](const O& o) {
                  const double period_s = FfcPeriodS(o);
                  return period_s == 0 || period_s >= 1
                             ? ""
                             : "must give at least 1 s between FFCs at housing_warming_k_per_min (got " +
                                   std::to_string(period_s) + " s)";
                })
          .Add("lens_shading", &O::lens_shading, true, "radial shading that grows as the housing warms after an FFC")
          .Add("housing_warming_k_per_min", &O::housing_warming_k_per_min, 0.5, "K/min", R::Closed(0, 10),
               "housing temperature rise after each FFC")
          .Add("vignetting_k_per_k", &O::vignetting_k_per_k, 0.4, "K/K", R::Closed(-5, 5),
               "corner minus centre per K of housing warming")
          .Add("narcissus_k_per_k", &O::narcissus_k_per_k, 0.2, "K/K", R::Closed(-5, 5),
               "depth of the centred dark spot per K of housing warming")
          .Add("narcissus_sigma", &O::narcissus_sigma, 0.35, "", R::Closed(0.05, 2),
               "spot radius (1-sigma) as a fraction of the half-diagonal")
          .Add("ffc_freeze", &O::ffc_freeze, true, "output repeats the last frame while the shutter is shut")
          .Add("ffc_freeze_s", &O::ffc_freeze_s, 0.5, "s", R::Closed(0, 5), "freeze length at each FFC")
          .Add("time_constant", &O::time_constant, true, "bolometer thermal lag (motion smear)")
          .Add("time_constant_s", &O::time_constant_s, 0.010, "s", R().Above(0).AtMost(1),
               "bolometer thermal time constant")
          .Add("quantisation", &O::quantisation, true, "output rounded to a temperature step")
          .Add("quantisation_step_k", &O::quantisation_step_k, 0.01, "K", R().Above(0).AtMost(1),
               "output temperature step")
          .Add("spatial_filter", &O::spatial_filter, false,
               "in-camera spatial noise reduction: a Gaussian on the output before its quantisation")
          .Add("spatial_filter_sigma_px", &O::spatial_filter_sigma_px, 0.9, "px", R().Above(0).AtMost(5),
               "its 1-sigma (0.9: the FLIR E8xt's frames; the Pocket2's is not published)")
          .Add("reference_temperature_c", &O::reference_temperature_c, 26.85, "°C", R::Closed(-50, 150),
               "scene temperature at which the K figures hold (NETD convention, 300 K)")
          .CodeOnly()
          .Add("emissivity_setting", &O::emissivity_setting, 1.0, "", R::Closed(0.01, 1),
               "emissivity the camera assumes when converting to temperature")
          .Add("reflected_temperature_c", &O::reflected_temperature_c, 22.0, "°C", R::Closed(-50, 150),
               "reflected temperature assumed when the emissivity setting is below 1 (the scene's room temperature)")
          .CodeOnly()
          .Add("display_min_c", &O::display_min_c, 20.0, "°C", R::Closed(-50, 200), "8-bit display window: maps to 0")
          .Add("display_max_c", &O::display_max_c, 30.0, "°C", R::Closed(-50, 200), "8-bit display window: maps to 255")
          .Rule("display_max_c", [](const O& o) {
            return o.display_max_c > o.display_min_c ? "" : "must be greater than display_min_c";
          });
  return table;
}

std::string SensorOptions::Check() const { return Table().FirstProblem(*this); }

double FfcPeriodS(const SensorOptions& options) {
  double period_s = options.ffc_interval_s;
  if (options.ffc_temperature_delta_k > 0 && options.housing_warming_k_per_min > 0) {
    const double by_temperature_s = options.ffc_temperature_delta_k / options.housing_warming_k_per_min * 60.0;
    period_s = period_s > 0 ? std::min(period_s, by_temperature_s) : by_temperature_s;
  }
  return period_s;
}

SensorModel::SensorModel(SensorOptions options, int width, int height, double frame_rate_hz, uint64_t seed,
                         const BandRadianceTable* table, int num_threads, std::optional<uint64_t> session_seed)
    : options_(std::move(options)),
      width_(width),
      height_(height),
      frame_rate_hz_(frame_rate_hz),
      ffc_period_s_(FfcPeriodS(options_)),
      seed_(seed),
      session_seed_(session_seed.value_or(seed)),
      table_(table),
      num_threads_(ResolveThreadCount(num_threads)),
      noise_scratch_(static_cast<size_t>(num_threads_) * std::max(width, 0)),
      signal_scratch_(static_cast<size_t>(num_threads_) * std::max(width, 0)) {
  const std::string problem = options_.Check();
  HOILCD_CHECK_MSG(problem.empty(), problem);
  HOILCD_CHECK(table_ != nullptr);
  HOILCD_CHECK_MSG(width > 0 && height > 0, width << "x" << height);
  HOILCD_CHECK_MSG(frame_rate_hz > 0.0, "frame rate " << frame_rate_hz);
  HOILCD_CHECK_MSG(ffc_period_s_ == 0.0 || ffc_period_s_ * frame_rate_hz >= 1.0, "FFC period shorter than a frame");
  responsivity_ = table_->SlopeFromKelvin(options_.reference_temperature_c + kZeroCelsiusK);
  shutter_radiance_ = table_->RadianceFromKelvin(options_.shutter_temperature_c + kZeroCelsiusK);
  reflected_radiance_ = table_->RadianceFromKelvin(options_.reflected_temperature_c + kZeroCelsiusK);
  blend_ = static_cast<float>(-std::expm1(-1.0 / (frame_rate_hz_ * options_.time_constant_s)));
  if (options_.optics_blur) pixel_response_.emplace(PixelResponseOf(options_, *table_), width_, height_);

  // Fixed pattern: keyed by pixel (or column) only, so it is the same in every frame.
  gain_ = cv::Mat::zeros(height_, width_, CV_32F);
  offset_signal_ = cv::Mat::zeros(height_, width_, CV_32F);
  std::vector<double> column_k(width_);
  for (int x = 0; x < width_; ++x) {
    column_k[x] = options_.column_stripe_k * KeyedRng(seed_, "sensor.column_stripe", x).Normal();
  }
  for (int y = 0; y < height_; ++y) {
    float* gain = gain_.ptr<float>(y);
    float* offset = offset_signal_.ptr<float>(y);
    for (int x = 0; x < width_; ++x) {
      const int64_t pixel = static_cast<int64_t>(y) * width_ + x;
      gain[x] = static_cast<float>(options_.fpn_gain_sigma * KeyedRng(seed_, "sensor.fpn_gain", pixel).Normal());
      const double offset_k = options_.fpn_offset_k * KeyedRng(seed_, "sensor.fpn_offset", pixel).Normal();
      offset[x] = static_cast<float>(responsivity_ * (offset_k + column_k[x]));
    }
  }

  // Lens shading shape: ρ = 1 at the corner pixels' centres.
  shading_shape_ = cv::Mat::zeros(height_, width_, CV_32F);
  const double cx = 0.5 * (width_ - 1), cy = 0.5 * (height_ - 1);
  const double half_diagonal_sq = std::max(cx * cx + cy * cy, 1e-12);
  const double spot_edge = std::exp(-0.5 / (options_.narcissus_sigma * options_.narcissus_sigma));
  for (int y = 0; y < height_; ++y) {
    float* shape = shading_shape_.ptr<float>(y);
    for (int x = 0; x < width_; ++x) {
      const double rho_sq = ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / half_diagonal_sq;
      const double spot =
          (std::exp(-0.5 * rho_sq / (options_.narcissus_sigma * options_.narcissus_sigma)) - spot_edge) /
          (1.0 - spot_edge);
      shape[x] = static_cast<float>(options_.vignetting_k_per_k * rho_sq - options_.narcissus_k_per_k * spot);
    }
  }
}

int64_t SensorModel::FfcFrame(int64_t index) const {
  return std::llround(static_cast<double>(index) * ffc_period_s_ * frame_rate_hz_);
}

int64_t SensorModel::FfcIndex(int frame) const {
  if (ffc_period_s_ <= 0.0) return 0;
  int64_t index = static_cast<int64_t>(std::floor(frame / (ffc_period_s_ * frame_rate_hz_)));
  while (FfcFrame(index + 1) <= frame) ++index;
  while (index > 0 && FfcFrame(index) > frame) --index;
  return index;
}

std::vector<int> SensorModel::FfcFrames(int num_frames) const {
  std::vector<int> frames;
  if (ffc_period_s_ <= 0.0) return frames;
  for (int64_t j = 1;; ++j) {
    const int64_t frame = FfcFrame(j);
    if (frame >= num_frames) break;
    frames.push_back(static_cast<int>(frame));
  }
  return frames;
}

double SensorModel::DriftK(int frame) const {
  if (!options_.drift) return 0.0;
  const int64_t index = FfcIndex(frame);
  const double since_ffc_s = static_cast<double>(frame - FfcFrame(index)) / frame_rate_hz_;
  const double slope_k_per_s =
      options_.drift_k_per_min / 60.0 * KeyedRng(session_seed_, "sensor.drift", index).Normal();
  return slope_k_per_s * since_ffc_s;
}

double SensorModel::HousingWarmingK(int frame) const {
  if (!options_.lens_shading) return 0.0;
  const double since_ffc_s = static_cast<double>(frame - FfcFrame(FfcIndex(frame))) / frame_rate_hz_;
  return options_.housing_warming_k_per_min / 60.0 * since_ffc_s;
}

double SensorModel::ShadingK(int frame, int x, int y) const {
  HOILCD_CHECK_MSG(x >= 0 && x < width_ && y >= 0 && y < height_, "pixel " << x << "," << y);
  return HousingWarmingK(frame) * shading_shape_.at<float>(y, x);
}

double SensorModel::ShadingCornerToCentreK(int frame) const {
  return HousingWarmingK(frame) * (options_.vignetting_k_per_k + options_.narcissus_k_per_k);
}

int SensorModel::FreezeFrames() const {
  if (!options_.ffc_freeze || ffc_period_s_ <= 0.0) return 0;
  const int64_t frames = std::llround(options_.ffc_freeze_s * frame_rate_hz_);
  const int64_t shortest_interval = static_cast<int64_t>(std::floor(ffc_period_s_ * frame_rate_hz_));
  return static_cast<int>(std::max<int64_t>(0, std::min(frames, shortest_interval - 1)));
}

int SensorModel::ShownFrame(int frame) const {
  const int freeze = FreezeFrames();
  if (freeze == 0) return frame;
  const int64_t index = FfcIndex(frame);
  const int64_t ffc = FfcFrame(index);
  if (index >= 1 && frame - ffc < freeze) return static_cast<int>(ffc - 1);
  return frame;
}

int SensorModel::ReplayFrom(int frame) const {
  if (frame <= 0) return 0;
  const int shown = ShownFrame(frame);
  // A frozen frame shows an earlier output, which itself depends on the frame before it.
  return shown != frame ? std::max(0, shown - 1) : frame - 1;
}

double SensorModel::TemporalNoiseK(double temperature_c) const {
  if (!options_.temporal_noise) return 0.0;
  return options_.netd_k * responsivity_ / table_->SlopeFromKelvin(temperature_c + kZeroCelsiusK);
}

cv::Mat SensorModel::Apply(int frame, const cv::Mat& radiance) {
  HOILCD_CHECK_MSG(radiance.type() == CV_32FC1 && radiance.cols == width_ && radiance.rows == height_,
                   "radiance must be CV_32F " << width_ << "x" << height_);
  HOILCD_CHECK_MSG(frame >= 0, "frame " << frame);
  HOILCD_CHECK_MSG(last_frame_ < 0 || frame == last_frame_ + 1,
                   "frame " << frame << " after frame " << last_frame_ << " (frames go in order)");
  // The blurred radiance goes into the spare buffer (no allocation after the first frames);
  // it becomes previous_ at the end and the old previous_ the next spare.
  cv::Mat& blurred = spare_;
  if (options_.optics_blur) {
    pixel_response_->Apply(radiance, &blurred, num_threads_);
  } else {
    radiance.copyTo(blurred);
  }
  const cv::Mat& previous = previous_.empty() ? blurred : previous_;
  if (ShownFrame(frame) != frame && !shown_.empty()) {  // FFC freeze: the shutter is shut
    std::swap(previous_, spare_);
    last_frame_ = frame;
    return shown_.clone();
  }
  SignalEffects effects;
  effects.time_constant = options_.time_constant;
  effects.fixed_pattern = options_.fixed_pattern;
  effects.temporal_noise = options_.temporal_noise;
  effects.blend = blend_;
  effects.shutter_radiance = shutter_radiance_;
  effects.drift_signal = responsivity_ * DriftK(frame);
  effects.shading_signal = responsivity_ * HousingWarmingK(frame);
  effects.noise_signal = options_.temporal_noise ? responsivity_ * options_.netd_k : 0.0;
  effects.correct = CorrectionOf(options_, reflected_radiance_);
  const double step_k = options_.quantisation ? options_.quantisation_step_k : 0.0;
  const uint64_t noise_key = HashCombine(session_seed_, HashString("sensor.noise"), static_cast<uint64_t>(frame));

  // With the in-camera filter, the rows leave unquantised; the filter and then the step follow.
  const double row_step_k = options_.spatial_filter ? 0.0 : step_k;
  cv::Mat temperature(height_, width_, CV_32F);
  ParallelForChunks(height_, kRowsPerChunk, num_threads_, [&](int64_t begin, int64_t end, int worker) {
    float* noise = noise_scratch_.data() + static_cast<size_t>(worker) * width_;
    double* signal = signal_scratch_.data() + static_cast<size_t>(worker) * width_;
    for (int64_t y = begin; y < end; ++y) {
      const int row = static_cast<int>(y);
      if (effects.temporal_noise) KeyedNormals(noise_key, y * width_, width_, noise);
      SignalRow(effects, width_, blurred.ptr<float>(row), previous.ptr<float>(row), gain_.ptr<float>(row),
                offset_signal_.ptr<float>(row), shading_shape_.ptr<float>(row), noise, signal);
      // Step 7: the table inversion (a gather per pixel), then the quantisation.
      table_->KelvinFromRadiance(signal, width_, signal);
      CelsiusRow(width_, signal, row_step_k, temperature.ptr<float>(row));
    }
  });
  if (options_.spatial_filter) ApplySpatialFilter(step_k, &temperature);
  std::swap(previous_, spare_);
  last_frame_ = frame;
  temperature.copyTo(shown_);
  return temperature;
}

void SensorModel::ApplySpatialFilter(double step_k, cv::Mat* temperature) const {
  cv::Mat filtered;
  cv::GaussianBlur(*temperature, filtered, cv::Size(0, 0), options_.spatial_filter_sigma_px,
                   options_.spatial_filter_sigma_px, cv::BORDER_REFLECT);
  ParallelForChunks(height_, kRowsPerChunk, num_threads_, [&](int64_t begin, int64_t end, int) {
    for (int64_t y = begin; y < end; ++y) {
      QuantiseRow(width_, filtered.ptr<float>(static_cast<int>(y)), step_k,
                  temperature->ptr<float>(static_cast<int>(y)));
    }
  });
}

cv::Mat SensorModel::IdealTemperature(const cv::Mat& radiance) const {
  HOILCD_CHECK_MSG(radiance.type() == CV_32FC1 && radiance.cols == width_ && radiance.rows == height_,
                   "radiance must be CV_32F " << width_ << "x" << height_);
  cv::Mat temperature(height_, width_, CV_32F);
  // The emissivity correction and the table inversion, a row at a time.
  const EmissivityCorrection correct = CorrectionOf(options_, reflected_radiance_);
  ParallelForChunks(height_, kRowsPerChunk, num_threads_, [&](int64_t begin, int64_t end, int) {
    std::vector<double> signal(static_cast<size_t>(width_));
    for (int64_t y = begin; y < end; ++y) {
      const float* in = radiance.ptr<float>(static_cast<int>(y));
      for (int x = 0; x < width_; ++x) signal[x] = correct(in[x]);
      table_->KelvinFromRadiance(signal.data(), width_, signal.data());
      CelsiusRow(width_, signal.data(), /*step_k=*/0.0, temperature.ptr<float>(static_cast<int>(y)));
    }
  });
  return temperature;
}

}  // namespace hoilcd
