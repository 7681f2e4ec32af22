// core/geometry as properties over keyed random draws (as Sophus tests its groups): Project and
// Unproject undo each other; Rigid3's inverse, composition and matrix agree with one another and
// with CameraPose::WorldFromCam, whose rotation is proper and orthonormal.
#include "hoilcd/core/geometry/camera.h"

#include <cmath>

#include <gtest/gtest.h>

#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

constexpr int kDraws = 1000;
constexpr uint64_t kSeed = 47;

Eigen::Vector3d RandomPoint(Rng& rng, double half_width_m) {
  return {rng.Uniform(-half_width_m, half_width_m), rng.Uniform(-half_width_m, half_width_m),
          rng.Uniform(-half_width_m, half_width_m)};
}

// A uniformly random rotation (a normalised Gaussian 4-vector) and a translation within 10 m.
Rigid3 RandomRigid(Rng& rng) {
  Rigid3 t;
  t.rotation = Eigen::Quaterniond(rng.Normal(), rng.Normal(), rng.Normal(), rng.Normal()).normalized();
  t.translation = RandomPoint(rng, 10.0);
  return t;
}

CameraIntrinsics RandomIntrinsics(Rng& rng) {
  CameraIntrinsics k =
      CameraIntrinsics::FromHorizontalFov(static_cast<int>(32 + rng.UniformInt(1000)),
                                          static_cast<int>(24 + rng.UniformInt(800)), rng.Uniform(10.0, 150.0));
  k.fy = k.fx * rng.Uniform(0.8, 1.25);  // non-square pixels and an off-centre principal point too
  k.cx += rng.Uniform(-5.0, 5.0);
  k.cy += rng.Uniform(-5.0, 5.0);
  return k;
}

void ExpectNear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tolerance) {
  EXPECT_LT((a - b).norm(), tolerance) << a.transpose() << " vs " << b.transpose();
}

TEST(Geometry, ProjectOfAnUnprojectedPixelAtAnyDepthIsThatPixel) {
  for (int i = 0; i < kDraws; ++i) {
    Rng rng = KeyedRng(kSeed, "test.project_unproject", i);
    const CameraIntrinsics k = RandomIntrinsics(rng);
    ASSERT_EQ(k.Check(), "");
    const double u = rng.Uniform(-0.5, k.width - 0.5), v = rng.Uniform(-0.5, k.height - 0.5);
    const double depth_m = rng.Uniform(0.05, 50.0);
    const Eigen::Vector3d ray = k.Unproject(u, v);
    EXPECT_EQ(ray.z(), 1.0);
    const Eigen::Vector2d back = k.Project(depth_m * ray);
    EXPECT_NEAR(back.x(), u, 1e-9) << i;
    EXPECT_NEAR(back.y(), v, 1e-9) << i;
  }
}

TEST(Geometry, UnprojectOfAProjectedPointTimesItsDepthIsThatPoint) {
  for (int i = 0; i < kDraws; ++i) {
    Rng rng = KeyedRng(kSeed, "test.unproject_project", i);
    const CameraIntrinsics k = RandomIntrinsics(rng);
    const Eigen::Vector3d point_in_cam(rng.Uniform(-20.0, 20.0), rng.Uniform(-20.0, 20.0), rng.Uniform(0.05, 50.0));
    const Eigen::Vector2d uv = k.Project(point_in_cam);
    ExpectNear(point_in_cam.z() * k.Unproject(uv.x(), uv.y()), point_in_cam, 1e-9 * point_in_cam.norm() + 1e-12);
  }
}

TEST(Geometry, TheCentresOfTheImageAndItsCornersProjectWhereTheFieldOfViewSays) {
  const CameraIntrinsics k = CameraIntrinsics::FromHorizontalFov(256, 192, 90.0);
  EXPECT_NEAR(k.HorizontalFovDeg(), 90.0, 1e-12);
  const Eigen::Vector2d centre = k.Project({0, 0, 3});
  EXPECT_NEAR(centre.x(), 127.5, 1e-12);
  EXPECT_NEAR(centre.y(), 95.5, 1e-12);
  // 45 degrees to the right lands on the right edge of the image (pixel 255's far side).
  EXPECT_NEAR(k.Project({1, 0, 1}).x(), 255.5, 1e-12);
}

