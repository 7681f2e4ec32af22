#include "hoilcd/sim/assets/skeleton.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat4 = Eigen::Matrix4d;
constexpr double kDeg = M_PI / 180.0;
constexpr double kMaxElbowFlexDeg = 145;
constexpr double kMaxWristBendDeg = 80;

// Part indices: pelvis, torso, neck, head, then per side upper_arm, lower_arm, hand, thigh,
// shin, foot.
constexpr int kPelvis = 0, kTorso = 1, kNeck = 2, kHead = 3;
int SidePart(int side, int k) { return 4 + 6 * side + k; }
constexpr int kUpperArm = 0, kLowerArm = 1, kHand = 2, kThigh = 3, kShin = 4, kFoot = 5;

Mat4 Translation(const Vec3& t) {
  Mat4 m = Mat4::Identity();
  m.topRightCorner<3, 1>() = t;
  return m;
}
Mat4 Rotation(double angle_rad, const Vec3& axis) {
  Mat4 m = Mat4::Identity();
  m.topLeftCorner<3, 3>() = Eigen::AngleAxisd(angle_rad, axis).toRotationMatrix();
  return m;
}
Vec3 Apply(const Mat4& m, const Vec3& p) { return m.topLeftCorner<3, 3>() * p + m.topRightCorner<3, 1>(); }

// Frame whose z axis is -direction and whose x axis leans towards `reference`.
Eigen::Matrix3d BoneFrame(const Vec3& direction, const Vec3& reference) {
  const Vec3 z = -direction.normalized();
  Vec3 x = reference - reference.dot(z) * z;
  if (x.norm() < 1e-9) x = std::abs(z.x()) < 0.9 ? Vec3::UnitX() - z.x() * z : Vec3::UnitY() - z.y() * z;
  x.normalize();
  Eigen::Matrix3d f;
  f.col(0) = x;
  f.col(1) = z.cross(x);
  f.col(2) = z;
  return f;
}

// Transform taking a rest bone (rest joint, rest frame) to a posed one, scaled about the joint.
Mat4 BoneTransform(const Eigen::Matrix3d& posed, const Eigen::Matrix3d& rest, const Vec3& posed_joint,
                   const Vec3& rest_joint, double scale) {
  Mat4 m = Mat4::Identity();
  const Eigen::Matrix3d r = scale * posed * rest.transpose();
  m.topLeftCorner<3, 3>() = r;
  m.topRightCorner<3, 1>() = posed_joint - r * rest_joint;
  return m;
}

Vec3 Lerp(const Vec3& a, const Vec3& b, double w) { return a + w * (b - a); }

}  // namespace

const std::array<const char*, kCocoKeypointCount> kCocoKeypointNames = {
    "nose",           "left_eye",   "right_eye",   "left_ear",   "right_ear",   "left_shoulder",
    "right_shoulder", "left_elbow", "right_elbow", "left_wrist", "right_wrist", "left_hip",
    "right_hip",      "left_knee",  "right_knee",  "left_ankle", "right_ankle"};

const std::array<DofLimit, kDofCount>& DofLimits() {
  static const std::array<DofLimit, kDofCount> kLimits = {{
      {"lumbar_flex", -25, 70},
      {"lumbar_bend", -30, 30},
      {"lumbar_twist", -35, 35},
      {"neck_flex", -50, 60},
      {"neck_bend", -35, 35},
      {"neck_twist", -70, 70},
      {"head_nod", -20, 25},
      {"hip_flex_left", -20, 120},
      {"hip_flex_right", -20, 120},
      {"hip_abduct_left", -25, 45},
      {"hip_abduct_right", -25, 45},
      {"knee_flex_left", 0, 140},
      {"knee_flex_right", 0, 140},
      {"ankle_flex_left", -45, 20},
      {"ankle_flex_right", -45, 20},
  }};
  return kLimits;
}

double SmoothStep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}

