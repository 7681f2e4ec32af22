#include "hoilcd/bench/evaluation/overlap.h"

#include <algorithm>
#include <cmath>

#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/memory.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/safe_text.h"

namespace hoilcd {
namespace {

// Points nearer the reference camera than this are behind it or on its lens: not seen.
constexpr float kNearestDepthM = 1e-3f;

bool HasDepth(float z) { return std::isfinite(z) && z > 0; }

}  // namespace

OverlapView MakeOverlapView(const cv::Mat& depth_m, const cv::Mat& class_id, int person_class,
                            const CameraIntrinsics& intrinsics, const Rigid3& world_from_cam, int stride_px) {
  HOILCD_CHECK(depth_m.type() == CV_32F && class_id.type() == CV_32F && depth_m.size() == class_id.size());
  HOILCD_CHECK(stride_px >= 1);
  OverlapView view;
  view.cam_from_world = world_from_cam.Inverse();
  view.depth_m = depth_m;
  for (int v = 0; v < depth_m.rows; v += stride_px) {
    for (int u = 0; u < depth_m.cols; u += stride_px) {
      const float z = depth_m.at<float>(v, u);
      if (!HasDepth(z) || static_cast<int>(class_id.at<float>(v, u)) == person_class) continue;
      const Eigen::Vector3d point_in_cam = intrinsics.Unproject(u, v) * static_cast<double>(z);
      view.static_points_world.push_back((world_from_cam * point_in_cam).cast<float>());
    }
  }
  return view;
}

namespace {

// Whether a world point is seen by one reference view (OverlapFraction's test).
class ReferenceView {
 public:
  ReferenceView(const OverlapView& reference, const CameraIntrinsics& k, double depth_tolerance_m)
      : rotation_(reference.cam_from_world.rotation.toRotationMatrix().cast<float>()),
        translation_(reference.cam_from_world.translation.cast<float>()),
        depth_(reference.depth_m),
        max_u_(static_cast<float>(depth_.cols - 1)),
        max_v_(static_cast<float>(depth_.rows - 1)),
        fx_(static_cast<float>(k.fx)),
        fy_(static_cast<float>(k.fy)),
        cx_(static_cast<float>(k.cx)),
        cy_(static_cast<float>(k.cy)),
        tolerance_(static_cast<float>(depth_tolerance_m)) {
    HOILCD_CHECK(depth_.type() == CV_32F && depth_.cols >= 2 && depth_.rows >= 2);
  }

  bool Sees(const Eigen::Vector3f& world) const {
    const Eigen::Vector3f p = rotation_ * world + translation_;
    if (p.z() < kNearestDepthM) return false;
    const float u = fx_ * p.x() / p.z() + cx_, v = fy_ * p.y() / p.z() + cy_;
    if (!(u >= 0 && u <= max_u_ && v >= 0 && v <= max_v_)) return false;
    const int u0 = std::min(static_cast<int>(u), depth_.cols - 2), v0 = std::min(static_cast<int>(v), depth_.rows - 2);
    float lowest = INFINITY, highest = -INFINITY;
    for (int dv = 0; dv < 2; ++dv) {
      const float* row = depth_.ptr<float>(v0 + dv) + u0;
      for (int du = 0; du < 2; ++du) {
        if (!HasDepth(row[du])) continue;
        lowest = std::min(lowest, row[du]);
        highest = std::max(highest, row[du]);
      }
    }
    return p.z() >= lowest - tolerance_ && p.z() <= highest + tolerance_;
  }

