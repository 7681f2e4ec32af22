// A loop-closure method hoilcd does not ship: each frame's column profile (mean 8-bit intensity
// per image column, i.e. where warm things sit left to right); two frames are alike when their
// profiles are close. Global, like the thumbnail baseline, and cheap.
#pragma once

#include <memory>

#include "hoilcd/bench/methods/loop_closure_method.h"

std::unique_ptr<hoilcd::LoopClosureMethod> MakeColumnProfileMethod();