BodyPose Blend(const BodyPose& a, const BodyPose& b, double w) {
  BodyPose out;
  out.pelvis_m = Lerp(a.pelvis_m, b.pelvis_m, w);
  out.scale = a.scale + w * (b.scale - a.scale);
  for (int i = 0; i < kDofCount; ++i) out.dof[i] = a.dof[i] + w * (b.dof[i] - a.dof[i]);
  for (int s = 0; s < 2; ++s) {
    out.arm[s].wrist_m = Lerp(a.arm[s].wrist_m, b.arm[s].wrist_m, w);
    out.arm[s].elbow_hint = Lerp(a.arm[s].elbow_hint, b.arm[s].elbow_hint, w);
    out.arm[s].hand_dir = Lerp(a.arm[s].hand_dir, b.arm[s].hand_dir, w);
    out.arm[s].back_hint = Lerp(a.arm[s].back_hint, b.arm[s].back_hint, w);
  }
  return out;
}

namespace {

// Legs of every seated posture: seat top at 0.45 m, thighs on the seat, shins nearly upright,
// feet flat on the floor.
BodyPose SeatedBase() {
  BodyPose p;
  p.pelvis_m = Vec3(-0.07, 0, 0.535);
  for (int s = 0; s < 2; ++s) {
    p.dof[kHipFlexLeft + s] = 87 * kDeg;
    p.dof[kHipAbductLeft + s] = 2 * kDeg;
    p.dof[kKneeFlexLeft + s] = 82 * kDeg;
    p.dof[kAnkleFlexLeft + s] = -5 * kDeg;
  }
  return p;
}

// Hands resting on the thighs.
void HandsOnThighs(BodyPose* p, double back_m) {
  for (int s = 0; s < 2; ++s) {
    const double sign = s == 0 ? 1 : -1;
    p->arm[s] = {Vec3(0.15 - back_m, sign * 0.15, 0.66), Vec3(-1, sign * 0.2, 0), Vec3(0.17, -sign * 0.03, -0.02),
                 Vec3(0, 0, 1)};
  }
}

}  // namespace

bool IsPresetPose(const std::string& name) {
  return name == "seated_upright" || name == "seated_leaning" || name == "seated_arms_on_table" ||
         name == "seated_leaning_back" || name == "standing";
}

BodyPose PresetPose(const std::string& name) {
  if (name == "standing") {
    BodyPose p;
    for (int s = 0; s < 2; ++s) {
      const double sign = s == 0 ? 1 : -1;
      p.dof[kKneeFlexLeft + s] = 2 * kDeg;
      p.dof[kHipFlexLeft + s] = 1 * kDeg;
      p.dof[kAnkleFlexLeft + s] = 1 * kDeg;
      p.arm[s] = {Vec3(0.01, sign * 0.215, 0.845), Vec3(-1, sign * 0.2, 0), Vec3(0.05, 0, -1), Vec3(0, sign, 0)};
    }
    return p;
  }
  BodyPose p = SeatedBase();
  if (name == "seated_upright") {
    HandsOnThighs(&p, 0.0);
  } else if (name == "seated_leaning_back") {
    p.pelvis_m.x() += 0.03;  // slides forward a little on the seat
    p.dof[kLumbarFlex] = -6 * kDeg;
    p.dof[kNeckFlex] = 8 * kDeg;
    HandsOnThighs(&p, -0.02);
  } else if (name == "seated_arms_on_table") {
    p.dof[kLumbarFlex] = 4 * kDeg;
    p.dof[kNeckFlex] = 4 * kDeg;
    for (int s = 0; s < 2; ++s) {
      const double sign = s == 0 ? 1 : -1;
      // Forearms on the table top (0.74 m, near edge at x = 0.30 m), hands flat.
      p.arm[s] = {Vec3(0.40, sign * 0.13, 0.775), Vec3(-0.3, sign, -1), Vec3(0.17, -sign * 0.03, -0.012),
                  Vec3(0, sign * 0.3, 1)};
    }
  } else if (name == "seated_leaning") {
    p.dof[kLumbarFlex] = 20 * kDeg;
    p.dof[kNeckFlex] = -8 * kDeg;
    for (int s = 0; s < 2; ++s) {
      const double sign = s == 0 ? 1 : -1;
      // Elbows and forearms on the table top, hands meeting in front.
      p.arm[s] = {Vec3(0.52, sign * 0.10, 0.79), Vec3(0, sign * 0.5, -0.7), Vec3(0.14, -sign * 0.06, -0.012),
                  Vec3(0, sign * 0.3, 1)};
    }
  } else {
    throw InputError("pose", "unknown pose preset \"" + name +
                                 "\" (expected seated_upright, seated_leaning, seated_arms_on_table, "
                                 "seated_leaning_back or standing)");
  }
  return p;
}