TEST(Geometry, ARigidTransformComposedWithItsInverseIsTheIdentityBothWays) {
  for (int i = 0; i < kDraws; ++i) {
    Rng rng = KeyedRng(kSeed, "test.rigid_inverse", i);
    const Rigid3 b_from_a = RandomRigid(rng);
    const Eigen::Vector3d p = RandomPoint(rng, 10.0);
    ExpectNear(b_from_a.Inverse() * (b_from_a * p), p, 1e-12 * 20);
    ExpectNear(b_from_a * (b_from_a.Inverse() * p), p, 1e-12 * 20);
    for (const Rigid3& identity : {b_from_a * b_from_a.Inverse(), b_from_a.Inverse() * b_from_a}) {
      EXPECT_LT(identity.rotation.angularDistance(Eigen::Quaterniond::Identity()), 1e-7) << i;
      EXPECT_LT(identity.translation.norm(), 1e-12 * 20) << i;
    }
    EXPECT_LT((b_from_a.Inverse().Inverse().Matrix() - b_from_a.Matrix()).cwiseAbs().maxCoeff(), 1e-12) << i;
  }
}

TEST(Geometry, CompositionIsAssociativeActsAsSuccessiveTransformsAndInvertsInReverseOrder) {
  for (int i = 0; i < kDraws; ++i) {
    Rng rng = KeyedRng(kSeed, "test.rigid_compose", i);
    const Rigid3 c_from_b = RandomRigid(rng), b_from_a = RandomRigid(rng), a_from_w = RandomRigid(rng);
    const Eigen::Vector3d p = RandomPoint(rng, 10.0);
    const double tolerance = 1e-11;
    ExpectNear((c_from_b * b_from_a) * p, c_from_b * (b_from_a * p), tolerance);
    ExpectNear(((c_from_b * b_from_a) * a_from_w) * p, (c_from_b * (b_from_a * a_from_w)) * p, tolerance);
    const Rigid3 inverse = (c_from_b * b_from_a).Inverse(), reversed = b_from_a.Inverse() * c_from_b.Inverse();
    ExpectNear(inverse * p, reversed * p, tolerance);
    // The 4 x 4 matrices compose and invert as the transforms do.
    EXPECT_LT(((c_from_b * b_from_a).Matrix() - c_from_b.Matrix() * b_from_a.Matrix()).cwiseAbs().maxCoeff(),
              tolerance);
    EXPECT_LT((b_from_a.Inverse().Matrix() - b_from_a.Matrix().inverse()).cwiseAbs().maxCoeff(), tolerance);
    const Eigen::Vector4d h = b_from_a.Matrix() * p.homogeneous();
    ExpectNear(h.head<3>(), b_from_a * p, tolerance);
    EXPECT_EQ(h.w(), 1.0);
  }
}

TEST(Geometry, WorldFromCamIsAProperRotationAndItsInverseTakesTheCameraCentreToTheOrigin) {
  for (int i = 0; i < kDraws; ++i) {
    Rng rng = KeyedRng(kSeed, "test.world_from_cam", i);
    CameraPose pose;
    pose.x_m = rng.Uniform(-10.0, 10.0), pose.y_m = rng.Uniform(-10.0, 10.0), pose.z_m = rng.Uniform(0.0, 3.0);
    pose.yaw_rad = rng.Uniform(-M_PI, M_PI), pose.pitch_rad = rng.Uniform(-1.5, 1.5),
    pose.roll_rad = rng.Uniform(-1.0, 1.0);
    const Rigid3 world_from_cam = pose.WorldFromCam();
    const Eigen::Matrix3d r = world_from_cam.rotation.toRotationMatrix();
    EXPECT_LT((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-12) << i;
    EXPECT_NEAR(r.determinant(), 1.0, 1e-12) << i;
    const Eigen::Vector3d centre(pose.x_m, pose.y_m, pose.z_m);
    ExpectNear(world_from_cam.Inverse() * centre, Eigen::Vector3d::Zero(), 1e-12 * 20);
    // Looking along the camera's z is looking along the body's x: yaw and pitch, whatever the roll.
    const Eigen::Vector3d forward = world_from_cam.rotation * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d expected(std::cos(pose.yaw_rad) * std::cos(pose.pitch_rad),
                                   std::sin(pose.yaw_rad) * std::cos(pose.pitch_rad), -std::sin(pose.pitch_rad));
    ExpectNear(forward, expected, 1e-12);
    // A point in front of the camera projects into its image; through the inverse pose it comes back.
    const CameraIntrinsics k;
    const Eigen::Vector3d point_in_world = world_from_cam * Eigen::Vector3d(0.3, -0.2, 2.0);
    const Eigen::Vector3d point_in_cam = world_from_cam.Inverse() * point_in_world;
    const Eigen::Vector2d uv = k.Project(point_in_cam);
    ExpectNear(world_from_cam * (point_in_cam.z() * k.Unproject(uv.x(), uv.y())), point_in_world, 1e-9);
  }
}

}  // namespace
}  // namespace hoilcd
