// Recording runs: a dataset may hold several runs of the robot over the same place (the same floor
// at several times of day, with other occupants), one after the other in frame order. runs.json
// says where each starts and when it was recorded; a dataset without it is one run.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace hoilcd {

struct RunRecord {
  int first_frame = 0;        // the run's first frame in the dataset
  int frames = 0;             // its frames
  double time_of_day_h = -1;  // h, local time at the run's start (-1: not stated, a single-run dataset)
  int day = 0;                // days after the first run's day
  double start_time_s = 0;    // s, poses.csv's t at the run's first frame: time since the first run began
  uint64_t seed = 0;          // the run's seed: its crowd, robot noise and camera noise (0: not stated)
  int end_frame() const { return first_frame + frames; }
};

// runs.json: {"runs": [{"first_frame", "frames", "time_of_day_h", "day", "start_time_s", "seed"}, ...]};
// numbers read back exactly.
std::string RunsToJson(const std::vector<RunRecord>& runs);
// Checks the runs tile frames 0..frame_count-1 in order, starting later than the last ended; errors
// name the file and the JSON pointer.
std::vector<RunRecord> RunsFromJson(const std::string& text, const std::string& path, int frame_count);

// One run over every frame: what a dataset without runs.json holds.
std::vector<RunRecord> SingleRun(int frame_count);

// The run of each frame (size: the runs' frames).
std::vector<int> RunOfFrames(const std::vector<RunRecord>& runs);

}  // namespace hoilcd