const std::array<std::string, Skeleton::kPartCount>& Skeleton::PartNames() {
  static const std::array<std::string, kPartCount> kNames = {
      "pelvis",     "torso",       "neck",       "head",      "upper_arm_left",  "lower_arm_left",
      "hand_left",  "thigh_left",  "shin_left",  "foot_left", "upper_arm_right", "lower_arm_right",
      "hand_right", "thigh_right", "shin_right", "foot_right"};
  return kNames;
}

Skeleton::Skeleton(AssetLibrary& assets) {
  static const std::array<std::string, kPartCount> kParents = {"",
                                                               "pelvis",
                                                               "torso",
                                                               "neck",
                                                               "torso",
                                                               "upper_arm_left",
                                                               "lower_arm_left",
                                                               "pelvis",
                                                               "thigh_left",
                                                               "shin_left",
                                                               "torso",
                                                               "upper_arm_right",
                                                               "lower_arm_right",
                                                               "pelvis",
                                                               "thigh_right",
                                                               "shin_right"};
  for (int i = 0; i < kPartCount; ++i) {
    const Asset& a = assets.Get("person_part_" + PartNames()[i]);
    if (a.part != PartNames()[i] || a.parent != kParents[i]) {
      throw InputError(a.path, "/scenes/0/extras: expected part \"" + PartNames()[i] + "\" with parent \"" +
                                   kParents[i] + "\", found part \"" + a.part + "\" with parent \"" + a.parent + "\"");
    }
    parts_[i] = &a;
  }
  for (int k = 0; k < kCocoKeypointCount; ++k) {
    bool found = false;
    for (int i = 0; i < kPartCount && !found; ++i) {
      for (size_t j = 0; j < parts_[i]->keypoints.size() && !found; ++j) {
        if (parts_[i]->keypoints[j].name != kCocoKeypointNames[k]) continue;
        keypoint_of_[k] = {i, static_cast<int>(j)};
        found = true;
      }
    }
    if (!found) {
      throw InputError(
          assets.Resolve("person_part_pelvis"),
          std::string("no person_part_* asset carries the COCO keypoint \"") + kCocoKeypointNames[k] + "\"");
    }
  }
}

Eigen::Vector2d Skeleton::UpperBodyHalfExtentM() const {
  const Eigen::Vector2f axis = parts_[kPelvis]->joint_m.head<2>();
  Eigen::Vector2d half = Eigen::Vector2d::Zero();
  for (int part : {kTorso, SidePart(0, kUpperArm), SidePart(1, kUpperArm)}) {
    const Eigen::AlignedBox3f& box = parts_[part]->bounds_m;  // the rest pose, body frame
    const Eigen::Vector2f far =
        (box.max().head<2>() - axis).cwiseAbs().cwiseMax((box.min().head<2>() - axis).cwiseAbs());
    half = half.cwiseMax(far.cast<double>());
  }
  return half;
}

Eigen::Vector3d Skeleton::Shoulder(const BodyPose& pose, int side) const {
  const Mat4 torso = Translation(pose.pelvis_m) * Rotation(pose.dof[kLumbarFlex], Vec3::UnitY()) *
                     Rotation(-pose.dof[kLumbarBend], Vec3::UnitX()) * Rotation(pose.dof[kLumbarTwist], Vec3::UnitZ());
  return Apply(torso, pose.scale * (RestJoint(SidePart(side, kUpperArm)) - RestJoint(kTorso)));
}

