#include "hoilcd/sim/people/garments.h"

#include <algorithm>
#include <cmath>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

constexpr double kM2KPerWattPerClo = 0.155;  // ISO 7730: 1 clo = 0.155 m²·K/W
constexpr double kWattPerM2PerMet = 58.15;   // ISO 7730: 1 met = 58.2 W/m² (58.15 in its Annex D code)

// ISO 7730:2005 Table C.1 (garment insulation I_clu, from ISO 9920).
constexpr Garment kTShirt{"T-shirt", 0.09, GarmentCover::kUpper};
constexpr Garment kShortShirt{"shirt, short sleeves", 0.15, GarmentCover::kUpper};
constexpr Garment kLongShirt{"shirt, long sleeves (normal)", 0.25, GarmentCover::kUpper};
constexpr Garment kBlouse{"blouse, long sleeves (lightweight)", 0.15, GarmentCover::kUpper};
constexpr Garment kThinSweater{"thin sweater", 0.20, GarmentCover::kUpper};
constexpr Garment kSweater{"sweater", 0.28, GarmentCover::kUpper};
constexpr Garment kJacket{"jacket", 0.35, GarmentCover::kUpper};
constexpr Garment kTrousers{"trousers (normal)", 0.25, GarmentCover::kLower};
constexpr Garment kLightTrousers{"trousers (lightweight)", 0.20, GarmentCover::kLower};
constexpr Garment kLightSkirt{"skirt, light (summer)", 0.15, GarmentCover::kLower};
constexpr Garment kHeavySkirt{"skirt, heavy (winter)", 0.25, GarmentCover::kLower};
constexpr Garment kPanties{"panties", 0.03, GarmentCover::kLower};
constexpr Garment kStockings{"nylon stockings", 0.03, GarmentCover::kLegs};
constexpr Garment kSocks{"socks", 0.02, GarmentCover::kFeet};
constexpr Garment kShoes{"shoes (thin soled)", 0.02, GarmentCover::kFeet};

// Shares of the body surface (Lund and Browder 1944, adult): trunk 26 %, upper arms 8 %,
// forearms 6 %, buttocks and genitals 6 %, thighs 19 %, lower legs 14 %.
constexpr double kUpperLongSleevesShare = 0.26 + 0.08 + 0.06;
constexpr double kUpperShortSleevesShare = 0.26 + 0.08;
constexpr double kTrousersShare = 0.06 + 0.19 + 0.14;
constexpr double kSkirtShare = 0.06 + 0.19;
constexpr double kStockingsShare = 0.19 + 0.14;

// The summed ensemble insulation an office ensemble keeps to (see DrawEnsemble).
constexpr double kMinEnsembleClo = 0.40, kMaxEnsembleClo = 1.0;

// An index drawn with the given relative weights.
template <size_t N>
size_t PickIndex(const double (&weights)[N], Rng* rng) {
  double total = 0;
  for (double w : weights) total += w;
  double pick = rng->Uniform() * total;
  for (size_t i = 0; i < N; ++i) {
    pick -= weights[i];
    if (pick < 0) return i;
  }
  return N - 1;
}

}  // namespace

GarmentOptions::GarmentOptions() { Table().FillDefaults(this); }

