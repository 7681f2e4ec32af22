#include "hoilcd/sim/people/body_fields.h"

#include <algorithm>
#include <cmath>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

// 0 below a, 1 above b, smooth in between (a > b gives the mirrored step).
double Ramp(double x, double a, double b) {
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// Rest-pose landmarks (tools/make_assets: RestSkeleton and HeadPart), m.
const Eigen::Vector3f kHeadCentre(0.005f, 0.0f, 1.60f);
constexpr double kShoulderZ = 1.365, kElbowZ = 1.085, kWristZ = 0.835, kFingertipZ = 0.665;
constexpr double kTorsoHemZ = 0.99, kKneeZ = 0.50;

// Skin offsets from the skin temperature parameter (34.0 °C by default), K. Micheletti et al.
// (2022): forehead 33.4, inner canthus 34.3, outer canthus 32.8 °C; the rest are estimates
// (docs/models/people.md).
constexpr double kForeheadK = -0.6, kInnerCanthusK = 0.3, kOuterCanthusK = -1.2, kFaceK = -1.0;
constexpr double kNoseK = -2.0, kEarK = -2.0, kChinK = -0.8;
constexpr double kNeckK = -0.3, kCollarK = 0.3;
constexpr double kHandBackK = -2.0, kFingertipK = -3.5, kForearmK = -1.2;
constexpr double kMottleK = 0.15;
constexpr double kHairK = 0.5;

double Bump(const Eigen::Vector3f& p, const Eigen::Vector3f& centre, double radius_m) {
  const double r2 = (p - centre).squaredNorm() / (radius_m * radius_m);
  return r2 >= 1 ? 0.0 : (1 - r2) * (1 - r2);
}

double FaceOffset(const Eigen::Vector3f& p) {
  const Eigen::Vector3f d = p - kHeadCentre;
  double t = kFaceK;
  t += (kForeheadK - kFaceK) * Ramp(d.z(), 0.03, 0.05);
  t += (kChinK - t) * Ramp(d.z(), -0.06, -0.08);
  t += (kEarK - t) * Ramp(std::abs(d.y()), 0.068, 0.076);
  t += (kNoseK - t) * Ramp(d.x(), 0.095, 0.112) * Ramp(d.z(), 0.015, 0.0);
  for (float side : {1.0f, -1.0f}) {
    t += (kInnerCanthusK - t) * Bump(d, Eigen::Vector3f(0.08f, side * 0.018f, 0.02f), 0.013);
    t += (kOuterCanthusK - t) * Bump(d, Eigen::Vector3f(0.066f, side * 0.052f, 0.022f), 0.011);
  }
  return t;
}

}  // namespace

BodyZone BodyZoneOfPart(const std::string& part_name) {
  static const std::pair<const char*, BodyZone> kZones[] = {
      {"pelvis", BodyZone::kPelvis}, {"torso", BodyZone::kTorso},        {"neck", BodyZone::kNeck},
      {"head", BodyZone::kHead},     {"upper_arm", BodyZone::kUpperArm}, {"lower_arm", BodyZone::kLowerArm},
      {"hand", BodyZone::kHand},     {"thigh", BodyZone::kThigh},        {"shin", BodyZone::kShin},
      {"foot", BodyZone::kFoot}};
  for (const auto& [prefix, zone] : kZones)
    if (part_name.rfind(prefix, 0) == 0) return zone;
  HOILCD_CHECK_MSG(false, "unknown body part " + part_name);
  return BodyZone::kTorso;
}

GarmentField::GarmentField(uint64_t key, BodyZone zone, const Ensemble& ensemble, bool seated,
                           const GarmentOptions& options)
    : key_(key),
      zone_(zone),
      seated_(seated),
      short_sleeves_(ensemble.short_sleeves),
      skirt_(ensemble.skirt),
      fit_(ensemble.fit),
      options_(options) {}

float GarmentField::OffsetK(const Eigen::Vector3f& object_point, const Eigen::Vector3f&) const {
  return static_cast<float>(OffsetAt(object_point));
}

