// The heat-trace measure of `hoilcd inspect`: the exponential fit and the section's figures.
#include "hoilcd/bench/report/inspect_heat_traces.h"

#include <cmath>

#include <gtest/gtest.h>

namespace hoilcd {
namespace {

std::vector<HeatTraceSample> Decay(double amplitude_k, double tau_s, double from_s, double to_s, double step_s) {
  std::vector<HeatTraceSample> out;
  for (double t = from_s; t <= to_s; t += step_s) out.push_back({0, t, amplitude_k * std::exp(-t / tau_s), 100});
  return out;
}

TEST(HeatTraces, FitRecoversAnExponentialAndNeedsASpan) {
  const ExponentialFit fit = FitExponentialDecay(Decay(1.9, 120, 5, 40, 0.5), 0.1);
  EXPECT_NEAR(fit.tau_s, 120, 1e-6);
  EXPECT_NEAR(fit.amplitude_k, 1.9, 1e-9);
  EXPECT_TRUE(std::isnan(FitExponentialDecay(Decay(1.9, 120, 5, 5.5, 0.25), 0.1).tau_s));  // under 1 s
  EXPECT_TRUE(std::isnan(FitExponentialDecay(Decay(0.05, 120, 5, 40, 0.5), 0.1).tau_s));   // all below the floor
}

TEST(HeatTraces, SectionReportsSightingsAndLifetime) {
  HeatTrace seen{"2.4", 1010, Decay(2.0, 120, 0, 200, 10)};
  HeatTrace unseen{"5.3", 1010, {}};
  const InspectSection s = HeatTraceSection({seen, unseen});
  EXPECT_EQ(s.Find("left_seats")->value, 2);
  EXPECT_EQ(s.Find("left_seats_seen")->value, 1);
  EXPECT_EQ(s.Find("sightings")->value, 21);
  // 2 K · exp(−t/120) ≥ 1 K up to 83.2 s: sightings at 0..80 s are warm, 90 s is the first cool one.
  EXPECT_EQ(s.Find("last_warm_s")->value, 80);
  EXPECT_EQ(s.Find("first_cool_s")->value, 90);
  EXPECT_NEAR(s.Find("fitted_tau_s")->value, 120, 1e-6);
  EXPECT_NEAR(s.Find("lifetime_s")->value, 120 * std::log(2.0), 1e-6);
}

}  // namespace
}  // namespace hoilcd
