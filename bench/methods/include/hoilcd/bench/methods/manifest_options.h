// What the front ends take from the dataset instead of from their options: the temperature window
// of the 8-bit frames (the person detector reads temperatures from them) and the frame rate
// (ByteTrack keeps a lost track for a number of frames scaled by it). RunBench applies it to every
// dataset it reads. (The point-set methods read the image height, which their vertical filter's
// tolerance is a fraction of, from the dataset themselves: point_set/point_set_method.cpp.)
#pragma once

#include "hoilcd/bench/methods/bench_options.h"
#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

// `options` with the fields above set from `manifest`.
BenchOptions WithManifest(BenchOptions options, const DatasetManifest& manifest);

}  // namespace hoilcd
