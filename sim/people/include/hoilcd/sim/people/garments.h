// What people wear and how warm its surface is: an ensemble of ISO 9920 garments drawn per person,
// the clothing surface temperature t_cl of ISO 7730's heat balance for the upper and lower garments
// (each from its own local insulation), metabolic rates per activity (ISO 7730 Annex B), and the
// garments' smooth warming and cooling when the activity changes. docs/models/people.md has the
// figures and their sources.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// The scene's /crowd/garments.
struct GarmentOptions {
  bool enabled;              // clothing from the ensemble's heat balance and within-garment fields
  bool skin_pattern;         // face, neck, hands, bare forearms at published temperatures; hair texture
  double air_speed_m_s;      // air speed relative to the body, m/s (ISO 7730 h_c)
  double time_constant_s;    // how fast a garment's surface follows an activity change, s
  double fold_amplitude_k;   // folds: banded pattern along a limb, peak K
  double gap_amplitude_k;    // broad patches where the air gap under the fabric varies, peak K
  double contact_warming_k;  // where fabric presses on skin (shoulders, seated thighs), K
  double hem_cooling_k;      // hems, cuffs and loose hanging fabric, K

  GarmentOptions();  // the registered defaults
  static const OptionTable<GarmentOptions>& Table();
};

// ISO 7730 Table C.1 (from ISO 9920): one garment's whole-body insulation and what it covers.
enum class GarmentCover { kUpper, kLower, kLegs, kFeet };
struct Garment {
  const char* name;
  double clo;  // whole-body insulation I_clu, clo (1 clo = 0.155 m²·K/W)
  GarmentCover cover;
};

// What one person wears (the same wherever and whenever they appear).
struct Ensemble {
  std::vector<std::string> garments;  // names from the ISO 7730 Table C.1 list
  double total_clo = 0;               // ISO 7730 C.2: the sum of the garments' values
  double upper_clo = 0;               // local insulation of the upper garments over what they cover
  double lower_clo = 0;               // the same for trousers or a skirt (with underwear)
  double legs_clo = 0;                // the shins: trousers, or stockings under a skirt
  bool short_sleeves = false;         // forearms bare
  bool skirt = false;                 // shins covered by stockings only
  double fit = 1;                     // looseness: scales the air-gap patches and hems (0.6-1.4)
};
// Draws an office ensemble for a person (keyed by seed and person id): its summed insulation is
// 0.40-1.0 clo, ISO 7730's office range 0.5-1.0 clo as Table C.1's values sum it.
Ensemble DrawEnsemble(uint64_t seed, int person_id);

// The room as the heat balance sees it.
struct ThermalEnvironment {
  double air_c = 22;      // t_a
  double radiant_c = 22;  // mean radiant temperature t_r
  double air_speed_m_s = 0.1;
};

// ISO 7730:2005 eq. (2)-(5) with no external work: the clothing surface temperature, the
// convective coefficient and the clothing area factor at the solution.
struct ClothingBalance {
  double t_cl_c = 0, h_c = 0, f_cl = 1;
};
ClothingBalance SolveClothingSurface(double clo, double met, const ThermalEnvironment& environment);

// Metabolic rate, met (ISO 7730 Table B.1): seated relaxed 1.0, sedentary activity 1.2, standing
// 1.2, walking at 2 km/h 1.9. `activity` is a seated activity name, "standing" or "walking".
double MetabolicRateMet(const std::string& activity);

// Surface temperatures of a person's garments, °C.
struct ClothingTemperatures {
  double upper_c = 0, lower_c = 0, legs_c = 0;
};
ClothingTemperatures SteadyClothing(const Ensemble& ensemble, double met, const ThermalEnvironment& environment);

// The garments' mean surface temperature over the body surface they cover (Lund-Browder shares).
double MeanClothingC(const Ensemble& ensemble, const ClothingTemperatures& temperatures);

// From `from_s` on, the garments head for `target` (the steady state of the activity then).
struct ClothingStep {
  double from_s = 0;
  ClothingTemperatures target;
};
// First-order response to the steps (ascending; the first is the state before any change), in
// closed form: T(t) = T_0 + Σ_k (T_k − T_k−1)(1 − exp(−(t − s_k)/τ)) over the steps with s_k ≤ t.
ClothingTemperatures ClothingAt(const std::vector<ClothingStep>& steps, double time_constant_s, double time_s);

}  // namespace hoilcd
