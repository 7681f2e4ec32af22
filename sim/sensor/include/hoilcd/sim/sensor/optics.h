// The camera's pixel response: how much of the scene radiance around a pixel reaches it. A real
// pixel integrates the image of a diffraction-limited lens over its absorber, so its modulation
// transfer function (MTF) is the product of the circular aperture's diffraction MTF (weighted over
// the band by the Planck spectrum) and the pixel area's sinc, times an optional Gaussian for lens
// aberrations and defocus. The renderer samples the radiance at the pixel centres; PixelResponseFilter
// gives that grid this MTF up to the Nyquist frequency (a point-sampled render filtered so has the
// slope of a 4x-supersampled one integrated over its pixels to 0.02: docs/results/2026-12-07-spectrum-slope.md).
#pragma once

#include <opencv2/core.hpp>

namespace hoilcd {

struct PixelResponse {
  double f_number;             // the lens's working f-number (N = focal length / aperture)
  double pixel_pitch_um;       // centre-to-centre distance of the detector's pixels, µm
  double fill_factor;          // share of the pixel's area that absorbs (0, 1]; the absorber a centred square
  double aberration_sigma_px;  // Gaussian 1-σ of the lens's aberrations and defocus, px (0: diffraction-limited)
  double lambda_min_um;        // the camera's band
  double lambda_max_um;
  double band_temperature_k;  // the Planck spectrum that weighs the wavelengths (the scene's typical temperature)
};

// Diffraction MTF of a circular aperture at one wavelength, ν = f·λ·N the frequency over the
// cutoff 1/(λN): (2/π)(arccos ν − ν√(1 − ν²)) for ν < 1, else 0.
double CircularApertureMtf(double nu);

// The response's MTF at (fx, fy) cycles per pixel, 1 at (0, 0).
double PixelResponseMtf(const PixelResponse& response, double fx, double fy);

// The MTF applied to a width x height image mirrored at its borders (cv::BORDER_REFLECT, as a
// convolution would see it): the image's DCT-II (which diagonalises exactly that symmetric
// convolution), times the MTF at each coefficient's frequency (u / 2W, v / 2H cycles/px), inverted.
// No kernel is cut: the MTF is exact on the grid, and a uniform image stays uniform. An odd side is
// mirrored by one more pixel (cv::dct takes even sizes), filtered, and cropped back.
class PixelResponseFilter {
 public:
  PixelResponseFilter(const PixelResponse& response, int width, int height);
  // `radiance` CV_32F width x height into `out` (CV_32F, the same size; not `radiance` itself), on
  // num_threads threads (0: every core); the same bytes at any count. Callable from several
  // threads at once.
  void Apply(const cv::Mat& radiance, cv::Mat* out, int num_threads = 1) const;
  // The MTF at DCT coefficient (u, v) of the (evened) image.
  double GainAt(int u, int v) const { return gain_t_.at<float>(u, v); }

 private:
  int width_, height_;
  cv::Mat gain_t_;  // CV_32F MTF at coefficient (u, v) in row u, column v: the evened size, transposed
};

}  // namespace hoilcd
