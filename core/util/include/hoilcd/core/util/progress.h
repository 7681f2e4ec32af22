// The one progress reporter: a bar with count, rate and time left on a terminal (reporters
// running at once, e.g. a render and the calibration beside it, share the line); plain periodic
// lines when stderr is not a terminal; silent when quiet. Thread-safe Update().
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace hoilcd {

class ProgressReporter {
 public:
  // unit names what is counted ("frames", "pairs").
  ProgressReporter(std::string title, int64_t total, std::string unit, bool quiet = false);
  ~ProgressReporter();
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  void Update(int64_t done_increment = 1);
  void Done();
  double ElapsedSeconds() const;

  // Process-wide default for quietness (set by `hoilcd --quiet`).
  static void SetQuietByDefault(bool quiet);

  // While it lives, reporters made on this thread put `prefix` before their title: a pipeline
  // run beside another ("calibration ") tells its lines apart.
  class ThreadTitlePrefix {
   public:
    explicit ThreadTitlePrefix(std::string prefix);
    ~ThreadTitlePrefix();
    ThreadTitlePrefix(const ThreadTitlePrefix&) = delete;
    ThreadTitlePrefix& operator=(const ThreadTitlePrefix&) = delete;

   private:
    std::string previous_;
  };

  // While it lives, reporters made on this thread are quiet: work done in many small calls (the
  // online bench scores each query alone) would print a line per call.
  class ThreadQuiet {
   public:
    ThreadQuiet();
    ~ThreadQuiet();
    ThreadQuiet(const ThreadQuiet&) = delete;
    ThreadQuiet& operator=(const ThreadQuiet&) = delete;
  };

 private:
  void Print(bool final_line);
  // Title, count, rate and time left (or taken, on the final line), with a bar `bar_width`
  // characters wide for a terminal, or as a plain line when bar_width is 0.
  std::string Status(int bar_width, bool final_line) const;

  std::string title_;
  std::string unit_;
  int64_t total_;
  bool quiet_;
  bool tty_;
  bool done_ = false;
  std::atomic<int64_t> count_{0};
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_print_;
  std::mutex mutex_;
};

}  // namespace hoilcd