double GarmentField::OffsetAt(const Eigen::Vector3f& p) const {
  // Folds run round a limb (and the trunk), a few centimetres apart along it: noise stretched
  // 12 cm round, 3.5 cm along the axis (z in the rest pose).
  const double folds = ValueNoise3(key_, Eigen::Vector3f(p.x() / 0.12f, p.y() / 0.12f, p.z() / 0.035f));
  // Where the fabric stands off the skin and where it touches, in patches of about 10 cm.
  const double gaps = ValueNoise3(HashCombine(key_, 1), p / 0.10f);
  double contact = 0, hanging = 0;
  const double z = p.z(), x = p.x();
  switch (zone_) {
    case BodyZone::kTorso:
      contact = std::max(Ramp(z, 1.31, 1.39),                                // shoulders carry the garment
                         0.6 * Ramp(-x, 0.04, 0.08) * Ramp(z, 1.10, 1.20));  // upper back
      hanging = Ramp(z, kTorsoHemZ + 0.07, kTorsoHemZ);                      // the hem hangs loose
      break;
    case BodyZone::kUpperArm:
      contact = Ramp(z, kShoulderZ - 0.07, kShoulderZ - 0.02);
      if (short_sleeves_) hanging = Ramp(z, kElbowZ + 0.09, kElbowZ + 0.02);  // the sleeve's opening
      break;
    case BodyZone::kLowerArm:
      hanging = 0.3 + 0.7 * Ramp(z, kWristZ + 0.08, kWristZ + 0.01);  // loose sleeve, cuff
      break;
    case BodyZone::kPelvis:
      contact = seated_ ? 0.5 : 0.3;  // the waistband and, seated, the seat of the trousers
      break;
    case BodyZone::kThigh:
      if (skirt_) {
        hanging = 0.5 + 0.5 * Ramp(z, kKneeZ + 0.15, kKneeZ + 0.05);  // a skirt hangs free
      } else {
        contact = (seated_ ? 1.0 : 0.3) * Ramp(x, 0.0, 0.05);  // pulled taut over the thigh
      }
      break;
    case BodyZone::kShin:
      hanging = skirt_ ? 0.0 : 0.3 + 0.7 * Ramp(z, 0.22, 0.12);          // trouser legs, their hem
      if (seated_ && !skirt_) contact = Ramp(z, kKneeZ - 0.06, kKneeZ);  // the bent knee
      break;
    default:
      break;
  }
  return options_.fold_amplitude_k * folds + options_.gap_amplitude_k * fit_ * gaps +
         options_.contact_warming_k * contact - options_.hem_cooling_k * fit_ * hanging;
}

SkinField::SkinField(uint64_t key, BodyZone zone) : key_(key), zone_(zone) {}

float SkinField::OffsetK(const Eigen::Vector3f& object_point, const Eigen::Vector3f&) const {
  return static_cast<float>(OffsetAt(object_point));
}

double SkinField::OffsetAt(const Eigen::Vector3f& p) const {
  double t = 0;
  switch (zone_) {
    case BodyZone::kHead:
      t = FaceOffset(p);
      break;
    case BodyZone::kNeck:
      t = kNeckK + (kCollarK - kNeckK) * Ramp(p.z(), 1.42, 1.38);  // warmest where the collar shelters it
      break;
    case BodyZone::kHand:
      t = kHandBackK + (kFingertipK - kHandBackK) * Ramp(p.z(), kWristZ - 0.06, kFingertipZ + 0.02);
      break;
    case BodyZone::kLowerArm:
    case BodyZone::kUpperArm:
      t = kForearmK;
      break;
    default:
      break;
  }
  return t + kMottleK * ValueNoise3(key_, p / 0.02f);
}

float HairField::OffsetK(const Eigen::Vector3f& object_point, const Eigen::Vector3f&) const {
  return static_cast<float>(kHairK * ValueNoise3(key_, object_point / 0.02f));
}

}  // namespace hoilcd
