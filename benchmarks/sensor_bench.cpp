// Cost of the sensor model per 256×192 frame with every effect on, of its pixel response alone
// (against the σ 0.5 px Gaussian it replaced), and of building the band radiance table.
// Run: build/bin/sensor_bench
#include <benchmark/benchmark.h>
#include <opencv2/imgproc.hpp>

#include "hoilcd/sim/sensor/optics.h"
#include "hoilcd/sim/sensor/radiometry.h"
#include "hoilcd/sim/sensor/sensor.h"

namespace hoilcd {
namespace {

cv::Mat BenchRadiance(const BandRadianceTable& table) {
  cv::Mat radiance(192, 256, CV_32F, cv::Scalar(table.RadianceFromCelsius(22.0f)));
  radiance(cv::Rect(100, 50, 40, 90)).setTo(table.RadianceFromCelsius(34.0f));
  return radiance;
}

void BM_SensorApplyAllEffects(benchmark::State& state) {
  const BandRadianceTable table;
  SensorModel model(SensorOptions(), 256, 192, 25.0, 1, &table, static_cast<int>(state.range(0)));
  const cv::Mat radiance = BenchRadiance(table);
  int frame = 0;
  for (auto _ : state) benchmark::DoNotOptimize(model.Apply(frame++, radiance));
  state.SetItemsProcessed(state.iterations() * 256 * 192);
}
BENCHMARK(BM_SensorApplyAllEffects)->Arg(1)->Arg(2)->ArgName("threads")->Unit(benchmark::kMillisecond);

void BM_PixelResponseFilter(benchmark::State& state) {
  const BandRadianceTable table;
  const PixelResponseFilter filter(PixelResponseOf(SensorOptions(), table), 256, 192);
  const cv::Mat radiance = BenchRadiance(table);
  cv::Mat out;
  for (auto _ : state) {
    filter.Apply(radiance, &out, static_cast<int>(state.range(0)));
    benchmark::DoNotOptimize(out.data);
  }
}
BENCHMARK(BM_PixelResponseFilter)->Arg(1)->Arg(2)->ArgName("threads")->Unit(benchmark::kMillisecond);

// The optics model of simulator revisions 1-21, for the ratio.
void BM_GaussianBlurHalfPixel(benchmark::State& state) {
  const BandRadianceTable table;
  const cv::Mat radiance = BenchRadiance(table);
  cv::Mat out;
  for (auto _ : state) {
    cv::GaussianBlur(radiance, out, cv::Size(0, 0), 0.5, 0.5, cv::BORDER_REFLECT);
    benchmark::DoNotOptimize(out.data);
  }
}
BENCHMARK(BM_GaussianBlurHalfPixel)->Unit(benchmark::kMillisecond);

void BM_BandRadianceTableBuild(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(BandRadianceTable());
}
BENCHMARK(BM_BandRadianceTableBuild)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace hoilcd

BENCHMARK_MAIN();
