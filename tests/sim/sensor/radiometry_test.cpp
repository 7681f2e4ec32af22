#include "hoilcd/sim/sensor/radiometry.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

namespace hoilcd {
namespace {

TEST(IntegratePlanckBand, ThreeHundredKelvinIn8To14UmIsAbout54_9) {
  // Independent check: the blackbody fraction F(0→λT) is 0.1403 at 2400 µm·K and 0.5160 at
  // 4200 µm·K, so the band holds 0.3757 of σT⁴/π = 146.20 W·m⁻²·sr⁻¹, i.e. 54.93.
  EXPECT_NEAR(IntegratePlanckBand(300.0), 54.93, 0.05);
}

TEST(IntegratePlanckBand, IsStrictlyIncreasingInTemperature) {
  double previous = IntegratePlanckBand(150.0, 8.0, 14.0, 2000);
  for (double t_k = 151.0; t_k <= 600.0; t_k += 1.0) {
    const double current = IntegratePlanckBand(t_k, 8.0, 14.0, 2000);
    ASSERT_GT(current, previous) << t_k;
    previous = current;
  }
}

TEST(PlanckBandSeries, AgreesWithNumericalIntegrationTo1e9) {
  for (double t_k : {200.0, 250.0, 295.15, 300.0, 350.0, 500.0}) {
    const double reference = IntegratePlanckBand(t_k);
    EXPECT_NEAR(PlanckBandSeries(t_k) / reference, 1.0, 1e-9) << t_k;
  }
  EXPECT_NEAR(PlanckBandSeries(300.0, 3.0, 5.0) / IntegratePlanckBand(300.0, 3.0, 5.0), 1.0, 1e-9);
}

TEST(BandRadianceTable, WithinOneMillionthOfDirectIntegrationFrom250To350K) {
  const BandRadianceTable table;
  double worst = 0.0;
  // Dense sweep deliberately off the 0.05 K grid (step 0.0137 K), checked at 0.1 % and
  // reported at its real worst case.
  for (double t_k = 250.0; t_k <= 350.0; t_k += 0.0137 * 20) {
    const double reference = IntegratePlanckBand(t_k, 8.0, 14.0, 2000);
    worst = std::max(worst, std::abs(table.RadianceFromKelvin(t_k) / reference - 1.0));
  }
  EXPECT_LT(worst, 1e-3);
  EXPECT_LT(worst, 1e-6);
}

TEST(BandRadianceTable, InverseRoundTripsTemperatureAndRadiance) {
  const BandRadianceTable table;
  for (double t_k = 250.0; t_k <= 350.0; t_k += 0.0137) {
    ASSERT_NEAR(table.KelvinFromRadiance(table.RadianceFromKelvin(t_k)), t_k, 1e-9) << t_k;
    // Inverse against the exact curve: within 0.1 % of temperature (and in fact < 1e-4 K).
    const double exact_radiance = PlanckBandSeries(t_k);
    ASSERT_NEAR(table.KelvinFromRadiance(exact_radiance), t_k, 1e-4) << t_k;
  }
  for (float t_c = -20.0f; t_c <= 70.0f; t_c += 0.173f) {
    ASSERT_NEAR(table.CelsiusFromRadiance(table.RadianceFromCelsius(t_c)), t_c, 2e-5f) << t_c;
  }
}

TEST(BandRadianceTable, ArrayInverseGivesTheBitsOfTheOneValueInverse) {
  // The LWIR default, and an MWIR table over a wide range whose inverse bins span many segments
  // at its cold end (the array form's long-walk path).
  for (const BandRadianceTable& table : {BandRadianceTable(), BandRadianceTable(3.0, 5.0, 150.0, 900.0)}) {
    std::vector<double> radiance;
    // Points on, just below and between the knots over the whole range, values outside it.
    for (double t_k = table.t_min_k() - 10; t_k <= table.t_max_k() + 10; t_k += 0.0125) {
      const double clamped = std::clamp(t_k, table.t_min_k(), table.t_max_k());
      radiance.push_back(table.RadianceFromKelvin(t_k));
      radiance.push_back(std::nextafter(radiance.back(), 0.0));
      radiance.push_back(PlanckBandSeries(clamped, table.lambda_min_um(), table.lambda_max_um()));
    }
    for (double v : {0.0, -1.0, 1e-300, 1e6, -0.0}) radiance.push_back(v);
    std::vector<double> kelvin(radiance.size());
    table.KelvinFromRadiance(radiance.data(), static_cast<int>(radiance.size()), kelvin.data());
    for (size_t i = 0; i < radiance.size(); ++i) {
      const double one = table.KelvinFromRadiance(radiance[i]);
      ASSERT_EQ(std::memcmp(&one, &kelvin[i], sizeof one), 0)
          << table.lambda_min_um() << " um, " << radiance[i] << ": " << one << " vs " << kelvin[i];
    }
    // In place, as the sensor model calls it.
    std::vector<double> in_place = radiance;
    table.KelvinFromRadiance(in_place.data(), static_cast<int>(in_place.size()), in_place.data());
    EXPECT_EQ(std::memcmp(in_place.data(), kelvin.data(), kelvin.size() * sizeof(double)), 0);
  }
}

TEST(BandRadianceTable, ClampsOutsideItsRange) {
  const BandRadianceTable table(8.0, 14.0, 200.0, 500.0);
  EXPECT_DOUBLE_EQ(table.RadianceFromKelvin(100.0), table.RadianceFromKelvin(200.0));
  EXPECT_DOUBLE_EQ(table.RadianceFromKelvin(900.0), table.RadianceFromKelvin(500.0));
  EXPECT_NEAR(table.KelvinFromRadiance(0.0), 200.0, 1e-9);
  EXPECT_NEAR(table.KelvinFromRadiance(1e6), 500.0, 1e-9);
}

TEST(BandRadianceTable, SlopeMatchesFiniteDifferenceOfIntegration) {
  const BandRadianceTable table;
  const double numeric = (IntegratePlanckBand(300.5, 8.0, 14.0, 2000) - IntegratePlanckBand(299.5, 8.0, 14.0, 2000));
  EXPECT_NEAR(table.SlopeFromKelvin(300.0), numeric, 1e-4);
  EXPECT_NEAR(table.SlopeFromKelvin(300.0), 0.838, 0.001);
}

TEST(SurfaceRadiance, IsothermalEnclosureReadsItsTemperatureWhateverTheEmissivity) {
  const BandRadianceTable table;
  const float wall = table.RadianceFromCelsius(22.0f);
  for (float emissivity : {0.05f, 0.5f, 0.9f, 1.0f}) {
    EXPECT_NEAR(table.CelsiusFromRadiance(SurfaceRadiance(emissivity, wall, wall)), 22.0f, 1e-4f);
  }
}

TEST(SurfaceRadiance, TableMirroringAPersonReadsAbout23_3C) {
  // SPEC.md: a 22 °C table (ε 0.90) mirroring a 34 °C person reads ~23.3 °C.
  const BandRadianceTable table;
  const float radiance = SurfaceRadiance(0.90f, table.RadianceFromCelsius(22.0f), table.RadianceFromCelsius(34.0f));
  EXPECT_NEAR(table.CelsiusFromRadiance(radiance), 23.26f, 0.02f);
}

}  // namespace
}  // namespace hoilcd