void Skeleton::SitOnSeat(BodyPose* pose, double seat_height_m) const {
  const double s = pose->scale;
  pose->pelvis_m.z() = seat_height_m + 0.085 * s;  // the buttocks' thickness below the hip joints
  for (int side = 0; side < 2; ++side) {
    const Vec3 hip = pose->pelvis_m + s * (RestJoint(SidePart(side, kThigh)) - RestJoint(kPelvis));
    const double a = s * (RestJoint(SidePart(side, kShin)) - RestJoint(SidePart(side, kThigh))).norm();
    const double b = s * (RestJoint(SidePart(side, kFoot)) - RestJoint(SidePart(side, kShin))).norm();
    // The ankle a little in front of the knee, at its standing height above the floor.
    const Eigen::Vector2d target(hip.x() + 0.455 * s, RestJoint(SidePart(side, kFoot)).z() * s + 0.01);
    const Eigen::Vector2d d(target.x() - hip.x(), target.y() - hip.z());
    const double dist = std::clamp(d.norm(), std::abs(a - b) + 1e-6, a + b - 1e-6);
    const double beta = std::atan2(d.x(), -d.y());
    const double gamma = std::acos(std::clamp((a * a + dist * dist - b * b) / (2 * a * dist), -1.0, 1.0));
    const double hip_flex = beta + gamma;
    const Eigen::Vector2d knee(hip.x() + a * std::sin(hip_flex), hip.z() - a * std::cos(hip_flex));
    const double shin = std::atan2(target.x() - knee.x(), -(target.y() - knee.y()));
    pose->dof[kHipFlexLeft + side] = hip_flex;
    pose->dof[kKneeFlexLeft + side] = hip_flex - shin;
    pose->dof[kAnkleFlexLeft + side] = -shin;
  }
}

BodyPose Skeleton::Limit(const BodyPose& pose) const {
  BodyPose out = pose;
  for (int i = 0; i < kDofCount; ++i) {
    out.dof[i] = std::clamp(pose.dof[i], DofLimits()[i].min_deg * kDeg, DofLimits()[i].max_deg * kDeg);
  }
  for (int s = 0; s < 2; ++s) {
    const double a = (RestJoint(SidePart(s, kLowerArm)) - RestJoint(SidePart(s, kUpperArm))).norm();
    const double b = (RestJoint(SidePart(s, kHand)) - RestJoint(SidePart(s, kLowerArm))).norm();
    const Vec3 shoulder = Shoulder(out, s);
    const double a_scaled = a * pose.scale, b_scaled = b * pose.scale;
    Vec3 reach = out.arm[s].wrist_m - shoulder;
    const double d_min = std::sqrt(a_scaled * a_scaled + b_scaled * b_scaled -
                                   2 * a_scaled * b_scaled * std::cos((180 - kMaxElbowFlexDeg) * kDeg));
    const double d = std::clamp(reach.norm(), d_min, a_scaled + b_scaled - 1e-4);
    if (reach.norm() < 1e-9) reach = Vec3(0, 0, -1);
    out.arm[s].wrist_m = shoulder + reach.normalized() * d;
  }
  return out;
}

