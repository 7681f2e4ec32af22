// Articulated people: the rest skeleton read from the person_part_* assets, a body pose (root,
// spine, neck and head angles, leg angles, wrist targets solved by two-bone IK) clamped to
// anatomical joint limits, forward kinematics to per-part transforms, the 17 COCO keypoints, and
// the pose presets (the seated postures, standing, a walking cycle).
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hoilcd/sim/assets/asset.h"

namespace hoilcd {

constexpr int kCocoKeypointCount = 17;
// The COCO keypoints in COCO order: indices into Keypoints(), Person::keypoints_m and
// kCocoKeypointNames. A side's keypoint is the left one plus the side (0 left, 1 right).
enum CocoKeypoint {
  kNose,
  kLeftEye,
  kRightEye,
  kLeftEar,
  kRightEar,
  kLeftShoulder,
  kRightShoulder,
  kLeftElbow,
  kRightElbow,
  kLeftWrist,
  kRightWrist,
  kLeftHip,
  kRightHip,
  kLeftKnee,
  kRightKnee,
  kLeftAnkle,
  kRightAnkle
};
static_assert(kRightAnkle + 1 == kCocoKeypointCount, "one name for each COCO keypoint");
// COCO keypoint names in COCO order.
extern const std::array<const char*, kCocoKeypointCount> kCocoKeypointNames;

// Angles of the joints with explicit degrees of freedom, radians. Positive: flexion (forward),
// bend to the left, twist to the left (counter-clockwise seen from above), abduction outwards.
enum Dof {
  kLumbarFlex,
  kLumbarBend,
  kLumbarTwist,
  kNeckFlex,
  kNeckBend,
  kNeckTwist,
  kHeadNod,
  kHipFlexLeft,
  kHipFlexRight,
  kHipAbductLeft,
  kHipAbductRight,
  kKneeFlexLeft,
  kKneeFlexRight,
  kAnkleFlexLeft,
  kAnkleFlexRight,
  kDofCount
};

struct DofLimit {
  const char* name;
  double min_deg, max_deg;
};
// Anatomical ranges (AAOS normal joint motion, rounded in): DofLimits()[kNeckTwist] = {-70, 70}.
const std::array<DofLimit, kDofCount>& DofLimits();

// One arm: where the wrist should be and how the arm and hand are oriented (person frame).
struct ArmPose {
  Eigen::Vector3d wrist_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d elbow_hint = Eigen::Vector3d(-1, 0, 0);  // the side the elbow points to
  Eigen::Vector3d hand_dir = Eigen::Vector3d(0, 0, -1);    // wrist towards the fingertips
  Eigen::Vector3d back_hint = Eigen::Vector3d(0, 1, 0);    // the back of the hand faces this way
};

// A whole-body pose in the person frame (seat frame for seated people: origin on the floor under
// the seat centre, facing +x; body frame for standing people and walkers).
struct BodyPose {
  Eigen::Vector3d pelvis_m = Eigen::Vector3d(0, 0, 0.925);
  std::array<double, kDofCount> dof{};  // radians
  std::array<ArmPose, 2> arm;           // 0 = left, 1 = right
  double scale = 1;                     // body size (bone lengths and part meshes), fraction
};

// a + w (b - a), for smooth transitions between poses (w in [0, 1]).
BodyPose Blend(const BodyPose& a, const BodyPose& b, double w);
// Smooth 0 -> 1 step over [0, 1] (zero slope at both ends).
double SmoothStep(double x);

// Pose presets: "seated_upright", "seated_leaning" (forward, elbows on the table),
// "seated_arms_on_table", "seated_leaning_back", "standing". Throws on an unknown name.
BodyPose PresetPose(const std::string& name);
bool IsPresetPose(const std::string& name);

class Skeleton {
 public:
  // Loads person_part_* from the library; throws InputError when a part is missing or the
  // hierarchy is not the expected one.
  explicit Skeleton(AssetLibrary& assets);

  static constexpr int kPartCount = 16;
  // Part names, parents before children: pelvis, torso, neck, head, then per side (left, right)
  // upper_arm, lower_arm, hand, thigh, shin, foot.
  static const std::array<std::string, kPartCount>& PartNames();
  const Asset& part(int i) const { return *parts_[i]; }

  // Clamps the explicit angles to DofLimits() and solves the arms (elbow flexion 0..145°, wrist
  // bend at most 80°): the result is a pose the body can take.
  BodyPose Limit(const BodyPose& pose) const;
  // person_from_part of every part (maps the part's asset coordinates into the person frame).
  std::array<Eigen::Matrix4d, kPartCount> PartTransforms(const BodyPose& pose) const;
  // The 17 COCO keypoints (person frame) of the part transforms.
  std::array<Eigen::Vector3d, kCocoKeypointCount> Keypoints(
      const std::array<Eigen::Matrix4d, kPartCount>& person_from_part) const;
  // Floor contacts of the feet (person frame).
  std::vector<std::pair<std::string, Eigen::Vector3d>> FootContacts(
      const std::array<Eigen::Matrix4d, kPartCount>& person_from_part) const;
  // Half extents (x forward, y sideways) about the spine's axis of the torso, shoulders and
  // hanging upper arms at scale 1 (m): the room a seated person takes beside them.
  Eigen::Vector2d UpperBodyHalfExtentM() const;
  // A joint (rest position) of a part in the rest body frame.
  Eigen::Vector3d RestJoint(int part) const { return parts_[part]->joint_m.cast<double>(); }
  // Seated: the hips on the seat (top at seat_height_m) and the feet flat on the floor below
  // the knees, whatever the body's scale (two-bone IK of each leg in its sagittal plane).
  void SitOnSeat(BodyPose* pose, double seat_height_m = 0.45) const;
  // Shoulder (side 0 left, 1 right) in the person frame for the pose's spine.
  Eigen::Vector3d Shoulder(const BodyPose& pose, int side) const;
  // The head's centre in the person frame (for gaze targets and the mouth).
  Eigen::Vector3d HeadPoint(const BodyPose& pose, const Eigen::Vector3d& rest_point) const;

  // A walking pose: gait phase (rad, 2π per stride) and stride length (two steps, m; an adult
  // at 1.3 m/s takes ~1.4 m strides), for body scale 1; a foot is on the floor.
  BodyPose Walking(double phase_rad, double stride_m) const;
  // Stride length (m, body scale 1) at a walking speed: 1.4 m at 1.3 m/s, shorter when slower
  // (stride ∝ √speed, as observed in gait studies), at least 0.5 m.
  static double StrideAt(double speed_m_s);

 private:
  std::array<const Asset*, kPartCount> parts_{};
  std::array<std::pair<int, int>, kCocoKeypointCount> keypoint_of_{};  // part, index in its list
};

}  // namespace hoilcd