const OptionTable<GarmentOptions>& GarmentOptions::Table() {
  using O = GarmentOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("enabled", &O::enabled, true,
               "clothing temperatures from each person's garments (ISO 7730 heat balance) with folds, contact zones "
               "and hems; false: one temperature per clothing region (clothing_temperature_c)")
          .Add("skin_pattern", &O::skin_pattern, true,
               "face, neck, hands and bare forearms at their published temperatures, hair by its thickness; false: one "
               "skin and one hair temperature")
          .Add("air_speed_m_s", &O::air_speed_m_s, 0.1, "m/s", R::Closed(0, 1),
               "air speed relative to the body in the heat balance (ISO 7730 h_c)")
          .Add("time_constant_s", &O::time_constant_s, 300.0, "s", R::Closed(1, 3600),
               "how fast a garment's surface follows an activity change (estimate)")
          .Add("fold_amplitude_k", &O::fold_amplitude_k, 0.5, "K", R::Closed(0, 5),
               "folds: peak of the banded pattern along a limb (estimate)")
          .Add("gap_amplitude_k", &O::gap_amplitude_k, 0.8, "K", R::Closed(0, 5),
               "peak of the broad patches where the air gap under the fabric varies (estimate)")
          .Add("contact_warming_k", &O::contact_warming_k, 1.2, "K", R::Closed(0, 5),
               "warming where fabric presses on skin: shoulders, upper back, a seated person's thighs (estimate)")
          .Add("hem_cooling_k", &O::hem_cooling_k, 1.0, "K", R::Closed(0, 5),
               "cooling of hems, cuffs and loose hanging fabric (estimate)");
  return table;
}

Ensemble DrawEnsemble(uint64_t seed, int person_id) {
  Rng rng = KeyedRng(seed, "crowd.ensemble", static_cast<uint64_t>(person_id));
  static const Garment* const kTops[] = {&kTShirt, &kShortShirt, &kLongShirt, &kBlouse};
  static const double kTopWeights[] = {0.3, 0.2, 0.35, 0.15};
  static const Garment* const kLayers[] = {nullptr, &kThinSweater, &kSweater, &kJacket};
  static const double kLayerWeights[] = {0.45, 0.2, 0.15, 0.2};
  // Draw until the summed insulation is an office ensemble's: ISO 7730's office ensembles are
  // 0.5-1.0 clo as measured on a manikin (Table C.2), where summing Table C.1 (C.2's rule) gives
  // less for light ones ('underpants, short-sleeved shirt, light trousers, socks, shoes': 0.5
  // measured, 0.42 summed); so 0.40-1.0 clo summed.
  Ensemble e;
  for (int attempt = 0;; ++attempt) {
    e = Ensemble();
    const bool skirt = rng.Uniform() < 0.2;
    const Garment& lower =
        skirt ? (rng.Uniform() < 0.5 ? kLightSkirt : kHeavySkirt) : (rng.Uniform() < 0.7 ? kTrousers : kLightTrousers);
    const Garment& top = *kTops[PickIndex(kTopWeights, &rng)];
    const Garment* layer = kLayers[PickIndex(kLayerWeights, &rng)];
    std::vector<const Garment*> worn = {&top, &lower, &kPanties, &kSocks, &kShoes};
    if (layer != nullptr) worn.push_back(layer);
    if (skirt) worn.push_back(&kStockings);
    e.skirt = skirt;
    e.short_sleeves = (&top == &kTShirt || &top == &kShortShirt) && layer == nullptr;
    double upper = 0, lower_sum = 0;
    for (const Garment* g : worn) {
      e.garments.push_back(g->name);
      e.total_clo += g->clo;
      if (g->cover == GarmentCover::kUpper) upper += g->clo;
      if (g->cover == GarmentCover::kLower) lower_sum += g->clo;
    }
    e.upper_clo = upper / (e.short_sleeves ? kUpperShortSleevesShare : kUpperLongSleevesShare);
    e.lower_clo = lower_sum / (skirt ? kSkirtShare : kTrousersShare);
    e.legs_clo = skirt ? kStockings.clo / kStockingsShare : e.lower_clo;
    e.fit = rng.Uniform(0.6, 1.4);
    if ((e.total_clo >= kMinEnsembleClo && e.total_clo <= kMaxEnsembleClo) || attempt >= 63) break;
  }
  return e;
}