std::array<Eigen::Matrix4d, Skeleton::kPartCount> Skeleton::PartTransforms(const BodyPose& input) const {
  const BodyPose pose = Limit(input);
  const auto& q = pose.dof;
  const double scale = pose.scale;
  auto J = [&](int part) -> Vec3 { return scale * RestJoint(part); };
  // Maps a part's rest mesh to the posed joint frame: scale about the rest joint, then the frame.
  auto mesh_transform = [&](const Mat4& joint_frame, int part) -> Mat4 {
    Mat4 m = joint_frame * Translation(-J(part));
    m.topLeftCorner<3, 3>() *= scale;
    return m;
  };
  std::array<Mat4, kPartCount> joint;  // person_from_joint frames (rest axes at the joint)
  joint[kPelvis] = Translation(pose.pelvis_m);
  auto child = [&](int parent, int part) -> Mat4 { return joint[parent] * Translation(J(part) - J(parent)); };
  // The spine flexes and bends in the pelvis's planes and twists about its own axis: a twist
  // turns the shoulders about a leaning trunk instead of swinging the lean sideways.
  joint[kTorso] = child(kPelvis, kTorso) * Rotation(q[kLumbarFlex], Vec3::UnitY()) *
                  Rotation(-q[kLumbarBend], Vec3::UnitX()) * Rotation(q[kLumbarTwist], Vec3::UnitZ());
  joint[kNeck] = child(kTorso, kNeck) * Rotation(q[kNeckTwist], Vec3::UnitZ()) * Rotation(q[kNeckFlex], Vec3::UnitY()) *
                 Rotation(-q[kNeckBend], Vec3::UnitX());
  joint[kHead] = child(kNeck, kHead) * Rotation(q[kHeadNod], Vec3::UnitY());
  std::array<Mat4, kPartCount> out;
  for (int i : {kPelvis, kTorso, kNeck, kHead}) out[i] = mesh_transform(joint[i], i);
  for (int s = 0; s < 2; ++s) {
    const double sign = s == 0 ? 1 : -1;
    const int thigh = SidePart(s, kThigh), shin = SidePart(s, kShin), foot = SidePart(s, kFoot);
    joint[thigh] = child(kPelvis, thigh) * Rotation(-q[kHipFlexLeft + s], Vec3::UnitY()) *
                   Rotation(sign * q[kHipAbductLeft + s], Vec3::UnitX());
    joint[shin] = child(thigh, shin) * Rotation(q[kKneeFlexLeft + s], Vec3::UnitY());
    joint[foot] = child(shin, foot) * Rotation(-q[kAnkleFlexLeft + s], Vec3::UnitY());
    for (int i : {thigh, shin, foot}) out[i] = mesh_transform(joint[i], i);

    // Arm: two-bone IK from the shoulder to the wrist target, the elbow towards its hint.
    const int upper = SidePart(s, kUpperArm), lower = SidePart(s, kLowerArm), hand = SidePart(s, kHand);
    const ArmPose& arm = pose.arm[s];
    const Vec3 rest_s = RestJoint(upper), rest_e = RestJoint(lower), rest_w = RestJoint(hand);
    const double a = scale * (rest_e - rest_s).norm(), b = scale * (rest_w - rest_e).norm();
    const Vec3 shoulder = Apply(joint[kTorso], J(upper) - J(kTorso));
    const Vec3 wrist = arm.wrist_m;
    const double d = (wrist - shoulder).norm();
    const Vec3 n = (wrist - shoulder) / d;
    const double cos_alpha = std::clamp((a * a + d * d - b * b) / (2 * a * d), -1.0, 1.0);
    Vec3 h = arm.elbow_hint - arm.elbow_hint.dot(n) * n;
    h = h.norm() > 1e-9 ? h.normalized() : BoneFrame(n, Vec3::UnitX()).col(0);
    const Vec3 elbow = shoulder + a * (cos_alpha * n + std::sqrt(1 - cos_alpha * cos_alpha) * h);
    const Vec3 u = (elbow - shoulder).normalized(), f = (wrist - elbow).normalized();
    Vec3 hand_dir = arm.hand_dir.normalized();
    const double bend = std::acos(std::clamp(hand_dir.dot(f), -1.0, 1.0));
    if (bend > kMaxWristBendDeg * kDeg) {
      const Vec3 axis = f.cross(hand_dir);
      hand_dir = axis.norm() > 1e-9 ? Eigen::AngleAxisd(kMaxWristBendDeg * kDeg, axis.normalized()) * f : f;
    }
    const Vec3 rest_back(0, sign, 0);
    Vec3 bend_dir = f - f.dot(u) * u;
    if (bend_dir.norm() < 1e-6) bend_dir = -h;
    out[upper] =
        BoneTransform(BoneFrame(u, bend_dir), BoneFrame(rest_e - rest_s, Vec3::UnitX()), shoulder, rest_s, scale);
    out[lower] =
        BoneTransform(BoneFrame(f, arm.back_hint), BoneFrame(rest_w - rest_e, rest_back), elbow, rest_e, scale);
    out[hand] =
        BoneTransform(BoneFrame(hand_dir, arm.back_hint), BoneFrame(Vec3(0, 0, -1), rest_back), wrist, rest_w, scale);
  }
  return out;
}

