// The RANSAC loop's templates, declared in ransac.h (include that): the stream of hypotheses
// (draw, screen, queue, solve, up to `trials`), the best-model search with its LO-RANSAC refits,
// and the two drivers RunRansac and RansacVariants.
#pragma once

#include "hoilcd/core/optim/ransac.h"
#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace internal {

// Hypotheses kept between drawing and scoring. Small, so that a search that is complete (every
// match an inlier) stops drawing soon: 16 saved ~7 % of the point-set methods' CPU over 128.
constexpr int kRansacChunk = 16;
static_assert(kRansacChunk >= kRansacLanes, "HypothesisStream::Next needs room for a solved batch");

// The hypotheses of one RANSAC stream, in draw order: samples are drawn eight at a time, those that
// pass E's screening are queued in draw order and solved eight at a time, and each valid solution
// is a hypothesis, up to options.trials of them. The stream depends only on the matches, the seed,
// trials and redraw_degenerate_samples: variants that differ only in their threshold or refits
// score the same hypotheses.
template <typename E>
class HypothesisStream {
 public:
  HypothesisStream(const typename E::Data& data, const RansacOptions& options, uint64_t seed)
      : data_(&data),
        sampler_(seed, static_cast<uint32_t>(data.count), E::kSampleSize),
        trials_(options.trials),
        // With exactly kSampleSize matches every sample is the same set: one draw decides.
        budget_(data.count == E::kSampleSize ? 1
                                             : static_cast<int64_t>(options.trials) *
                                                   (options.redraw_degenerate_samples ? kRansacMaxDrawsPerTrial : 1)) {}

  // Writes the next hypotheses to out (kModelSize floats each), at most max >= kRansacLanes of
  // them, and returns how many.
  int Next(int max, float* out) {
    int n = 0;
    while (n + kRansacLanes <= max && !Done()) {
      if (draws_ >= budget_) {  // the last, partly filled queue
        n += Solve(queued_, out + E::kModelSize * n);
        queued_ = 0;
        break;
      }
      const int size = static_cast<int>(std::min<int64_t>(kRansacLanes, budget_ - draws_));
      SampleBatch drawn;
      int32_t keep[kRansacLanes];
      E::DrawAndScreen(sampler_, static_cast<uint32_t>(draws_), *data_, &drawn, keep);
      draws_ += size;
      for (int b = 0; b < size; ++b) {
        // Branch-free queueing: every sample is copied, only kept ones advance the queue.
        for (int k = 0; k < E::kSampleSize; ++k) pending_[k][queued_] = drawn[k][b];
        queued_ -= keep[b];             // a kept lane holds -1
        if (queued_ == kRansacLanes) {  // at most once per drawn batch, so n stays within max
          n += Solve(kRansacLanes, out + E::kModelSize * n);
          queued_ = 0;
        }
      }
    }
    return n;
  }

  // No hypothesis is left: trials are in, or every draw is spent and solved.
  bool Done() const { return produced_ >= trials_ || (draws_ >= budget_ && queued_ == 0); }

 private:
  // Solves the first `size` queued samples; writes the valid ones, up to the trials left.
  int Solve(int size, float* out) {
    ModelBatch<E::kModelSize> solved;
    E::Solve(pending_, *data_, &solved);
    int n = 0;
    for (int b = 0; b < size && produced_ < trials_; ++b) {
      if (!solved.valid[b]) continue;
      for (int k = 0; k < E::kModelSize; ++k) out[E::kModelSize * n + k] = solved.model[k][b];
      ++n;
      ++produced_;
    }
    return n;
  }

  const typename E::Data* data_;
  RansacSampler sampler_;
  int trials_;
  int64_t budget_;
  int64_t draws_ = 0;
  int produced_ = 0;
  SampleBatch pending_ = {};  // unused lanes keep index 0, a valid match
  int queued_ = 0;
};

// One variant's search over a stream: the best model so far and its inlier count, with the
// LO-RANSAC refits of each new best model. lo_mask is scratch (kept between calls by its owner).
template <typename E>
class BestModelSearch {
 public:
  void Start(const typename E::Data& data, const RansacOptions& options, std::vector<uint8_t>* lo_mask) {
    data_ = &data;
    threshold_sq_ = static_cast<float>(options.inlier_threshold_px * options.inlier_threshold_px);
    refits_ = options.local_optimisation_refits;
    lo_mask_ = lo_mask;
    std::copy(E::kNoModel, E::kNoModel + E::kModelSize, best_);
    best_inliers_ = 0;
  }

  // Scores n hypotheses in order, up to the first that makes the search complete.
  void Score(const float* hypotheses, int n) {
    for (int i = 0; i < n && !Complete(); ++i) {
      float model[E::kModelSize];
      std::copy(hypotheses + E::kModelSize * i, hypotheses + E::kModelSize * (i + 1), model);
      const int inliers = E::CountInliers(model, *data_, threshold_sq_, best_inliers_);
      if (inliers <= best_inliers_) continue;
      Keep(model, inliers);
      if (refits_ > 0 && inliers > E::kSampleSize) Refine(model);
    }
  }

  int inliers() const { return best_inliers_; }
  // Every match is an inlier of the best model: no later hypothesis or refit can beat it (a new
  // best needs strictly more inliers), so the rest of the stream cannot change the result.
  bool Complete() const { return best_inliers_ >= data_->count; }
  const float* best() const { return best_; }

