// The crowd's clothing: each person's garments drawn once, the garment and skin fields their
// body parts' materials point to, and the garments' surface temperatures at a time (closed form
// over the person's activities, so a frame's temperatures depend on its time only).
#include <algorithm>
#include <memory>

#include "hoilcd/core/util/random.h"
#include "hoilcd/sim/people/body_fields.h"
#include "hoilcd/sim/world/crowd.h"

namespace hoilcd {
namespace {

// The steps of a person's activity (what their garments head for, from when): seated people by
// their activity episodes, people standing still and walkers at one rate.
std::vector<std::pair<double, double>> MetabolicSteps(const Person& p) {
  if (!p.seated) return {{0.0, MetabolicRateMet(p.walker >= 0 ? "walking" : "standing")}};
  std::vector<std::pair<double, double>> steps = {{p.arrive_s, MetabolicRateMet("idle")}};
  for (const ActivityEpisode& e : p.activities) {
    const double met = MetabolicRateMet(e.name);
    if (met != steps.back().second) steps.emplace_back(std::max(e.start_s, steps.back().first), met);
  }
  return steps;
}

}  // namespace

void Crowd::Dress(Person* person) {
  const GarmentOptions& g = options_.garments;
  if (!g.enabled && !g.skin_pattern) return;
  Person& p = *person;
  p.ensemble = DrawEnsemble(seed_, p.person_id);
  p.clothing_steps.clear();
  for (const auto& [from_s, met] : MetabolicSteps(p)) {
    p.clothing_steps.push_back({from_s, SteadyClothing(p.ensemble, met, thermal_environment_)});
  }
  const auto& names = Skeleton::PartNames();
  const int hand = static_cast<int>(std::find(names.begin(), names.end(), "hand_left") - names.begin());
  const ThermalMaterial& skin = skeleton_->part(hand).materials.at(0);
  const double skin_c = stage_.MutableInstance(p.parts[hand]).materials.at(0).temperature_c;
  for (int i = 0; i < Skeleton::kPartCount; ++i) {
    const Asset& part = skeleton_->part(i);
    const BodyZone zone = BodyZoneOfPart(Skeleton::PartNames()[i]);
    const uint64_t key = HashCombine(seed_, HashString("crowd.body_field"), static_cast<uint64_t>(p.person_id),
                                     static_cast<uint64_t>(i));
    InstanceInfo& info = stage_.MutableInstance(p.parts[i]);
    for (size_t m = 0; m < part.materials.size(); ++m) {
      const std::string& region = part.materials[m].region;
      InstanceMaterial& im = info.materials[m];
      const bool bare_forearm = zone == BodyZone::kLowerArm && p.ensemble.short_sleeves && g.enabled;
      if (bare_forearm) {
        // The asset's forearm is sleeved; short sleeves bare it: skin's temperature and emissivity.
        im.emissivity = static_cast<float>(skin.emissivity);
        im.temperature_c = im.temperature_top_c = static_cast<float>(skin_c);
        stage_.Finish(&im);
      }
      if ((region == "skin" || bare_forearm) && g.skin_pattern) {
        fields_.push_back(std::make_unique<SkinField>(key, zone));
      } else if (region == "hair" && g.skin_pattern) {
        fields_.push_back(std::make_unique<HairField>(key));
      } else if (region.rfind("clothing", 0) == 0 && g.enabled && !bare_forearm) {
        fields_.push_back(std::make_unique<GarmentField>(key, zone, p.ensemble, p.seated, g));
      } else {
        continue;
      }
      im.field = fields_.back().get();
    }
  }
}

void Crowd::UpdateClothing(const Person& p, double time_s) {
  if (!options_.garments.enabled) return;
  const ClothingTemperatures t = ClothingAt(p.clothing_steps, options_.garments.time_constant_s, time_s);
  for (int i = 0; i < Skeleton::kPartCount; ++i) {
    const BodyZone zone = BodyZoneOfPart(Skeleton::PartNames()[i]);
    if (zone == BodyZone::kLowerArm && p.ensemble.short_sleeves) continue;
    const Asset& part = skeleton_->part(i);
    InstanceInfo& info = stage_.MutableInstance(p.parts[i]);
    for (size_t m = 0; m < part.materials.size(); ++m) {
      const std::string& region = part.materials[m].region;
      double c = 0;
      if (region == "clothing_upper") {
        c = t.upper_c;
      } else if (region == "clothing_lower") {
        c = zone == BodyZone::kShin ? t.legs_c : t.lower_c;
      } else {
        continue;
      }
      InstanceMaterial& im = info.materials[m];
      im.temperature_c = im.temperature_top_c = static_cast<float>(c);
      stage_.Finish(&im);
    }
  }
}

}  // namespace hoilcd