std::array<Eigen::Vector3d, kCocoKeypointCount> Skeleton::Keypoints(
    const std::array<Eigen::Matrix4d, kPartCount>& person_from_part) const {
  std::array<Vec3, kCocoKeypointCount> out;
  for (int k = 0; k < kCocoKeypointCount; ++k) {
    const auto [part, index] = keypoint_of_[k];
    out[k] = Apply(person_from_part[part], parts_[part]->keypoints[index].position_m.cast<double>());
  }
  return out;
}

std::vector<std::pair<std::string, Eigen::Vector3d>> Skeleton::FootContacts(
    const std::array<Eigen::Matrix4d, kPartCount>& person_from_part) const {
  std::vector<std::pair<std::string, Vec3>> out;
  for (int s = 0; s < 2; ++s) {
    const int foot = SidePart(s, kFoot);
    for (const ContactPoint& c : parts_[foot]->contacts) {
      out.emplace_back(c.name, Apply(person_from_part[foot], c.position_m.cast<double>()));
    }
  }
  return out;
}

Eigen::Vector3d Skeleton::HeadPoint(const BodyPose& pose, const Eigen::Vector3d& rest_point) const {
  return Apply(PartTransforms(pose)[kHead], rest_point);
}

double Skeleton::StrideAt(double speed_m_s) { return std::max(0.5, 1.4 * std::sqrt(std::max(0.0, speed_m_s) / 1.3)); }

BodyPose Skeleton::Walking(double phase_rad, double stride_m) const {
  BodyPose p = PresetPose("standing");
  // Hip swing such that the feet travel one stride per cycle (a 1.4 m stride swings the hips
  // ±25°); knees, ankles, arms and trunk scale with it.
  const double leg_m = RestJoint(SidePart(0, kThigh)).z() - RestJoint(SidePart(0, kFoot)).z();
  const double swing_deg = std::asin(std::clamp(stride_m / (4 * leg_m), 0.0, 0.6)) / kDeg;
  const double s = swing_deg / 25;
  p.dof[kLumbarFlex] = 3 * kDeg * s;
  p.dof[kLumbarTwist] = 4 * kDeg * s * std::sin(phase_rad);
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1 : -1;
    const double leg = phase_rad + side * M_PI;
    p.dof[kHipFlexLeft + side] = swing_deg * kDeg * std::sin(leg);
    const double swing = std::max(0.0, std::cos(leg));  // > 0 while the leg swings forward
    p.dof[kKneeFlexLeft + side] = (4 + 55 * s * swing * swing) * kDeg;
    p.dof[kAnkleFlexLeft + side] = 10 * kDeg * s * swing;
    // The arm swings with the opposite leg, the elbow a little bent.
    const double psi = 20 * kDeg * s * std::sin(leg + M_PI);
    const double elbow = (15 + 10 * s) * kDeg;
    const Vec3 shoulder = Shoulder(p, side);
    const double a = (RestJoint(SidePart(side, kLowerArm)) - RestJoint(SidePart(side, kUpperArm))).norm();
    const double b = (RestJoint(SidePart(side, kHand)) - RestJoint(SidePart(side, kLowerArm))).norm();
    const Vec3 e = shoulder + a * Vec3(std::sin(psi), sign * 0.06, -std::cos(psi)).normalized();
    const Vec3 f = Vec3(std::sin(psi + elbow), sign * 0.03, -std::cos(psi + elbow)).normalized();
    p.arm[side] = {e + b * f, Vec3(-std::cos(psi), sign * 0.2, -std::sin(psi)), f, Vec3(0, sign, 0)};
  }
  // Feet on the floor: the lower foot touches it.
  const auto parts = PartTransforms(p);
  double lowest = 1e9;
  for (const auto& [name, at] : FootContacts(parts)) lowest = std::min(lowest, at.z());
  p.pelvis_m.z() -= lowest;
  for (int side = 0; side < 2; ++side) p.arm[side].wrist_m.z() -= lowest;
  return p;
}

}  // namespace hoilcd
