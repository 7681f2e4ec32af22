// Uncooled microbolometer camera model: turns the renderer's scene radiance into the apparent
// temperature the camera reports (lens and pixel response, bolometer time constant, fixed-pattern noise,
// drift reset by flat-field correction, temporal noise, quantisation), plus the 8- and 16-bit
// encodings of the dataset folder. Every random draw is keyed by (seed, effect, frame, pixel).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "hoilcd/core/util/option_table.h"
#include "hoilcd/sim/sensor/optics.h"
#include "hoilcd/sim/sensor/radiometry.h"

namespace hoilcd {

// Every effect has a switch (defaults and ranges: Table() in sensor.cpp). Figures in kelvin are specified at
// reference_temperature_c (the NETD convention, 300 K) and applied in the signal (radiance) domain through the camera's
// responsivity dL/dT there, as a real detector does: on colder surfaces the same signal noise
// reads as slightly more temperature noise, on hotter ones as less.
struct SensorOptions {
  bool optics_blur;                  // the camera's pixel response on the radiance (optics.h)
  double f_number;                   // the lens's working f-number
  double pixel_pitch_um;             // detector pixel pitch, µm
  double pixel_fill_factor;          // share of each pixel's area that absorbs, (0, 1]
  double aberration_sigma_px;        // Gaussian 1-σ of aberrations and defocus, px (0: diffraction-limited)
  bool temporal_noise;               // white noise, new every frame
  double netd_k;                     // noise-equivalent temperature difference (1-σ), K
  bool fixed_pattern;                // residual non-uniformity after factory calibration
  double fpn_offset_k;               // per-pixel offset (1-σ), K
  double fpn_gain_sigma;             // per-pixel relative gain error (1-σ), fraction
  double column_stripe_k;            // per-column offset (1-σ), K
  double shutter_temperature_c;      // FFC shutter temperature: gain errors vanish there, °C
  bool drift;                        // global offset ramp between flat-field corrections
  double drift_k_per_min;            // 1-σ of the ramp's random slope per FFC interval, K/min
  double ffc_interval_s;             // time between flat-field corrections, s (0: none by time)
  double ffc_temperature_delta_k;    // an FFC also once the housing warmed this much since the last, K (0: off)
  bool lens_shading;                 // radial shading that grows as the housing warms after an FFC
  double housing_warming_k_per_min;  // housing temperature rise after each FFC, K/min
  double vignetting_k_per_k;         // corner minus centre per K of housing warming, K/K
  double narcissus_k_per_k;          // depth of the centred dark spot per K of warming, K/K
  double narcissus_sigma;            // spot radius (1-σ) as a fraction of the half-diagonal
  bool ffc_freeze;                   // output repeats the last frame while the shutter is shut
  double ffc_freeze_s;               // freeze length at each FFC, s
  bool time_constant;                // bolometer thermal lag (motion smear)
  double time_constant_s;            // bolometer thermal time constant, s
  bool quantisation;                 // output rounded to a temperature step
  double quantisation_step_k;        // output temperature step, K
  bool spatial_filter;               // in-camera spatial noise reduction (off: the Pocket2's is not published)
  double spatial_filter_sigma_px;    // its Gaussian 1-σ, px
  double reference_temperature_c;    // scene temperature at which K figures hold, °C
  double emissivity_setting;         // emissivity the camera assumes when converting, 0–1
  double reflected_temperature_c;    // reflected temperature assumed when ε setting < 1, °C
  double display_min_c;              // 8-bit display window: maps to 0, °C
  double display_max_c;              // 8-bit display window: maps to 255, °C

  SensorOptions();  // the registered defaults
  // Every field once: JSON name (the scene's /camera), unit, default, range, description.
  static const OptionTable<SensorOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// Seconds between flat-field corrections: ffc_interval_s, or sooner the time the housing takes
// to warm by ffc_temperature_delta_k at housing_warming_k_per_min (a camera's trigger on its own
// temperature change since the last FFC, as a FLIR Lepton's); 0 when neither triggers (never).
// The housing warms at a constant rate, so the FFCs come at a constant period either way.
double FfcPeriodS(const SensorOptions& options);

// The pixel response the options describe: their lens and pixel, the table's band, the Planck
// spectrum at the reference temperature.
PixelResponse PixelResponseOf(const SensorOptions& options, const BandRadianceTable& table);

// A stateful model for one sequence, applied to frames in order. Apply(k) does, per pixel:
//   1. the pixel response: the radiance filtered by PixelResponseFilter (diffraction of the lens's
//      aperture × the pixel's area × the aberration Gaussian; optics.h), mirrored at the border;
//   2. time constant: y_k = a·x_k + (1−a)·x_{k−1}, a = 1 − exp(−Δt/τ), x the blurred radiance.
//      This is the per-frame discretisation of a first-order low-pass: between frames the
//      bolometer relaxes towards the new input by a; the remainder of older frames, (1−a)²
//      (3·10⁻⁴ at 25 Hz, τ 10 ms) is dropped so that the state is exactly one frame. The
//      renderer may also pass a motion-blurred radiance for smear within a frame;
//   3. fixed pattern: y + g_p·(y − L_shutter) + R·(o_p + c_column), R = dL/dT at the reference;
//   4. drift: + R·d(k), d a linear ramp from 0 at each FFC with a keyed random slope;
//   5. lens shading: + R·s(k, p), s(k, p) = ΔT_h(k)·(v·ρ² − n·spot(ρ)), ρ the distance from the
//      image centre over the half-diagonal (0 centre, 1 corner), spot a Gaussian of 1-σ
//      narcissus_sigma scaled to 1 at the centre and 0 at the corners, ΔT_h the housing warming
//      since the last FFC. The FFC shutter sits behind the lens, so it flattens the image at the
//      housing temperature of the moment; the lens and housing then warm and their stray
//      radiation (vignetting: the corners see more barrel) and the detector's reflection off the
//      lens (narcissus: a cold spot at the centre) grow until the next FFC. Corner minus centre
//      is ShadingCornerToCentreK(k) = ΔT_h·(v + n);
//   6. temporal noise: + R·NETD·n(k, p), n standard normal: value p of KeyedNormals for the
//      key HashCombine(session_seed, HashString("sensor.noise"), k) (random.h; p = y·width + x);
//   7. conversion to apparent temperature with the emissivity setting; with spatial_filter, the
//      camera's own noise reduction (a Gaussian of spatial_filter_sigma_px, mirrored border) on
//      that image; then quantisation;
//   8. FFC freeze: for FreezeFrames() frames from each FFC frame on, the output is the output of
//      the frame before the FFC (the bolometer state still follows the scene).
// Resuming at frame k: on a new model, call Apply for every frame from ReplayFrom(k) to k−1 with
// their radiance, then Apply(k, ...); the output from frame k on is byte-identical to an
// uninterrupted run. The first frame a model sees is taken as steady (x_{k−1} = x_k).
class SensorModel {
 public:
  // `table` must outlive the model. num_threads: 0 = every core; output does not depend on it.
  // seed keys the camera's own fixed pattern; session_seed (default: seed) what is new each time it
  // is switched on, its temporal noise and drift (a recording run's seed).
  SensorModel(SensorOptions options, int width, int height, double frame_rate_hz, uint64_t seed,
              const BandRadianceTable* table, int num_threads = 1, std::optional<uint64_t> session_seed = {});