 private:
  void Keep(const float* model, int inliers) {
    best_inliers_ = inliers;
    std::copy(model, model + E::kModelSize, best_);
  }

  // LO-RANSAC: refits to the inliers of the new best model while each refit gains inliers.
  void Refine(float* model) {
    lo_mask_->resize(data_->count);
    E::MarkInliers(model, *data_, threshold_sq_, lo_mask_->data());
    for (int refit = 0; refit < refits_; ++refit) {
      if (!E::Refit(*data_, lo_mask_->data(), model)) break;
      const int refit_inliers = E::CountInliers(model, *data_, threshold_sq_, best_inliers_);
      if (refit_inliers <= best_inliers_) break;
      Keep(model, refit_inliers);
      E::MarkInliers(model, *data_, threshold_sq_, lo_mask_->data());
    }
  }

  const typename E::Data* data_ = nullptr;
  float threshold_sq_ = 0;
  int refits_ = 0;
  std::vector<uint8_t>* lo_mask_ = nullptr;
  float best_[E::kModelSize] = {};
  int best_inliers_ = 0;
};

// Variants score one stream when they draw the same samples.
inline bool SameStream(const RansacOptions& a, const RansacOptions& b) {
  return a.trials == b.trials && a.redraw_degenerate_samples == b.redraw_degenerate_samples;
}

}  // namespace internal

// Hand-written rather than a library's (cv::findHomography): the paper runs exactly N trials, while
// OpenCV stops adaptively and refines the model afterwards.
template <typename E>
int RunRansac(const typename E::Data& data, const RansacOptions& options, uint64_t seed, float* best_model) {
  if (data.count < E::kSampleSize) {
    std::copy(E::kNoModel, E::kNoModel + E::kModelSize, best_model);
    return 0;
  }
  internal::HypothesisStream<E> stream(data, options, seed);
  std::vector<uint8_t> lo_mask;
  internal::BestModelSearch<E> search;
  search.Start(data, options, &lo_mask);
  float hypotheses[E::kModelSize * internal::kRansacChunk];
  while (!stream.Done() && !search.Complete()) {
    const int n = stream.Next(internal::kRansacChunk, hypotheses);
    search.Score(hypotheses, n);
  }
  std::copy(search.best(), search.best() + E::kModelSize, best_model);
  return search.inliers();
}

// The timing interleaves with the scoring (each variant is charged its share as it goes), which
// keeps the groups, the early stop and the clock in one function.
template <typename E>
template <typename Prepare>
void RansacVariants<E>::Count(int count, const Prepare& prepare, const RansacOptions* variants, int num_variants,
                              uint64_t seed, int* inliers, int64_t* alone_ns, int64_t* total_ns) {
  const bool timed = alone_ns != nullptr;
  HOILCD_CHECK_MSG(!timed || total_ns != nullptr, "alone_ns needs total_ns");
  hypotheses_scored_ = 0;
  if (timed) {
    std::fill(alone_ns, alone_ns + num_variants, int64_t{0});
    *total_ns = 0;
  }
  if (count < E::kSampleSize) {
    std::fill(inliers, inliers + num_variants, 0);
    return;
  }
  using Clock = std::chrono::steady_clock;
  const auto elapsed_ns = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(b - a).count();
  };
  const Clock::time_point start = timed ? Clock::now() : Clock::time_point();
  Clock::time_point last = start;  // preparing the data counts as the first stream's drawing
  const typename E::Data data = prepare();
  if (lo_masks_.size() < static_cast<size_t>(num_variants)) lo_masks_.resize(num_variants);
  scored_.assign(num_variants, 0);  // 1 once a variant is in a group
  hypotheses_.resize(E::kModelSize * internal::kRansacChunk);
  // Groups of variants on one stream, in order: the first variant not yet scored and every later
  // one on the same stream, at most kMaxSharing at once (a larger group draws its stream again).
  constexpr int kMaxSharing = 8;
  for (int first = 0; first < num_variants; ++first) {
    if (scored_[first]) continue;
    int group[kMaxSharing], size = 0;
    internal::BestModelSearch<E> searches[kMaxSharing];
    for (int v = first; v < num_variants && size < kMaxSharing; ++v) {
      if (scored_[v] || !internal::SameStream(variants[first], variants[v])) continue;
      scored_[v] = 1;
      searches[size].Start(data, variants[v], &lo_masks_[v]);
      group[size++] = v;
    }
    internal::HypothesisStream<E> stream(data, variants[first], seed);
    const auto complete = [&] {
      return std::all_of(searches, searches + size, [](const internal::BestModelSearch<E>& s) { return s.Complete(); });
    };
    while (!stream.Done() && !complete()) {
      const int n = stream.Next(internal::kRansacChunk, hypotheses_.data());
      hypotheses_scored_ += n;
      Clock::time_point now;
      int64_t drawing_ns = 0;
      if (timed) {
        now = Clock::now();
        drawing_ns = elapsed_ns(last, now);
        last = now;
      }
      for (int g = 0; g < size; ++g) {
        searches[g].Score(hypotheses_.data(), n);
        if (!timed) continue;
        now = Clock::now();
        alone_ns[group[g]] += drawing_ns + elapsed_ns(last, now);
        last = now;
      }
    }
    for (int g = 0; g < size; ++g) inliers[group[g]] = searches[g].inliers();
  }
  if (timed) *total_ns = elapsed_ns(start, last);
}

}  // namespace hoilcd