ClothingBalance SolveClothingSurface(double clo, double met, const ThermalEnvironment& environment) {
  HOILCD_CHECK(clo >= 0 && met > 0);
  const double i_cl = clo * kM2KPerWattPerClo;
  const double m = met * kWattPerM2PerMet;
  ClothingBalance b;
  b.f_cl = i_cl <= 0.078 ? 1.0 + 1.290 * i_cl : 1.05 + 0.645 * i_cl;
  const double h_forced = 12.1 * std::sqrt(environment.air_speed_m_s);
  const double t_ra4 = std::pow(environment.radiant_c + 273.0, 4);
  const double t_a = environment.air_c;
  // t_cl = 35.7 − 0.028 M − I_cl {3.96e-8 f_cl [(t_cl + 273)^4 − (t_r + 273)^4] + f_cl h_c (t_cl − t_a)},
  // h_c = max(2.38 |t_cl − t_a|^0.25, 12.1 √v): damped fixed-point iteration (ISO 7730 Annex D does
  // the same with a halving step), to 1e-6 K.
  double t_cl = t_a + (35.5 - t_a) / (3.5 * i_cl + 0.1);
  for (int i = 0; i < 500; ++i) {
    b.h_c = std::max(h_forced, 2.38 * std::pow(std::abs(t_cl - t_a), 0.25));
    const double next = 35.7 - 0.028 * m -
                        i_cl * (3.96e-8 * b.f_cl * (std::pow(t_cl + 273.0, 4) - t_ra4) + b.f_cl * b.h_c * (t_cl - t_a));
    const double step = 0.5 * (next - t_cl);
    t_cl += step;
    if (std::abs(step) < 1e-7) break;
  }
  b.t_cl_c = t_cl;
  b.h_c = std::max(h_forced, 2.38 * std::pow(std::abs(t_cl - t_a), 0.25));
  return b;
}

double MetabolicRateMet(const std::string& activity) {
  if (activity == "idle" || activity == "head_turn") return 1.0;                            // seated, relaxed
  if (activity == "talking" || activity == "drinking" || activity == "typing") return 1.2;  // sedentary activity
  if (activity == "standing") return 1.2;                                                   // standing, relaxed
  HOILCD_CHECK_MSG(activity == "walking", activity);
  return 1.9;  // walking on the level at 2 km/h
}

ClothingTemperatures SteadyClothing(const Ensemble& ensemble, double met, const ThermalEnvironment& environment) {
  ClothingTemperatures t;
  t.upper_c = SolveClothingSurface(ensemble.upper_clo, met, environment).t_cl_c;
  t.lower_c = SolveClothingSurface(ensemble.lower_clo, met, environment).t_cl_c;
  t.legs_c = SolveClothingSurface(ensemble.legs_clo, met, environment).t_cl_c;
  return t;
}

double MeanClothingC(const Ensemble& e, const ClothingTemperatures& t) {
  const double upper = e.short_sleeves ? kUpperShortSleevesShare : kUpperLongSleevesShare;
  const double lower = e.skirt ? kSkirtShare : kTrousersShare - 0.14;  // trousers: the shins are legs_c
  const double legs = 0.14;
  return (upper * t.upper_c + lower * t.lower_c + legs * t.legs_c) / (upper + lower + legs);
}

ClothingTemperatures ClothingAt(const std::vector<ClothingStep>& steps, double time_constant_s, double time_s) {
  HOILCD_CHECK(!steps.empty() && time_constant_s > 0);
  ClothingTemperatures t = steps[0].target;
  for (size_t k = 1; k < steps.size() && steps[k].from_s <= time_s; ++k) {
    const double w = 1.0 - std::exp(-(time_s - steps[k].from_s) / time_constant_s);
    t.upper_c += w * (steps[k].target.upper_c - steps[k - 1].target.upper_c);
    t.lower_c += w * (steps[k].target.lower_c - steps[k - 1].target.lower_c);
    t.legs_c += w * (steps[k].target.legs_c - steps[k - 1].target.legs_c);
  }
  return t;
}

}  // namespace hoilcd
