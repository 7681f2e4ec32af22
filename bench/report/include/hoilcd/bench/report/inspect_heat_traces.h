// Heat traces of left seats, measured from a dataset folder alone (docs/models/contact_heat.md):
// after each leave event whose seat nobody takes again, the chair's pixels are found in the
// EXR (class chair, placed in the world by their depth Z and the true camera pose, inside the
// chair's footprint from footprints.json, within 5 cm of the seat's height) and their
// warmest part (90th percentile of T_true) is compared with the room's air (scene.json's
// room.environment_temperature_c). `hoilcd inspect` reports how long the traces stay ≥ 1 K.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "hoilcd/bench/report/inspect.h"
#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

struct HeatTraceSample {
  int frame = 0;
  double since_leave_s = 0;  // time since the leave event, s
  double excess_k = 0;       // p90 of the chair's T_true minus the room's air, K
  int pixels = 0;            // chair pixels found in the chair's footprint
};

struct HeatTrace {
  std::string seat;  // "table.seat", as in events.json
  int leave_frame = 0;
  std::vector<HeatTraceSample> samples;  // frames that see at least kHeatTraceMinPixels of the chair
};

constexpr int kHeatTraceMinPixels = 12;

// Every left seat's trace, reading at most `max_frames` evenly spaced frames after each leave
// (until the seat is taken again or the dataset ends) on `threads` threads.
std::vector<HeatTrace> MeasureHeatTraces(const Dataset& dataset, int threads, int max_frames = 400);

// log(excess) = log(amplitude) − t / τ, least squares over the samples with excess ≥ min_excess_k
// (NaN when fewer than 3 samples or they span less than 1 s).
struct ExponentialFit {
  double amplitude_k = NAN, tau_s = NAN;
  int samples = 0;
};
ExponentialFit FitExponentialDecay(const std::vector<HeatTraceSample>& samples, double min_excess_k);

// The inspect section: left seats, those seen, the share of sightings ≥ 1 K, the latest
// sighting ≥ 1 K and the earliest < 1 K after the leave, and the pooled exponential fit's τ and
// the lifetime ≥ 1 K it implies.
InspectSection HeatTraceSection(const std::vector<HeatTrace>& traces);

}  // namespace hoilcd