  // Scene radiance (CV_32F, W·m⁻²·sr⁻¹, width×height) to apparent temperature (CV_32F, °C).
  // frame: 0 or more, and one more than the previous call's (a new model accepts any frame).
  cv::Mat Apply(int frame, const cv::Mat& radiance);

  // Apparent temperature of an ideal camera (no sensor effects, same emissivity setting):
  // the EXR's T_true channel. Equals Apply with every effect off.
  cv::Mat IdealTemperature(const cv::Mat& radiance) const;

  // Frames in [1, num_frames) at which a flat-field correction happens (round(j·period·fps)
  // for j = 1, 2, ..., period = FfcPeriodS); the camera has just corrected when frame 0 is taken.
  std::vector<int> FfcFrames(int num_frames) const;

  // Drift offset at `frame`, K (0 at each FFC frame; 0 when drift is off).
  double DriftK(int frame) const;

  // Lens shading offset at `frame` and pixel (x, y), K (0 when lens shading is off).
  double ShadingK(int frame, int x, int y) const;
  // Corner minus centre of the lens shading at `frame`, K.
  double ShadingCornerToCentreK(int frame) const;

  // Frames frozen at each FFC: round(ffc_freeze_s·fps), at most one less than the frames
  // between FFCs (0 when the freeze or the FFC is off).
  int FreezeFrames() const;
  // The frame whose output `frame` shows: itself, or the frame before the FFC during a freeze.
  int ShownFrame(int frame) const;
  // The first frame a new model must be given to resume at `frame` (see the class comment):
  // frame − 1, or during a freeze the frame before the one shown.
  int ReplayFrom(int frame) const;

  // Expected 1-σ temporal noise in apparent temperature for a scene at temperature_c, K
  // (NETD scaled by the responsivity ratio; 0 when temporal noise is off).
  double TemporalNoiseK(double temperature_c) const;

  const SensorOptions& options() const { return options_; }

 private:
  // Index j of the FFC period holding `frame` (FFC j at round(j·period·fps), FFC 0 at 0).
  int64_t FfcIndex(int frame) const;
  int64_t FfcFrame(int64_t index) const;
  // Housing temperature rise since the last FFC, K (0 when lens shading is off).
  double HousingWarmingK(int frame) const;
  // Step 7's in-camera filter on the unquantised temperature, then the quantisation to step_k.
  void ApplySpatialFilter(double step_k, cv::Mat* temperature) const;

  SensorOptions options_;
  int width_, height_;
  double frame_rate_hz_;
  double ffc_period_s_;    // FfcPeriodS(options_)
  uint64_t seed_;          // fixed pattern
  uint64_t session_seed_;  // temporal noise, drift
  const BandRadianceTable* table_;
  int num_threads_;
  double responsivity_;                                // dL/dT at the reference temperature, W·m⁻²·sr⁻¹·K⁻¹
  double shutter_radiance_;                            // band radiance of the shutter
  double reflected_radiance_;                          // band radiance of the assumed reflected temperature
  float blend_;                                        // a = 1 − exp(−Δt/τ)
  cv::Mat gain_;                                       // CV_32F per-pixel relative gain error
  cv::Mat offset_signal_;                              // CV_32F per-pixel + column offset, radiance units
  std::vector<float> noise_scratch_;                   // per worker: one row of temporal noise
  std::vector<double> signal_scratch_;                 // per worker: one row of signal
  cv::Mat previous_;                                   // blurred radiance of the last frame applied (empty: none yet)
  cv::Mat spare_;                                      // the buffer the next frame's blurred radiance goes into
  cv::Mat shown_;                                      // output of the last frame not frozen (empty: none yet)
  std::optional<PixelResponseFilter> pixel_response_;  // step 1 (none when optics_blur is off)
  cv::Mat shading_shape_;  // CV_32F per-pixel v·ρ² − n·spot(ρ), K per K of housing warming
  int last_frame_ = -1;
};

}  // namespace hoilcd
