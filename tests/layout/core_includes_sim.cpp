// Must not compile: core's targets do not see the simulator's headers (tests/layout).
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/sim/scene/scene.h"
