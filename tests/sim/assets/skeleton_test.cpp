#include "hoilcd/sim/assets/skeleton.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hoilcd/core/util/error.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

constexpr double kDeg = M_PI / 180.0;

const Skeleton& Shipped() {
  static AssetLibrary assets(ShippedAssetDir());
  static const Skeleton skeleton(assets);
  return skeleton;
}

void ExpectRigid(const std::array<Eigen::Matrix4d, Skeleton::kPartCount>& parts, const std::string& what) {
  for (int i = 0; i < Skeleton::kPartCount; ++i) {
    ASSERT_TRUE(parts[i].allFinite()) << what << ": " << Skeleton::PartNames()[i];
    const Eigen::Matrix3d r = parts[i].topLeftCorner<3, 3>();
    EXPECT_LT((r.transpose() * r - Eigen::Matrix3d::Identity()).norm(), 1e-9)
        << what << ": " << Skeleton::PartNames()[i];
    EXPECT_NEAR(r.determinant(), 1.0, 1e-9) << what;
  }
}

TEST(Skeleton, EachCocoKeypointConstantIndexesTheKeypointItNames) {
  const std::vector<std::pair<CocoKeypoint, std::string>> named = {{kNose, "nose"},
                                                                   {kLeftEye, "left_eye"},
                                                                   {kRightEye, "right_eye"},
                                                                   {kLeftEar, "left_ear"},
                                                                   {kRightEar, "right_ear"},
                                                                   {kLeftShoulder, "left_shoulder"},
                                                                   {kRightShoulder, "right_shoulder"},
                                                                   {kLeftElbow, "left_elbow"},
                                                                   {kRightElbow, "right_elbow"},
                                                                   {kLeftWrist, "left_wrist"},
                                                                   {kRightWrist, "right_wrist"},
                                                                   {kLeftHip, "left_hip"},
                                                                   {kRightHip, "right_hip"},
                                                                   {kLeftKnee, "left_knee"},
                                                                   {kRightKnee, "right_knee"},
                                                                   {kLeftAnkle, "left_ankle"},
                                                                   {kRightAnkle, "right_ankle"}};
  ASSERT_EQ(named.size(), static_cast<size_t>(kCocoKeypointCount));
  for (const auto& [k, name] : named) EXPECT_EQ(kCocoKeypointNames[k], name);
  // A side's keypoint is the left one plus the side (0 left, 1 right).
  for (const CocoKeypoint left :
       {kLeftEye, kLeftEar, kLeftShoulder, kLeftElbow, kLeftWrist, kLeftHip, kLeftKnee, kLeftAnkle}) {
    std::string right = kCocoKeypointNames[left];
    right.replace(0, 4, "right");
    EXPECT_EQ(kCocoKeypointNames[left + 1], right);
  }
}

TEST(Skeleton, EveryPresetGivesRigidPartTransformsAndKeypointsOnTheBody) {
  for (const char* name :
       {"seated_upright", "seated_leaning", "seated_arms_on_table", "seated_leaning_back", "standing"}) {
    const auto parts = Shipped().PartTransforms(PresetPose(name));
    ExpectRigid(parts, name);
    const auto keypoints = Shipped().Keypoints(parts);
    // Head above shoulders above hips; ankles near the floor.
    EXPECT_GT(keypoints[kNose].z(), keypoints[kLeftShoulder].z()) << name;
    EXPECT_GT(keypoints[kLeftShoulder].z(), keypoints[kLeftHip].z()) << name;
    EXPECT_LT(keypoints[kLeftAnkle].z(), 0.12) << name;
    EXPECT_LT(keypoints[kRightAnkle].z(), 0.12) << name;
    // Left is +y.
    EXPECT_GT(keypoints[kLeftShoulder].y(), keypoints[kRightShoulder].y()) << name;
  }
}

TEST(Skeleton, RestPoseJointsLandOnTheRestKeypoints) {
  // A pose with every angle 0 and the wrists at their rest places is the rest pose: the trunk
  // and legs do not move, the arms (straightened to the IK's reach) move by less than 2 cm.
  BodyPose rest;
  for (int s = 0; s < 2; ++s) {
    rest.arm[s].wrist_m = Shipped().RestJoint(6 + 6 * s);
    rest.arm[s].elbow_hint = Eigen::Vector3d(-1, 0, 0);
    rest.arm[s].hand_dir = Eigen::Vector3d(0, 0, -1);
    rest.arm[s].back_hint = Eigen::Vector3d(0, s == 0 ? 1 : -1, 0);
  }
  const auto parts = Shipped().PartTransforms(rest);
  for (int i : {0, 1, 2, 3, 7, 8, 9, 13, 14, 15}) {
    EXPECT_LT((parts[i] - Eigen::Matrix4d::Identity()).norm(), 1e-6) << Skeleton::PartNames()[i];
  }
  std::array<Eigen::Matrix4d, Skeleton::kPartCount> identity;
  identity.fill(Eigen::Matrix4d::Identity());
  const auto posed = Shipped().Keypoints(parts), at_rest = Shipped().Keypoints(identity);
  for (int k = 0; k < kCocoKeypointCount; ++k) {
    EXPECT_LT((posed[k] - at_rest[k]).norm(), 0.02) << kCocoKeypointNames[k];
  }
}

