// A ground truth from what two frames share (`--ground-truth overlap`): the fraction of the
// query's static (non-person) pixels whose surface point, placed in the world with the true camera
// pose and the EXR depth, lands inside the reference's image, in front of its camera, at a depth
// the reference's own depth map agrees with. A reference at the same spot facing the other way
// shares nothing; one 2 m away looking at the same table shares most of it.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "hoilcd/bench/evaluation/protocol.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/geometry/camera.h"

namespace hoilcd {

// What one frame contributes to the overlap: as a query, its sampled static pixels as world
// points; as a reference, its depth map and where its camera is.
struct OverlapView {
  Rigid3 cam_from_world;
  std::vector<Eigen::Vector3f> static_points_world;  // every stride_px-th pixel (rows and columns)
  cv::Mat depth_m;  // CV_32F, Z along the optical axis; +inf (or <= 0) where nothing was hit
};

// `depth_m` and `class_id` (CV_32F, as ReadDatasetExr gives them) of one frame seen from
// `world_from_cam`; the pixels of class `person_class`, and those with no finite positive depth,
// are not static. `stride_px` >= 1.
OverlapView MakeOverlapView(const cv::Mat& depth_m, const cv::Mat& class_id, int person_class,
                            const CameraIntrinsics& intrinsics, const Rigid3& world_from_cam, int stride_px);

// The fraction (0..1) of query.static_points_world that the reference sees: projected into the
// reference's image within its pixel centres' span, at a depth z with
//   min(d) - tolerance <= z <= max(d) + tolerance,
// d the reference's depths at the four pixel centres around the projection (so a slanted floor
// or an edge between two surfaces is not a mismatch), tolerance = depth_tolerance_m. A point
// behind something the reference sees nearer (a person, a table) is not shared. 0 when the query
// has no static pixel.
double OverlapFraction(const OverlapView& query, const OverlapView& reference, const CameraIntrinsics& intrinsics,
                       double depth_tolerance_m);

// Every (query, database frame) pair of `queries` labelled by overlap: a true match when
// OverlapFraction >= options.overlap_threshold. Reads the EXRs of the queries and their
// databases (InputError naming the missing output when the dataset has none; the allocation is
// checked first). `threads`: 0 = every CPU. Deterministic at any thread count.
std::vector<Query> OverlapLabels(const Dataset& dataset, const std::vector<Query>& queries,
                                 const ProtocolOptions& options, int threads = 0);

}  // namespace hoilcd
