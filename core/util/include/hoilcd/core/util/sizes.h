// The largest sizes hoilcd takes from a user, each the bound of every option and file field that
// counts pixels of an image side or frames of a sequence, so that no value a user can set asks for
// more than a machine holds or runs without end. (Requests within them that still exceed this
// machine's memory are refused by CheckAllocation, memory.h.)
#pragma once

namespace hoilcd {

// Width or height of a camera image: the dataset format's bound (CameraIntrinsics::Check); thermal
// cameras have at most 1280 px a side, the scene file's camera at most 4096.
constexpr int kMaxImageSidePx = 8192;

// Frames of a sequence: the scene file's bound on "frames" (scenes/scene.schema.json), 11 hours
// at 25 Hz. Every frame count and frame gap a user sets is at most this.
constexpr int kMaxFrames = 1000000;

// Nesting of a JSON document hoilcd reads (ParseJson, json_reader.h): its deepest files (a scene
// with a floor and runs, a report.json) nest about 8 levels, and deeper text would make every
// recursive step after parsing (copies, schema checks) a stack overflow.
constexpr int kMaxJsonDepth = 64;

// Seeds, wherever a user gives one (scene, --seed, suite, generator): the largest whole number a
// JSON reader that keeps numbers as doubles (Python's json with floats, JavaScript) holds exactly,
// 2^53. Compared as an integer, never through a double that would round 2^53 + 1 down to it.
constexpr unsigned long long kMaxSeed = 9007199254740992ULL;

}  // namespace hoilcd