TEST(Skeleton, JointAnglesAreClampedToAnatomicalLimits) {
  BodyPose pose = PresetPose("seated_upright");
  pose.dof[kNeckTwist] = 170 * kDeg;
  pose.dof[kKneeFlexLeft] = -40 * kDeg;
  pose.arm[0].wrist_m = Eigen::Vector3d(3, 0, 1);  // out of reach
  const BodyPose limited = Shipped().Limit(pose);
  EXPECT_DOUBLE_EQ(limited.dof[kNeckTwist], 70 * kDeg);
  EXPECT_DOUBLE_EQ(limited.dof[kKneeFlexLeft], 0.0);
  const double reach = (limited.arm[0].wrist_m - Shipped().Shoulder(limited, 0)).norm();
  EXPECT_LT(reach, 0.531);
  ExpectRigid(Shipped().PartTransforms(pose), "limited");
}

TEST(Skeleton, WalkingSwingsTheLegsAndKeepsAFootOnTheFloor) {
  double min_ankle_x = 1e9, max_ankle_x = -1e9;
  for (int i = 0; i < 16; ++i) {
    const BodyPose pose = Shipped().Walking(2 * M_PI * i / 16, Skeleton::StrideAt(1.3));
    const auto parts = Shipped().PartTransforms(pose);
    ExpectRigid(parts, "walking");
    double lowest = 1e9;
    for (const auto& [name, at] : Shipped().FootContacts(parts)) lowest = std::min(lowest, at.z());
    EXPECT_NEAR(lowest, 0.0, 1e-6);
    const auto keypoints = Shipped().Keypoints(parts);
    min_ankle_x = std::min(min_ankle_x, keypoints[kLeftAnkle].x());
    max_ankle_x = std::max(max_ankle_x, keypoints[kLeftAnkle].x());
  }
  EXPECT_GT(max_ankle_x - min_ankle_x, 0.3);  // a step of ~0.7 m swings each ankle
}

TEST(Skeleton, BlendIsSmoothBetweenPoses) {
  const BodyPose a = PresetPose("seated_upright"), b = PresetPose("seated_leaning");
  EXPECT_DOUBLE_EQ(Blend(a, b, 0).dof[kLumbarFlex], a.dof[kLumbarFlex]);
  EXPECT_DOUBLE_EQ(Blend(a, b, 1).dof[kLumbarFlex], b.dof[kLumbarFlex]);
  EXPECT_DOUBLE_EQ(SmoothStep(0.5), 0.5);
  EXPECT_DOUBLE_EQ(SmoothStep(-1), 0.0);
  EXPECT_DOUBLE_EQ(SmoothStep(2), 1.0);
}

TEST(Skeleton, AnUnknownPresetIsAnError) {
  EXPECT_THROW(PresetPose("seated_sideways"), InputError);
  EXPECT_FALSE(IsPresetPose("seated_sideways"));
}

// Copies the shipped person_part_* assets into dir, changing the scene extras of one part.
void CopyPartsWith(const std::filesystem::path& dir, const std::string& part,
                   const std::function<void(nlohmann::json*)>& edit) {
  for (const std::string& name : Skeleton::PartNames()) {
    const std::string file = "person_part_" + name + ".gltf";
    nlohmann::json gltf = nlohmann::json::parse(std::ifstream(std::filesystem::path(ShippedAssetDir()) / file));
    if (name == part) edit(&gltf["scenes"][0]["extras"]);
    std::ofstream(dir / file) << gltf.dump();
  }
}

// The message of the InputError building a skeleton from dir throws, or "".
std::string SkeletonError(const std::filesystem::path& dir) {
  try {
    AssetLibrary assets(dir.string());
    Skeleton skeleton(assets);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Skeleton, APartWithTheWrongParentIsAnErrorNamingItsFileAndWhatWasExpected) {
  const test::TestDir temp;
  CopyPartsWith(temp.path(), "neck", [](nlohmann::json* extras) { (*extras)["parent"] = "pelvis"; });
  const std::string message = SkeletonError(temp.path());
  EXPECT_NE(message.find((temp.path() / "person_part_neck.gltf").string() + ": /scenes/0/extras"), std::string::npos)
      << message;
  EXPECT_NE(message.find("expected part \"neck\" with parent \"torso\", found part \"neck\" with parent \"pelvis\""),
            std::string::npos)
      << message;
}

TEST(Skeleton, AMissingCocoKeypointIsAnErrorNamingTheKeypoint) {
  const test::TestDir temp;
  CopyPartsWith(temp.path(), "head", [](nlohmann::json* extras) { (*extras)["keypoints"].erase(0); });  // the nose
  const std::string message = SkeletonError(temp.path());
  EXPECT_NE(message.find("person_part_pelvis.gltf"), std::string::npos) << message;
  EXPECT_NE(message.find("no person_part_* asset carries the COCO keypoint \"nose\""), std::string::npos) << message;
}

TEST(Skeleton, TheShippedPartsBuildASkeleton) { EXPECT_EQ(SkeletonError(ShippedAssetDir()), ""); }

}  // namespace
}  // namespace hoilcd
