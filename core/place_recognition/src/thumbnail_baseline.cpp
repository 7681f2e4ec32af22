#include "hoilcd/core/place_recognition/thumbnail_baseline.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/memory.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/sizes.h"

namespace hoilcd {
namespace {

// Below this standard deviation (grey levels) a patch counts as flat and is set to zero.
constexpr double kFlatPatchStd = 1e-3;

void NormalisePatch(cv::Mat patch) {
  cv::Scalar mean, stddev;
  cv::meanStdDev(patch, mean, stddev);
  if (stddev[0] < kFlatPatchStd) {
    patch.setTo(0.0f);
  } else {
    patch.convertTo(patch, CV_32F, 1.0 / stddev[0], -mean[0] / stddev[0]);
  }
}

}  // namespace

ThumbnailOptions::ThumbnailOptions() { Table().FillDefaults(this); }

const OptionTable<ThumbnailOptions>& ThumbnailOptions::Table() {
  using O = ThumbnailOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          // No larger than the camera image can be (the dataset's own image: CheckImage).
          .Add("width_px", &O::width_px, 32, "px", R::Closed(1, kMaxImageSidePx), "thumbnail width")
          .Add("height_px", &O::height_px, 24, "px", R::Closed(1, kMaxImageSidePx), "thumbnail height")
          .Add("patch_px", &O::patch_px, 8, "px", R::Closed(1, kMaxImageSidePx),
               "side of the square patches normalised to zero mean and unit variance");
  return table;
}

std::string ThumbnailOptions::Check() const { return Table().FirstProblem(*this); }

std::string ThumbnailOptions::CheckImage(int image_width_px, int image_height_px) const {
  if (width_px > image_width_px) {
    return "width_px: must be at most the image width, " + std::to_string(image_width_px) + " px";
  }
  if (height_px > image_height_px) {
    return "height_px: must be at most the image height, " + std::to_string(image_height_px) + " px";
  }
  return "";
}

double ThumbnailOptions::DatabaseBytes(int frames) const {
  return static_cast<double>(frames) * width_px * height_px * sizeof(float);
}

std::vector<float> ThumbnailDescriptor(const cv::Mat& thermal_u8, const ThumbnailOptions& options) {
  HOILCD_CHECK_MSG(options.Check().empty(), options.Check());
  HOILCD_CHECK_MSG(thermal_u8.type() == CV_8UC1 && !thermal_u8.empty(),
                   "ThumbnailDescriptor needs a non-empty CV_8UC1 image");
  cv::Mat image_f32;
  thermal_u8.convertTo(image_f32, CV_32F);
  cv::Mat thumbnail;
  cv::resize(image_f32, thumbnail, cv::Size(options.width_px, options.height_px), 0, 0, cv::INTER_AREA);
  for (int y = 0; y < thumbnail.rows; y += options.patch_px) {
    for (int x = 0; x < thumbnail.cols; x += options.patch_px) {
      const cv::Rect patch(x, y, std::min(options.patch_px, thumbnail.cols - x),
                           std::min(options.patch_px, thumbnail.rows - y));
      NormalisePatch(thumbnail(patch));
    }
  }
  std::vector<float> descriptor(thumbnail.begin<float>(), thumbnail.end<float>());
  double sum = 0.0;
  for (float v : descriptor) sum += v;
  const float mean = static_cast<float>(sum / static_cast<double>(descriptor.size()));
  double norm_sq = 0.0;
  for (float& v : descriptor) {
    v -= mean;
    norm_sq += static_cast<double>(v) * v;
  }
  if (norm_sq < 1e-12) {
    std::fill(descriptor.begin(), descriptor.end(), 0.0f);
    return descriptor;
  }
  const float inv_norm = static_cast<float>(1.0 / std::sqrt(norm_sq));
  for (float& v : descriptor) v *= inv_norm;
  return descriptor;
}

float ThumbnailSimilarity(const std::vector<float>& a, const std::vector<float>& b) {
  HOILCD_CHECK_MSG(a.size() == b.size(), "descriptor lengths differ: " << a.size() << " vs " << b.size());
  // Eight independent partial sums in a fixed order: vectorises without -ffast-math and, unlike
  // a BLAS GEMM (which blocks by matrix size), gives the same bits for a pair in any call.
  constexpr size_t kLanes = 8;
  float partial[kLanes] = {};
  const size_t n = a.size();
  const size_t full = n - n % kLanes;
  for (size_t i = 0; i < full; i += kLanes) {
    for (size_t l = 0; l < kLanes; ++l) partial[l] += a[i + l] * b[i + l];
  }
  for (size_t i = full; i < n; ++i) partial[i - full] += a[i] * b[i];
  float sum = 0.0f;
  for (float p : partial) sum += p;
  return std::clamp(sum, -1.0f, 1.0f);
}

ThumbnailIndex::ThumbnailIndex(ThumbnailOptions options) : options_(options) {
  HOILCD_CHECK_MSG(options_.Check().empty(), options_.Check());
}

void ThumbnailIndex::Add(const cv::Mat& thermal_u8) {
  descriptors_.push_back(ThumbnailDescriptor(thermal_u8, options_));
}

void ThumbnailIndex::AddDescriptor(std::vector<float> descriptor) {
  HOILCD_CHECK_MSG(descriptor.size() == static_cast<size_t>(options_.width_px) * options_.height_px,
                   "descriptor of " << descriptor.size() << " values for a " << options_.width_px << "x"
                                    << options_.height_px << " thumbnail");
  descriptors_.push_back(std::move(descriptor));
}

const std::vector<float>& ThumbnailIndex::descriptor(int frame) const {
  HOILCD_CHECK_MSG(frame >= 0 && frame < size(), "frame " << frame << " not in the index");
  return descriptors_[static_cast<size_t>(frame)];
}

std::vector<std::vector<float>> ThumbnailIndex::ScoreAll(const std::vector<int>& queries,
                                                         const std::vector<int>& database, int threads) const {
  for (int frame : queries) descriptor(frame);
  for (int frame : database) descriptor(frame);
  CheckAllocation(static_cast<double>(queries.size()) * (database.size() * sizeof(float) + sizeof(std::vector<float>)),
                  "",
                  "the " + std::to_string(queries.size()) + " x " + std::to_string(database.size()) +
                      " thumbnail similarity matrix");
  std::vector<std::vector<float>> scores(queries.size(), std::vector<float>(database.size()));
  ParallelForChunks(static_cast<int64_t>(queries.size()), 8, ResolveThreadCount(threads),
                    [&](int64_t begin, int64_t end, int) {
                      for (int64_t i = begin; i < end; ++i) {
                        const auto& query = descriptors_[static_cast<size_t>(queries[i])];
                        auto& row = scores[static_cast<size_t>(i)];
                        for (size_t j = 0; j < database.size(); ++j) {
                          row[j] = ThumbnailSimilarity(query, descriptors_[static_cast<size_t>(database[j])]);
                        }
                      }
                    });
  return scores;
}

SeqSlamOptions::SeqSlamOptions() { Table().FillDefaults(this); }

const OptionTable<SeqSlamOptions>& SeqSlamOptions::Table() {
  using O = SeqSlamOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          // No longer than a sequence can be; longer than the sequence at hand counts as all of it.
          .Add("sequence_length", &O::sequence_length, 10, "frames", R::Closed(1, kMaxFrames),
               "frames along each trajectory, the end point included")
          // |v| * sequence_length stays far inside an int; a line faster than 1000 frames per frame
          // crosses a whole sequence in a few steps.
          .Add("min_velocity", &O::min_velocity, 0.8, "", R::Closed(-1000, 1000),
               "slowest trajectory, database frames per query frame")
          .Add("max_velocity", &O::max_velocity, 1.25, "", R::Closed(-1000, 1000),
               "fastest trajectory, database frames per query frame")
          .Rule("min_velocity",
                [](const O& o) { return o.min_velocity <= o.max_velocity ? "" : "must be at most max_velocity"; })
          // SeqSLAM tries a handful (5 by default); the search's time grows with their number.
          .Add("velocity_steps", &O::velocity_steps, 5, "", R::Closed(1, 100),
               "trajectories tried between the slowest and fastest velocity (1: the midpoint)");
  return table;
}

std::string SeqSlamOptions::Check() const { return Table().FirstProblem(*this); }

std::vector<std::vector<float>> SequenceScores(const std::vector<std::vector<float>>& similarity,
                                               const SeqSlamOptions& options, int threads) {
  HOILCD_CHECK_MSG(options.Check().empty(), options.Check());
  const int rows = static_cast<int>(similarity.size());
  const int cols = rows == 0 ? 0 : static_cast<int>(similarity[0].size());
  for (const auto& row : similarity) {
    HOILCD_CHECK_MSG(static_cast<int>(row.size()) == cols, "similarity rows differ in length");
  }
  // column_offsets[s][k]: how many database frames trajectory s moves back over k query frames.
  // A line never has more steps than there are rows.
  const int length = std::min(options.sequence_length, std::max(rows, 1));
  CheckAllocation(static_cast<double>(rows) * (static_cast<double>(cols) * sizeof(float) + sizeof(std::vector<float>)),
                  "", "the " + std::to_string(rows) + " x " + std::to_string(cols) + " sequence similarity matrix");
  std::vector<std::vector<int>> column_offsets(static_cast<size_t>(options.velocity_steps));
  for (int s = 0; s < options.velocity_steps; ++s) {
    const double v =
        options.velocity_steps == 1
            ? 0.5 * (options.min_velocity + options.max_velocity)
            : options.min_velocity + (options.max_velocity - options.min_velocity) * s / (options.velocity_steps - 1);
    for (int k = 0; k < length; ++k) {
      column_offsets[static_cast<size_t>(s)].push_back(static_cast<int>(std::lround(v * k)));
    }
  }
  std::vector<std::vector<float>> out(static_cast<size_t>(rows), std::vector<float>(static_cast<size_t>(cols)));
  ParallelForChunks(rows, 16, ResolveThreadCount(threads), [&](int64_t begin, int64_t end, int) {
    for (int64_t i = begin; i < end; ++i) {
      const int steps_in_rows = static_cast<int>(std::min<int64_t>(length, i + 1));
      for (int j = 0; j < cols; ++j) {
        float best = -std::numeric_limits<float>::infinity();
        for (const auto& offsets : column_offsets) {
          float sum = 0.0f;
          for (int k = 0; k < steps_in_rows; ++k) {
            const int c = j - offsets[static_cast<size_t>(k)];
            if (c < 0 || c >= cols) break;
            sum += similarity[static_cast<size_t>(i - k)][static_cast<size_t>(c)];
          }
          best = std::max(best, sum / static_cast<float>(steps_in_rows));
        }
        out[static_cast<size_t>(i)][static_cast<size_t>(j)] = best;
      }
    }
  });
  return out;
}

}  // namespace hoilcd
