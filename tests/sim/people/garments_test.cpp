#include "hoilcd/sim/people/garments.h"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "hoilcd/sim/people/body_fields.h"

namespace hoilcd {
namespace {

// ISO 7730:2005 eq. (1): PMV from the clothing surface temperature the balance solves.
double Pmv(double ta, double tr, double v, double rh_pct, double met, double clo) {
  const ClothingBalance b = SolveClothingSurface(clo, met, {ta, tr, v});
  const double m = met * 58.15;
  const double pa = rh_pct * 10 * std::exp(16.6536 - 4030.183 / (ta + 235));
  const double hl1 = 3.05e-3 * (5733 - 6.99 * m - pa);
  const double hl2 = m > 58.15 ? 0.42 * (m - 58.15) : 0.0;
  const double hl3 = 1.7e-5 * m * (5867 - pa);
  const double hl4 = 0.0014 * m * (34 - ta);
  const double hl5 = 3.96e-8 * b.f_cl * (std::pow(b.t_cl_c + 273, 4) - std::pow(tr + 273, 4));
  const double hl6 = b.f_cl * b.h_c * (b.t_cl_c - ta);
  return (0.303 * std::exp(-0.036 * m) + 0.028) * (m - hl1 - hl2 - hl3 - hl4 - hl5 - hl6);
}

// ISO 7730:2005 Annex D, Table D.1: the standard's own examples of its program's output. The PMV
// follows from t_cl (the heat losses are evaluated at it), so matching PMV to its two printed
// decimals checks the clothing surface temperature.
TEST(Garments, ClothingSurfaceTemperatureReproducesIso7730TableD1) {
  struct Row {
    double ta, tr, v, rh, met, clo, pmv;
  };
  const Row rows[] = {{22, 22, 0.1, 60, 1.2, 0.5, -0.75}, {27, 27, 0.1, 60, 1.2, 0.5, 0.77},
                      {27, 27, 0.3, 60, 1.2, 0.5, 0.44},  {23.5, 25.5, 0.1, 60, 1.2, 0.5, -0.01},
                      {19, 19, 0.1, 40, 1.2, 1.0, -0.60}, {23, 21, 0.1, 40, 1.2, 1.0, 0.05},
                      {23, 21, 0.3, 40, 1.2, 1.0, -0.16}, {22, 22, 0.1, 60, 1.6, 0.5, 0.05}};
  for (const Row& r : rows) {
    EXPECT_NEAR(Pmv(r.ta, r.tr, r.v, r.rh, r.met, r.clo), r.pmv, 0.015) << r.ta << " " << r.met << " " << r.clo;
  }
  // And the balance itself holds at the solution.
  const ClothingBalance b = SolveClothingSurface(0.5, 1.2, {22, 22, 0.1});
  const double i_cl = 0.5 * 0.155;
  const double rhs = 35.7 - 0.028 * 1.2 * 58.15 -
                     i_cl * (3.96e-8 * b.f_cl * (std::pow(b.t_cl_c + 273, 4) - std::pow(22 + 273.0, 4)) +
                             b.f_cl * b.h_c * (b.t_cl_c - 22));
  EXPECT_NEAR(b.t_cl_c, rhs, 1e-4);
  EXPECT_GT(b.t_cl_c, 27.0);
  EXPECT_LT(b.t_cl_c, 31.0);
}

TEST(Garments, MoreInsulationAndMoreActivityGiveCoolerClothingSurfaces) {
  const ThermalEnvironment room{22, 22, 0.1};
  EXPECT_GT(SolveClothingSurface(0.5, 1.0, room).t_cl_c, SolveClothingSurface(1.0, 1.0, room).t_cl_c);
  EXPECT_GT(SolveClothingSurface(0.7, 1.0, room).t_cl_c, SolveClothingSurface(0.7, 1.9, room).t_cl_c);
  EXPECT_DOUBLE_EQ(MetabolicRateMet("idle"), 1.0);
  EXPECT_DOUBLE_EQ(MetabolicRateMet("typing"), 1.2);
  EXPECT_DOUBLE_EQ(MetabolicRateMet("walking"), 1.9);
}

TEST(Garments, EnsemblesAreOfficeEnsemblesStablePerPersonAndVaried) {
  int short_sleeves = 0, skirts = 0;
  double lo = 1e9, hi = -1e9;
  for (int id = 0; id < 200; ++id) {
    const Ensemble e = DrawEnsemble(1, id);
    EXPECT_GE(e.total_clo, 0.40 - 1e-9);
    EXPECT_LE(e.total_clo, 1.0 + 1e-9);
    EXPECT_EQ(DrawEnsemble(1, id).garments, e.garments);
    short_sleeves += e.short_sleeves;
    skirts += e.skirt;
    lo = std::min(lo, e.total_clo), hi = std::max(hi, e.total_clo);
  }
  EXPECT_GT(short_sleeves, 10);
  EXPECT_GT(skirts, 10);
  EXPECT_GT(hi - lo, 0.3);
}

// ISO 7730's office clothing (0.5-1.0 clo, Table C.2; the lightest, 0.5 clo, sums to 0.42 clo from
// Table C.1) at seated-quiet to sedentary activity (1.0-1.2 met, Annex B) in a 22 °C room puts the
// whole-body clothing surface at t_cl(1.0 clo, 1.2 met) to t_cl(0.42 clo, 1.0 met), 26.8-29.6 °C.
// Each drawn ensemble's garments, each at its own local insulation, average (over the body
// surface they cover) within it, to 0.3 K.
TEST(Garments, EveryEnsemblesMeanClothingTemperatureIsInIso7730sOfficeRange) {
  const ThermalEnvironment room{22, 22, 0.1};
  const double lo = SolveClothingSurface(1.0, 1.2, room).t_cl_c, hi = SolveClothingSurface(0.42, 1.0, room).t_cl_c;
  double seen_lo = 1e9, seen_hi = -1e9;
  for (int id = 0; id < 500; ++id) {
    const Ensemble e = DrawEnsemble(1, id);
    for (double met : {1.0, 1.2}) {
      const double mean = MeanClothingC(e, SteadyClothing(e, met, room));
      seen_lo = std::min(seen_lo, mean), seen_hi = std::max(seen_hi, mean);
    }
  }
  std::printf("ISO 7730 office range %.2f-%.2f °C; ensembles' means %.2f-%.2f °C\n", lo, hi, seen_lo, seen_hi);
  EXPECT_GE(seen_lo, lo - 0.3);
  EXPECT_LE(seen_hi, hi + 0.3);
}

// The response to a step is a smooth exponential with the set time constant, from where the
// earlier steps had brought it.
TEST(Garments, ClothingFollowsActivityStepsInClosedForm) {
  std::vector<ClothingStep> steps = {{0, {28, 27, 27}}, {100, {27, 26, 26}}, {400, {28, 27, 27}}};
  EXPECT_DOUBLE_EQ(ClothingAt(steps, 300, 50).upper_c, 28);
  EXPECT_NEAR(ClothingAt(steps, 300, 400).upper_c, 28 - (1 - std::exp(-1.0)), 1e-12);
  const double before = ClothingAt(steps, 300, 400 - 1e-3).upper_c, after = ClothingAt(steps, 300, 400 + 1e-3).upper_c;
  EXPECT_NEAR(before, after, 1e-5) << "no jump at a step";
  EXPECT_NEAR(ClothingAt(steps, 300, 1e6).lower_c, 27, 1e-9);
}

TEST(Garments, FieldsDifferBetweenPeopleAndStayWithinTheirAmplitudes) {
  const GarmentOptions options;
  const Ensemble e = DrawEnsemble(1, 3);
  const GarmentField a(11, BodyZone::kTorso, e, true, options), b(12, BodyZone::kTorso, e, true, options);
  double differ = 0;
  const double bound = options.fold_amplitude_k + 1.4 * options.gap_amplitude_k + options.contact_warming_k +
                       1.4 * options.hem_cooling_k;
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3f p(0.12f, -0.1f + 0.002f * i, 1.0f + 0.004f * i);
    differ += std::abs(a.OffsetAt(p) - b.OffsetAt(p));
    EXPECT_LE(std::abs(a.OffsetAt(p)), bound);
  }
  EXPECT_GT(differ / 100, 0.1);
  // The face: inner canthus warmest, nose and ears cooler than the forehead.
  const SkinField face(5, BodyZone::kHead);
  const Eigen::Vector3f c(0.005f, 0, 1.60f);
  const double forehead = face.OffsetAt(c + Eigen::Vector3f(0.08f, 0, 0.06f));
  EXPECT_NEAR(forehead, -0.6, 0.2);
  EXPECT_GT(face.OffsetAt(c + Eigen::Vector3f(0.08f, 0.018f, 0.02f)), forehead + 0.5);
  EXPECT_LT(face.OffsetAt(c + Eigen::Vector3f(0.118f, 0, -0.015f)), forehead - 1.0);
  EXPECT_LT(face.OffsetAt(c + Eigen::Vector3f(-0.005f, 0.09f, -0.005f)), forehead - 1.0);
  const SkinField hand(5, BodyZone::kHand);
  EXPECT_LT(hand.OffsetAt(Eigen::Vector3f(0.18f, 0.18f, 0.68f)),
            hand.OffsetAt(Eigen::Vector3f(0.18f, 0.18f, 0.81f)) - 1.0)
      << "fingers cooler than the back of the hand";
}

}  // namespace
}  // namespace hoilcd
