// Cost of the sensor model per 256×192 frame with every effect on, and of building the band
// radiance table. Run: build/bin/sensor_bench
#include <benchmark/benchmark.h>

#include "hoilcd/sim/sensor/radiometry.h"
#include "hoilcd/sim/sensor/sensor.h"

namespace hoilcd {
namespace {

void BM_SensorApplyAllEffects(benchmark::State& state) {
  const BandRadianceTable table;
  SensorModel model(SensorOptions(), 256, 192, 25.0, 1, &table, static_cast<int>(state.range(0)));
  cv::Mat radiance(192, 256, CV_32F, cv::Scalar(table.RadianceFromCelsius(22.0f)));
  radiance(cv::Rect(100, 50, 40, 90)).setTo(table.RadianceFromCelsius(34.0f));
  int frame = 0;
  for (auto _ : state) benchmark::DoNotOptimize(model.Apply(frame++, radiance));
  state.SetItemsProcessed(state.iterations() * 256 * 192);
}
BENCHMARK(BM_SensorApplyAllEffects)->Arg(1)->Arg(2)->ArgName("threads")->Unit(benchmark::kMillisecond);

void BM_BandRadianceTableBuild(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(BandRadianceTable());
}
BENCHMARK(BM_BandRadianceTableBuild)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace hoilcd

BENCHMARK_MAIN();