 private:
  Eigen::Matrix3f rotation_;
  Eigen::Vector3f translation_;
  const cv::Mat& depth_;
  float max_u_, max_v_, fx_, fy_, cx_, cy_, tolerance_;
};

// Whether OverlapFraction(query, reference) >= threshold, stopping as soon as the count decides it.
bool SharesAtLeast(const OverlapView& query, const OverlapView& reference, const CameraIntrinsics& k,
                   double depth_tolerance_m, double threshold) {
  const int64_t n = static_cast<int64_t>(query.static_points_world.size());
  if (n == 0) return false;
  // The fewest points seen that make seen / n >= threshold, by the same division as OverlapFraction.
  const auto enough = [&](int64_t seen) { return static_cast<double>(seen) / static_cast<double>(n) >= threshold; };
  int64_t needed = std::clamp<int64_t>(static_cast<int64_t>(std::ceil(threshold * static_cast<double>(n))), 0, n);
  while (needed > 0 && enough(needed - 1)) --needed;
  while (needed <= n && !enough(needed)) ++needed;
  if (needed > n) return false;
  const ReferenceView view(reference, k, depth_tolerance_m);
  int64_t seen = 0, unseen = 0;
  for (const Eigen::Vector3f& world : query.static_points_world) {
    if (view.Sees(world)) {
      if (++seen >= needed) return true;
    } else if (++unseen > n - needed) {
      return false;
    }
  }
  return seen >= needed;
}

}  // namespace

double OverlapFraction(const OverlapView& query, const OverlapView& reference, const CameraIntrinsics& intrinsics,
                       double depth_tolerance_m) {
  if (query.static_points_world.empty()) return 0;
  const ReferenceView view(reference, intrinsics, depth_tolerance_m);
  int64_t seen = 0;
  for (const Eigen::Vector3f& world : query.static_points_world) seen += view.Sees(world);
  return static_cast<double>(seen) / static_cast<double>(query.static_points_world.size());
}

std::vector<Query> OverlapLabels(const Dataset& dataset, const std::vector<Query>& queries,
                                 const ProtocolOptions& options, int threads) {
  if (!dataset.manifest().outputs.exr) {
    throw InputError(SafeText(dataset.dir()),
                     "EXR frames (the depth and class channels) for --ground-truth overlap; "
                     "the dataset was rendered without the 'exr' output");
  }
  const CameraIntrinsics& intrinsics = dataset.manifest().intrinsics;
  const int person_class = dataset.manifest().ClassId("person");
  // What each frame is needed as: a query (its points) and/or a reference (its depth map); each
  // needed frame is read once.
  enum Role : uint8_t { kQuery = 1, kReference = 2 };
  std::vector<uint8_t> roles(dataset.poses().size(), 0);
  for (const Query& q : queries) {
    roles.at(static_cast<size_t>(q.frame)) |= kQuery;
    for (int r : q.database) roles.at(static_cast<size_t>(r)) |= kReference;
  }
  std::vector<int> needed;
  for (size_t f = 0; f < roles.size(); ++f)
    if (roles[f] != 0) needed.push_back(static_cast<int>(f));
  const auto references = std::count_if(roles.begin(), roles.end(), [](uint8_t r) { return (r & kReference) != 0; });
  CheckAllocation(static_cast<double>(references) * intrinsics.width * intrinsics.height * sizeof(float),
                  "--ground-truth overlap", "the depth maps of " + std::to_string(references) + " reference frames");
  std::vector<OverlapView> views(roles.size());  // by frame; empty for frames not needed
  ParallelFor(static_cast<int64_t>(needed.size()), threads, [&](int64_t i) {
    const int frame = needed[static_cast<size_t>(i)];
    const ExrChannels channels = ReadDatasetExr(dataset, frame);
    const std::string path = DatasetExrPath(dataset, frame);
    OverlapView view =
        MakeOverlapView(ExrChannel(channels, "Z", path), ExrChannel(channels, "class", path), person_class, intrinsics,
                        dataset.poses()[static_cast<size_t>(frame)].Camera().WorldFromCam(), options.overlap_stride_px);
    if (!(roles[static_cast<size_t>(frame)] & kReference)) view.depth_m = cv::Mat();
    if (!(roles[static_cast<size_t>(frame)] & kQuery)) view.static_points_world = {};
    views[static_cast<size_t>(frame)] = std::move(view);
  });
  std::vector<Query> out = queries;
  ParallelFor(static_cast<int64_t>(out.size()), threads, [&](int64_t i) {
    Query& q = out[static_cast<size_t>(i)];
    const OverlapView& query = views[static_cast<size_t>(q.frame)];
    for (size_t j = 0; j < q.database.size(); ++j) {
      q.is_true_match[j] = SharesAtLeast(query, views[static_cast<size_t>(q.database[j])], intrinsics,
                                         options.overlap_depth_tolerance_m, options.overlap_threshold)
                               ? 1
                               : 0;
    }
  });
  return out;
}

}  // namespace hoilcd
