// A global-image baseline in the spirit of SeqSLAM (Milford & Wyeth 2012): each thermal frame
// becomes a tiny patch-normalised thumbnail, frames are compared by normalised cross-correlation,
// and an optional sequence search scores straight trajectories through the similarity matrix.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// Defaults and ranges: Table() in thumbnail_baseline.cpp.
struct ThumbnailOptions {
  int width_px;   // thumbnail width after area downsampling, px
  int height_px;  // thumbnail height after area downsampling, px
  int patch_px;   // side of the square patches normalised to zero mean / unit variance,
                  // thumbnail px (SeqSLAM's patch normalisation); edge patches may be smaller

  ThumbnailOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<ThumbnailOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
  // "" when a thumbnail of this size fits in a width x height image (area downsampling only
  // shrinks), else the problem ("width_px: must be at most the image width, 256 px").
  std::string CheckImage(int width_px, int height_px) const;
  // Bytes of the descriptors of `frames` frames (floats, width_px x height_px each).
  double DatabaseBytes(int frames) const;
};

// The descriptor of one 8-bit frame (CV_8UC1): area-downsampled to width x height, every patch
// shifted and scaled to zero mean and unit variance (a flat patch becomes all zeros), flattened
// row-major, then the whole vector centred and scaled to unit length. The dot product of two
// descriptors is therefore their normalised cross-correlation, in [-1, 1]; an all-zero descriptor
// (a featureless frame) correlates 0 with everything, itself included.
std::vector<float> ThumbnailDescriptor(const cv::Mat& thermal_u8, const ThumbnailOptions& options);

// Normalised cross-correlation of two descriptors of equal length (their dot product), summed in
// a fixed order so a pair's score is bit-identical whichever call computes it.
float ThumbnailSimilarity(const std::vector<float>& a, const std::vector<float>& b);

class ThumbnailIndex {
 public:
  explicit ThumbnailIndex(ThumbnailOptions options = {});
  // Frame ids are 0..size-1 in Add order.
  void Add(const cv::Mat& thermal_u8);
  // A descriptor made by ThumbnailDescriptor with this index's options (e.g. computed in parallel).
  void AddDescriptor(std::vector<float> descriptor);
  int size() const { return static_cast<int>(descriptors_.size()); }
  const std::vector<float>& descriptor(int frame) const;

  // scores[i][j] = ThumbnailSimilarity(frame queries[i], frame database[j]) in [-1, 1], higher
  // is more similar; parallel over query rows (threads 0 = all cores), identical at any thread
  // count. ScoreAll(all, all, threads) gives the dense frame-by-frame matrix SequenceScores takes.
  // Throws InputError when the matrix needs more memory than this process may allocate.
  std::vector<std::vector<float>> ScoreAll(const std::vector<int>& queries, const std::vector<int>& database,
                                           int threads) const;

 private:
  ThumbnailOptions options_;
  std::vector<std::vector<float>> descriptors_;
};

// SeqSLAM's trajectory search. v is database frames advanced per query frame.
// Defaults and ranges: Table() in thumbnail_baseline.cpp.
struct SeqSlamOptions {
  int sequence_length;  // frames along each trajectory, the end point included (SeqSLAM ds)
  double min_velocity;  // slowest trajectory, database frames per query frame
  double max_velocity;  // fastest trajectory, database frames per query frame
  int velocity_steps;   // trajectories tried, evenly spaced in [min, max]; 1 = the midpoint

  SeqSlamOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<SeqSlamOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// `similarity[i][j]`: single-frame similarity of query-timeline frame i and database-timeline
// frame j, both consecutive in time (e.g. the dense all-frames matrix, rows = cols = frames).
// Returns a matrix of the same shape: out[i][j] = max over velocities v of the mean of
// similarity[i - k][j - round(v k)] for k = 0..sequence_length-1, the line ending at (i, j); a
// sequence_length beyond the rows counts as the rows there are. Throws InputError when the result
// needs more memory than this process may allocate.
// Near the first rows a line is shortened to the rows there are (every entry of the row alike);
// steps that leave the columns count as similarity 0 (NCC's "unrelated"), so a line cut short at
// the matrix edge cannot win on one lucky frame. Parallel over rows, deterministic.
std::vector<std::vector<float>> SequenceScores(const std::vector<std::vector<float>>& similarity,
                                               const SeqSlamOptions& options, int threads);

}  // namespace hoilcd
