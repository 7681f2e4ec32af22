// The noise of a frame's flattest regions, at its native resolution, and how strongly neighbouring
// pixels share it: white detector noise has a lag-1 correlation near 0, a camera that filters its
// frames spatially (the FLIR E8xt: 0.7) shows it plainly. One of realism's frame statistics.
#pragma once

#include <cmath>

#include <opencv2/core.hpp>

namespace hoilcd {

// Blocks of this size, tiled from the top-left corner (a partial block at the right or bottom
// edge is left out).
constexpr int kFlatBlockPx = 16;
// The flattest share of the blocks (by their residual's std) is kept; at least one block.
constexpr double kFlatBlockShare = 0.1;

struct FlatNoise {
  int blocks = 0;       // blocks kept (0: the frame is smaller than one block)
  double std = NAN;     // median over the kept blocks of the residual's std, the frame's unit
  double lag1_x = NAN;  // the residual's lag-1 autocorrelation along x, pooled over the kept blocks
  double lag1_y = NAN;  // the same along y
  double lag1 = NAN;    // (lag1_x + lag1_y) / 2; NaN when the kept blocks' residual is zero (flat)
};

// `frame` (one channel, any depth, at the camera's own resolution: do not resize, the correlation
// is a per-pixel property) tiled into kFlatBlockPx blocks; a least-squares quadratic surface
// (1, x, y, x², y², xy) is subtracted from each; the kFlatBlockShare of blocks with the smallest
// residual std are kept. Each lag's correlation is Σ over kept blocks of mean(r·r_shifted) / Σ of
// mean(r²) (docs/results/2026-12-07-spectrum-slope/q_acf.py, flat_blocks and acf).
FlatNoise MeasureFlatNoise(const cv::Mat& frame);

}  // namespace hoilcd
