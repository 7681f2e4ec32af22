#include "hoilcd/bench/evaluation/overlap.h"

#include <cmath>

#include <gtest/gtest.h>

#include "../../common/input_error_of.h"
#include "../../common/test_dir.h"
#include "../../common/tiny_room.h"
#include "hoilcd/bench/evaluation/evaluate.h"
#include "hoilcd/core/dataset/exr_io.h"

namespace hoilcd {
namespace {

constexpr int kWall = 3, kPerson = 7;

// The default 256 x 192 camera (f = 274.5 px, principal point at the centre).
CameraIntrinsics Camera() { return CameraIntrinsics(); }

// A camera at (x, y, 1 m) looking along world +x, turned by yaw.
Rigid3 CameraAt(double x_m, double y_m, double yaw_rad = 0) {
  CameraPose pose;
  pose.x_m = x_m;
  pose.y_m = y_m;
  pose.z_m = 1.0;
  pose.yaw_rad = yaw_rad;
  return pose.WorldFromCam();
}

cv::Mat Depth(float z_m) { return cv::Mat(192, 256, CV_32F, cv::Scalar(z_m)); }
cv::Mat Classes(int id) { return cv::Mat(192, 256, CV_32F, cv::Scalar(id)); }

// A query facing a wall 2 m ahead; the reference 0.5 m to the query's right (world -y) sees the
// same wall shifted by f * 0.5 / 2 = 68.625 px, so the query's columns u >= 68.625 stay in view:
// u = 69..255, 187 of 256 columns.
TEST(Overlap, ASidewaysShiftSharesTheColumnsStillInViewAsComputedByHand) {
  const OverlapView query = MakeOverlapView(Depth(2), Classes(kWall), kPerson, Camera(), CameraAt(0, 0), 1);
  const OverlapView reference = MakeOverlapView(Depth(2), Classes(kWall), kPerson, Camera(), CameraAt(0, -0.5), 1);
  EXPECT_EQ(query.static_points_world.size(), 256u * 192u);
  EXPECT_DOUBLE_EQ(OverlapFraction(query, reference, Camera(), 0.05), 187.0 / 256.0);
  // Sampled every 4th pixel: columns 72, 76, ..., 252 of 0, 4, ..., 252: 46 of 64.
  const OverlapView sparse = MakeOverlapView(Depth(2), Classes(kWall), kPerson, Camera(), CameraAt(0, 0), 4);
  EXPECT_DOUBLE_EQ(OverlapFraction(sparse, reference, Camera(), 0.05), 46.0 / 64.0);
  // A view shares all of itself.
  EXPECT_DOUBLE_EQ(OverlapFraction(query, query, Camera(), 0.05), 1.0);
}

// Within the paper's 0.2 m, but facing the other way: a wall the reference never saw.
TEST(Overlap, AReferenceAtTheSameSpotFacingAwaySharesNothing) {
  const OverlapView query = MakeOverlapView(Depth(2), Classes(kWall), kPerson, Camera(), CameraAt(1, 1), 1);
  const OverlapView behind = MakeOverlapView(Depth(2), Classes(kWall), kPerson, Camera(), CameraAt(1.1, 1, M_PI), 1);
  EXPECT_DOUBLE_EQ(OverlapFraction(query, behind, Camera(), 0.05), 0.0);
  // Turned by 90 degrees the wall is off to the side, out of the 50-degree field of view.
  const OverlapView side = MakeOverlapView(Depth(2), Classes(kWall), kPerson, Camera(), CameraAt(1, 1, M_PI / 2), 1);
  EXPECT_DOUBLE_EQ(OverlapFraction(query, side, Camera(), 0.05), 0.0);
}

// Something nearer the reference (1 m) covers its left half: the wall behind it is not seen.
// Reference column u_r = u - 68.625 is seen when a depth among its two neighbouring columns is the
// wall's: u_r >= 127, so u >= 195.625, columns 196..255.
TEST(Overlap, WhatIsHiddenBehindANearerSurfaceInTheReferenceIsNotShared) {
  const OverlapView query = MakeOverlapView(Depth(2), Classes(kWall), kPerson, Camera(), CameraAt(0, 0), 1);
  cv::Mat depth = Depth(2);
  depth(cv::Rect(0, 0, 128, 192)).setTo(1.0f);
  const OverlapView reference = MakeOverlapView(depth, Classes(kWall), kPerson, Camera(), CameraAt(0, -0.5), 1);
  EXPECT_DOUBLE_EQ(OverlapFraction(query, reference, Camera(), 0.05), 60.0 / 256.0);
  // A tolerance wider than the step makes the near surface consistent again.
  EXPECT_DOUBLE_EQ(OverlapFraction(query, reference, Camera(), 1.5), 187.0 / 256.0);
}

TEST(Overlap, PersonPixelsAndPixelsWithoutDepthAreNotStatic) {
  cv::Mat classes = Classes(kWall);
  classes(cv::Rect(0, 0, 256, 96)).setTo(kPerson);
  cv::Mat depth = Depth(2);
  depth(cv::Rect(0, 96, 128, 96)).setTo(std::numeric_limits<float>::infinity());
  const OverlapView query = MakeOverlapView(depth, classes, kPerson, Camera(), CameraAt(0, 0), 1);
  EXPECT_EQ(query.static_points_world.size(), 128u * 96u);
  const OverlapView nothing = MakeOverlapView(Depth(2), Classes(kPerson), kPerson, Camera(), CameraAt(0, 0), 1);
  EXPECT_TRUE(nothing.static_points_world.empty());
  EXPECT_DOUBLE_EQ(OverlapFraction(nothing, query, Camera(), 0.05), 0.0);
}

// A slanted floor changes depth fast from pixel to pixel at a grazing angle; the four neighbours'
// depth range keeps it consistent without a loose tolerance.
TEST(Overlap, ASlantedFloorSeenFromNearbyIsShared) {
  const CameraIntrinsics k = Camera();
  // Camera 1 m above a floor, looking along +x: floor rows v > cy at depth z = f / (v - cy).
  cv::Mat depth = Depth(std::numeric_limits<float>::infinity());
  for (int v = 96; v < 192; ++v) depth.row(v).setTo(static_cast<float>(k.fy / (v - k.cy)));
  const OverlapView query = MakeOverlapView(depth, Classes(kWall), kPerson, k, CameraAt(0, 0), 1);
  const OverlapView reference = MakeOverlapView(depth, Classes(kWall), kPerson, k, CameraAt(0.05, 0), 1);
  // 5 cm forward, every floor point in view of the query stays in view except the nearest rows.
  EXPECT_GT(OverlapFraction(query, reference, k, 0.01), 0.9);
}

TEST(Overlap, LabelsOfARenderedRoomAgreeWithPositionsWhereTheyShouldAndAreDeterministic) {
  const test::TestDir temp;
  const Dataset dataset = test::TinyRoomDataset(temp / "dataset");
  ProtocolOptions protocol;
  protocol.ground_truth = "overlap";
  const Labelling one = LabelQueries(dataset, protocol, 1);
  const Labelling two = LabelQueries(dataset, protocol, 2);
  ASSERT_EQ(one.queries.size(), two.queries.size());
  int64_t true_pairs = 0;
  for (size_t i = 0; i < one.queries.size(); ++i) {
    EXPECT_EQ(one.queries[i].is_true_match, two.queries[i].is_true_match);
    true_pairs += one.queries[i].NumTrueMatches();
  }
  EXPECT_GT(true_pairs, 0);
  // The three ground truths are compared pairwise, over the same pairs.
  ASSERT_EQ(one.agreements.size(), 3u);
  EXPECT_EQ(one.agreements[1].a, "overlap");
  EXPECT_EQ(one.agreements[1].b, "odometry");
  EXPECT_EQ(one.agreements[1].counts.pairs_true_in_a, true_pairs);
  for (const LabelAgreement& g : one.agreements) {
    EXPECT_EQ(g.counts.pairs_true_in_a - g.counts.pairs_only_in_a, g.counts.pairs_true_in_b - g.counts.pairs_only_in_b);
  }
  // The labels are OverlapFraction >= threshold, pair by pair (checked on the first queries).
  const auto view_of = [&](int frame) {
    const ExrChannels channels = ReadDatasetExr(dataset, frame);
    cv::Mat depth, classes;
    for (const auto& [name, image] : channels) {
      if (name == "Z") depth = image;
      if (name == "class") classes = image;
    }
    return MakeOverlapView(depth, classes, dataset.manifest().classes.at("person"), dataset.manifest().intrinsics,
                           dataset.poses()[frame].Camera().WorldFromCam(), protocol.overlap_stride_px);
  };
  for (size_t i = 0; i < 3 && i < one.queries.size(); ++i) {
    const Query& q = one.queries[i];
    const OverlapView query = view_of(q.frame);
    for (size_t j = 0; j < q.database.size(); j += 7) {
      const double shared = OverlapFraction(query, view_of(q.database[j]), dataset.manifest().intrinsics,
                                            protocol.overlap_depth_tolerance_m);
      EXPECT_EQ(q.is_true_match[j], shared >= protocol.overlap_threshold ? 1 : 0) << shared;
    }
  }
  // A pair at the same true spot and heading shares most of its view: true under overlap.
  const std::vector<PoseRecord>& poses = dataset.poses();
  for (size_t i = 0; i < one.queries.size(); ++i) {
    const Query& q = one.queries[i];
    for (size_t j = 0; j < q.database.size(); ++j) {
      const PoseRecord& a = poses[q.frame];
      const PoseRecord& b = poses[q.database[j]];
      if (std::hypot(a.cam_x_m - b.cam_x_m, a.cam_y_m - b.cam_y_m) < 0.02 &&
          std::abs(std::remainder(a.cam_yaw_rad - b.cam_yaw_rad, 2 * M_PI)) < 0.02) {
        EXPECT_EQ(q.is_true_match[j], 1) << "query " << q.frame << " reference " << q.database[j];
      }
    }
  }
}

TEST(Overlap, ADatasetWithoutEXRsIsRefusedNamingTheOutput) {
  const test::TestDir temp;
  const Scene scene = LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/tiny_room.json", {"frames=20"});
  SequenceOptions options;
  options.output_dir = temp / "no_exr";
  options.outputs = "thermal,persons";
  RenderSequence(scene, options);
  const Dataset dataset = Dataset::Open(options.output_dir);
  ProtocolOptions protocol;
  protocol.ground_truth = "overlap";
  const std::string error = test::InputErrorOf([&] { LabelQueries(dataset, protocol); });
  EXPECT_NE(error.find("no_exr"), std::string::npos) << error;
  EXPECT_NE(error.find("rendered without the 'exr' output"), std::string::npos) << error;
}

}  // namespace
}  // namespace hoilcd
