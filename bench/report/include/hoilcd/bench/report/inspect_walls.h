// How much structure the room's own surfaces show (`hoilcd inspect`'s "walls" section): per view,
// the spread (p95 − p5) of the true temperature over wall pixels, and over wall, ceiling and floor
// pixels together; the median over views. Cold corners, a radiator's plume, sun patches and the
// texture of room_surfaces.md raise it; a perfectly even room has only its vertical gradient.
#pragma once

#include "hoilcd/bench/report/inspect.h"

namespace hoilcd {

// Views with fewer than this many pixels of a class do not count towards its median.
constexpr int kMinSurfacePixels = 500;

// From the EXR ground truth of up to kViewFramesSampled evenly spaced frames.
InspectSection WallSection(const Dataset& dataset, int threads);

}  // namespace hoilcd
