// Temperature fields over a clothed body, in each body part's own frame (the rest pose: z up,
// x forward, y to the left), so they move with the part: within a garment, folds banded along the
// limb, broad air-gap patches, warmer contact zones and cooler hems; over skin, the face's regions,
// neck, hands and fingers, bare forearms; over hair, its thickness. docs/models/people.md has the figures and sources.
#pragma once

#include <cstdint>
#include <string>

#include "hoilcd/sim/assets/surface_field.h"
#include "hoilcd/sim/people/garments.h"

namespace hoilcd {

// The kind of body part a field lies on (Skeleton::PartNames without the side).
enum class BodyZone { kPelvis, kTorso, kNeck, kHead, kUpperArm, kLowerArm, kHand, kThigh, kShin, kFoot };
// "upper_arm_left" -> kUpperArm; throws on an unknown part name.
BodyZone BodyZoneOfPart(const std::string& part_name);

// A garment's offset from its surface temperature t_cl. `key` is the person's and part's (so
// every person has their own folds); `options` must outlive the field.
class GarmentField : public SurfaceField {
 public:
  GarmentField(uint64_t key, BodyZone zone, const Ensemble& ensemble, bool seated, const GarmentOptions& options);
  float OffsetK(const Eigen::Vector3f& object_point, const Eigen::Vector3f& world_point) const override;
  // The same, of a point in the part's rest frame (m, body scale 1).
  double OffsetAt(const Eigen::Vector3f& rest_point) const;

 private:
  uint64_t key_;
  BodyZone zone_;
  bool seated_, short_sleeves_, skirt_;
  double fit_;
  const GarmentOptions& options_;
};

// Exposed skin's offset from the person's skin temperature (crowd.skin_temperature_c, drawn per
// person): the face's regions, neck, back of the hand and fingers, bare forearms, and a faint
// keyed mottle.
class SkinField : public SurfaceField {
 public:
  SkinField(uint64_t key, BodyZone zone);
  float OffsetK(const Eigen::Vector3f& object_point, const Eigen::Vector3f& world_point) const override;
  double OffsetAt(const Eigen::Vector3f& rest_point) const;

 private:
  uint64_t key_;
  BodyZone zone_;
};

// Hair's offset from the person's hair temperature: thicker and thinner hair in keyed patches of
// about 2 cm (estimate, docs/models/people.md).
class HairField : public SurfaceField {
 public:
  explicit HairField(uint64_t key) : key_(key) {}
  float OffsetK(const Eigen::Vector3f& object_point, const Eigen::Vector3f& world_point) const override;

 private:
  uint64_t key_;
};

}  // namespace hoilcd
