// What a user checks before trusting a sequence (`hoilcd inspect`, and a section of every bench
// report): laps, lap-to-lap true path difference, odometry drift, camera jitter, people in view,
// occlusion, blank views, how the odometric and true ground truths disagree, and each recording run.
// Each topic is one section of named figures; a new topic is a new section builder added to
// InspectDataset. Recording runs are rows of their own (InspectRun), one per run.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/bench/evaluation/protocol.h"
#include "hoilcd/core/dataset/dataset.h"

namespace hoilcd {

// One number (or histogram) with its unit and a short label for people.
struct InspectFigure {
  std::string key;                // JSON key, snake_case with the unit (e.g. "median_m")
  std::string label;              // printed name
  double value = 0;               // the number (unused for histograms)
  std::string unit;               // printed unit ("m", "%", "deg", "")
  std::vector<double> bin_edges;  // histogram: counts[i] in [edge i, edge i+1); the last bin is closed
  std::vector<int64_t> counts;    // histogram counts; empty for a plain number
};

// A plain-number figure.
InspectFigure NumberFigure(std::string key, std::string label, double value, std::string unit);

struct InspectSection {
  std::string key;    // JSON key of the section ("trajectory", "camera", ...)
  std::string title;  // printed title
  std::vector<InspectFigure> figures;
  const InspectFigure* Find(const std::string& key) const;
};

// One recording run of a dataset of several (runs.h): when it was recorded and how it went.
struct InspectRun {
  int run = 0;                         // index in runs.json
  RunRecord record;                    // as runs.json states it (frames, time of day, start time)
  int laps = 0;                        // laps started in the run (true heading, LapIndexFromPoses)
  double path_length_m = 0;            // true distance driven in the run
  double people_per_frame_mean = NAN;  // people in view per frame (PeopleSection's count); NaN: no persons.json
  double odometry_drift_end_m = 0;     // |odometric - true position| at the run's last frame
  double odometry_drift_end_pct = 0;   // of the run's true distance driven
  nlohmann::json ToJson() const;       // the fields above, the record's flattened; null for NaN
};

struct InspectReport {
  std::vector<InspectSection> sections;
  std::vector<InspectRun> runs;  // a dataset of 2+ recording runs only
  const InspectSection* Find(const std::string& key) const;
  // {section: {figure: value | {bin_edges, counts}}, "runs": [run, ...] (when there are runs)}
  nlohmann::json ToJson() const;
  std::string ToText() const;      // for the terminal
  std::string ToMarkdown() const;  // for report.md
};

// Lap-to-lap true path difference: for every frame of a later lap (laps from the true heading),
// the distance of its true base position to the first lap's true path (a polyline); median, p90.
// Odometry drift: |odometric - true position| at the end, its maximum, and the end as a % of the
// true distance driven; laps and frames.
InspectSection TrajectorySection(const std::vector<PoseRecord>& poses);
// Camera roll, pitch and height: standard deviation about the mean and RMS change frame to frame.
InspectSection CameraSection(const std::vector<PoseRecord>& poses);
// People in view per frame (mean, min, max) and a histogram of their occlusion fractions.
InspectSection PeopleSection(const std::vector<FramePersons>& persons, int frames);
// Each recording run's figures; none for fewer than two runs. `persons`: null without persons.json.
std::vector<InspectRun> InspectRuns(const std::vector<RunRecord>& runs, const std::vector<PoseRecord>& poses,
                                    const std::vector<FramePersons>* persons);
// What the camera sees, from the EXR ground truth of up to kViewFramesSampled evenly spaced
// frames: the share of blank views (query_conditions.h: true temperature spread below
// kBlankSpreadK with nothing but walls, floor and ceiling in view), the median spread, the median
// share of static pixels with contrast, and frames showing people. Datasets without EXRs: none.
constexpr int kViewFramesSampled = 400;
InspectSection ViewSection(const Dataset& dataset, int threads);
// The frames the view and thermal sections read: up to kViewFramesSampled, evenly spaced.
std::vector<int> SampledViewFrames(const Dataset& dataset);
// Reflections in glossy surfaces from the same frames' EXR ground truth (ReflectionFigures).
InspectSection ReflectionSection(const Dataset& dataset, int threads);
// Reflections (inspect_reflections.cpp): for whiteboards and windows, how many of `frames` show
// one (≥ 100 interior pixels) and the median and largest p98 − p2 of the true temperature over
// its interior pixels: a plain one is nearly uniform, one that mirrors a warm body is not.
std::vector<InspectFigure> ReflectionFigures(const Dataset& dataset, const std::vector<int>& frames, int threads);
// Clothing within a person, from the same sampled frames' EXRs: the share of neighbouring
// clothing pixel pairs of one person (4-neighbours) within kEqualClothingK of each other, and the
// median over people and frames (with at least kClothingMinPixels clothing pixels) of the p95 - p5
// spread of a person's clothing. The EXR's class channel has one "person" class for every body
// part, so clothing is an interior person pixel (its four neighbours show the same person, so no
// edge mixing) whose T_true is in [kClothingMinC, kClothingMaxC). Limits: hair (~29-30 °C as
// seen), shoes (~25 °C) and the coolest skin (fingertips, ears, nose tip: 30.5-32 °C at the
// surface, ~30-31 °C as seen through ε = 0.98) fall in the band, and clothing warmer than 31 °C
// (a T-shirt where it presses on the shoulders) falls out; rooms far from 22 °C shift the band.
constexpr float kClothingMinC = 24.0f, kClothingMaxC = 31.0f;
constexpr float kEqualClothingK = 0.02f;
constexpr size_t kClothingMinPixels = 30;
InspectSection ClothingSection(const Dataset& dataset, int threads);
// How the odometric and the true ground truth label the protocol's queries differently.
InspectSection LabelSection(const std::vector<PoseRecord>& poses, const ProtocolOptions& protocol);

// Every section, for a dataset folder; the camera's output (video PSNR, lens shading, FFC
// freezes) is the last, from camera_output.h, measured on `threads` threads (0: every core).
InspectReport InspectDataset(const Dataset& dataset, const ProtocolOptions& protocol = {}, int threads = 0);

// hoilcd inspect -o DIR: InputError unless DIR may hold inspect.json (the guard of
// output_folder.h: new, empty or holding an earlier inspect.json); call it before the work.
void CheckInspectFolder(const std::string& dir);

// DIR/inspect.json (report.ToJson(), indented), written atomically; DIR is created. Checks DIR
// as CheckInspectFolder does.
void WriteInspectFolder(const InspectReport& report, const std::string& dir);

}  // namespace hoilcd
