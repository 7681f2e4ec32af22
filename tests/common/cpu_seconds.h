// The CPU seconds a step costs this process (every thread, user and system): what a test that
// bounds a step's cost measures, because a loaded machine stretches wall time but not CPU time.
#pragma once

#include <functional>

#include <time.h>

namespace hoilcd::test {

inline double ProcessCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

inline double CpuSecondsOf(const std::function<void()>& fn) {
  const double start = ProcessCpuSeconds();
  fn();
  return ProcessCpuSeconds() - start;
}

}  // namespace hoilcd::test
