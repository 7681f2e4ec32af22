#include "hoilcd/bench/report/inspect.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <sstream>

#include "hoilcd/bench/evaluation/json_number.h"
#include "hoilcd/bench/evaluation/query_conditions.h"
#include "hoilcd/bench/evaluation/run_metrics.h"
#include "hoilcd/bench/report/camera_output.h"
#include "hoilcd/bench/report/inspect_heat_traces.h"
#include "hoilcd/bench/report/inspect_walls.h"
#include "hoilcd/bench/report/output_folder.h"
#include "hoilcd/bench/report/realism_report.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/folder_lock.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/stats.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

// An earlier `hoilcd inspect -o DIR`: its inspect.json has InspectDataset's first sections.
OutputMarker InspectMarker() {
  return {"inspect.json", {"trajectory", "camera", "people", "labels"}, "inspect output"};
}

double RmsFrameToFrame(const std::vector<double>& values) {
  if (values.size() < 2) return 0;
  double sum = 0;
  for (size_t i = 1; i < values.size(); ++i) sum += (values[i] - values[i - 1]) * (values[i] - values[i - 1]);
  return std::sqrt(sum / (values.size() - 1));
}

double DistanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

std::string FormatValue(const InspectFigure& f) {
  if (!std::isfinite(f.value)) return kMissingFigure;  // nothing to measure (no second lap, no person)
  char text[64];
  if (f.unit.empty() && f.value == std::round(f.value)) {
    std::snprintf(text, sizeof(text), "%.0f", f.value);
  } else {
    std::snprintf(text, sizeof(text), "%.4g%s%s", f.value, f.unit.empty() ? "" : " ", f.unit.c_str());
  }
  return text;
}

std::string FormatHistogram(const InspectFigure& f) {
  std::ostringstream out;
  for (size_t i = 0; i < f.counts.size(); ++i) {
    if (i) out << ", ";
    out << "[" << f.bin_edges[i] << ", " << f.bin_edges[i + 1] << (i + 1 == f.counts.size() ? "]: " : "): ")
        << f.counts[i];
  }
  return out.str();
}

// People listed in persons.json per frame (PeopleSection's "in view").
std::vector<int> PeoplePerFrame(const std::vector<FramePersons>& persons, int frames) {
  std::vector<int> per_frame(std::max(frames, 0), 0);
  for (const FramePersons& f : persons) {
    if (f.frame >= 0 && f.frame < frames) per_frame[f.frame] += static_cast<int>(f.persons.size());
  }
  return per_frame;
}

// One line of the terminal's or a row of report.md's runs: its figures in words.
std::vector<std::string> RunCells(const InspectRun& r) {
  return {std::to_string(r.run),
          WhenRecorded(r.record),
          std::to_string(r.record.first_frame) + "-" + std::to_string(r.record.end_frame() - 1),
          Fixed(r.record.start_time_s / 3600, 2) + " h",
          std::to_string(r.laps),
          Fixed(r.path_length_m, 1) + " m",
          Fixed(r.people_per_frame_mean, 2),
          Fixed(r.odometry_drift_end_m, 3) + " m (" + Fixed(r.odometry_drift_end_pct, 2) + " %)"};
}
const char* const kRunColumns[] = {"run",
                                   "recorded",
                                   "frames",
                                   "starts after",
                                   "laps",
                                   "true distance",
                                   "people in view per frame",
                                   "odometry drift at its end"};

}  // namespace

nlohmann::json InspectRun::ToJson() const {
  return {{"run", run},
          {"time_of_day_h", record.time_of_day_h},
          {"day", record.day},
          {"start_time_s", record.start_time_s},
          {"first_frame", record.first_frame},
          {"frames", record.frames},
          {"laps", laps},
          {"path_length_m", path_length_m},
          {"people_per_frame_mean", JsonNumber(people_per_frame_mean)},
          {"odometry_drift_end_m", odometry_drift_end_m},
          {"odometry_drift_end_pct", odometry_drift_end_pct}};
}

InspectFigure NumberFigure(std::string key, std::string label, double value, std::string unit) {
  InspectFigure f;
  f.key = std::move(key);
  f.label = std::move(label);
  f.value = value;
  f.unit = std::move(unit);
  return f;
}

const InspectFigure* InspectSection::Find(const std::string& k) const {
  for (const InspectFigure& f : figures)
    if (f.key == k) return &f;
  return nullptr;
}

const InspectSection* InspectReport::Find(const std::string& k) const {
  for (const InspectSection& s : sections)
    if (s.key == k) return &s;
  return nullptr;
}

nlohmann::json InspectReport::ToJson() const {
  nlohmann::json out = nlohmann::json::object();
  for (const InspectSection& s : sections) {
    nlohmann::json section = nlohmann::json::object();
    for (const InspectFigure& f : s.figures) {
      if (f.counts.empty()) {
        section[f.key] = f.value;
      } else {
        section[f.key] = {{"bin_edges", f.bin_edges}, {"counts", f.counts}};
      }
    }
    out[s.key] = section;
  }
  for (const InspectRun& r : runs) out["runs"].push_back(r.ToJson());
  return out;
}

std::string InspectReport::ToText() const {
  std::ostringstream out;
  for (const InspectSection& s : sections) {
    out << s.title << "\n";
    for (const InspectFigure& f : s.figures) {
      out << "  " << f.label << ": " << (f.counts.empty() ? FormatValue(f) : FormatHistogram(f)) << "\n";
    }
  }
  if (!runs.empty()) out << "Recording runs\n";
  for (const InspectRun& r : runs) {
    const std::vector<std::string> cells = RunCells(r);
    out << "  run " << cells[0];
    for (size_t c = 1; c < cells.size(); ++c) out << (c == 1 ? ": " : ", ") << kRunColumns[c] << " " << cells[c];
    out << "\n";
  }
  return out.str();
}

std::string InspectReport::ToMarkdown() const {
  std::ostringstream out;
  for (const InspectSection& s : sections) {
    out << "### " << s.title << "\n\n| figure | value |\n|---|---|\n";
    for (const InspectFigure& f : s.figures) {
      out << "| " << f.label << " | " << (f.counts.empty() ? FormatValue(f) : FormatHistogram(f)) << " |\n";
    }
    out << "\n";
  }
  if (!runs.empty()) {
    out << "### Recording runs\n\n|";
    for (const char* column : kRunColumns) out << " " << column << " |";
    out << "\n|";
    for (size_t c = 0; c < std::size(kRunColumns); ++c) out << "---|";
    out << "\n";
    for (const InspectRun& r : runs) {
      out << "|";
      for (const std::string& cell : RunCells(r)) out << " " << cell << " |";
      out << "\n";
    }
    out << "\n";
  }
  return out.str();
}

InspectSection TrajectorySection(const std::vector<PoseRecord>& poses) {
  InspectSection s{"trajectory", "Trajectory (true poses vs odometry)", {}};
  const std::vector<int> laps = LapIndexFromPoses(poses);
  std::vector<Eigen::Vector2d> first_lap;
  for (size_t i = 0; i < poses.size(); ++i)
    if (laps[i] == 0) first_lap.emplace_back(poses[i].x_m, poses[i].y_m);
  std::vector<double> lap_difference_m;
  for (size_t i = 0; i < poses.size(); ++i) {
    if (laps[i] == 0 || first_lap.empty()) continue;
    const Eigen::Vector2d p(poses[i].x_m, poses[i].y_m);
    double best = (first_lap[0] - p).norm();
    for (size_t k = 1; k < first_lap.size(); ++k)
      best = std::min(best, DistanceToSegment(p, first_lap[k - 1], first_lap[k]));
    lap_difference_m.push_back(best);
  }
  // The robot is carried back to its dock between recording runs, where its odometry restarts: the
  // path leaves out the carrying, and the drift at the end is over the last run's path.
  double path_m = 0, run_path_m = 0, max_drift_m = 0, end_drift_m = 0;
  for (size_t i = 0; i < poses.size(); ++i) {
    if (i > 0 && poses[i].run != poses[i - 1].run) run_path_m = 0;
    const double step_m = i == 0 || poses[i].run != poses[i - 1].run
                              ? 0.0
                              : std::hypot(poses[i].x_m - poses[i - 1].x_m, poses[i].y_m - poses[i - 1].y_m);
    path_m += step_m;
    run_path_m += step_m;
    end_drift_m = std::hypot(poses[i].odo_x_m - poses[i].x_m, poses[i].odo_y_m - poses[i].y_m);
    max_drift_m = std::max(max_drift_m, end_drift_m);
  }
  const double end_heading_deg =
      poses.empty() ? 0 : std::remainder(poses.back().odo_theta_rad - poses.back().theta_rad, 2 * M_PI) * kRadToDeg;
  s.figures = {
      NumberFigure("frames", "frames", static_cast<double>(poses.size()), ""),
      NumberFigure("laps", "laps started (true heading)", laps.empty() ? 0 : laps.back() + 1, ""),
      NumberFigure("path_length_m", "true distance driven", path_m, "m"),
      NumberFigure("lap_difference_median_m", "lap-to-lap true path difference, median",
                   Quantile(lap_difference_m, 0.5), "m"),
      NumberFigure("lap_difference_p90_m", "lap-to-lap true path difference, p90", Quantile(lap_difference_m, 0.9),
                   "m"),
      NumberFigure("odometry_drift_end_m", "odometry drift at the end", end_drift_m, "m"),
      NumberFigure("odometry_drift_max_m", "odometry drift, max", max_drift_m, "m"),
      NumberFigure("odometry_drift_end_pct", "odometry drift at the end, % of distance",
                   run_path_m > 0 ? 100 * end_drift_m / run_path_m : 0, "%"),
      NumberFigure("odometry_heading_error_end_deg", "odometry heading error at the end", end_heading_deg, "deg"),
  };
  return s;
}

InspectSection CameraSection(const std::vector<PoseRecord>& poses) {
  InspectSection s{"camera", "Camera mount (jitter)", {}};
  std::vector<double> roll_deg, pitch_deg, height_m;
  for (const PoseRecord& p : poses) {
    roll_deg.push_back(p.cam_roll_rad * kRadToDeg);
    pitch_deg.push_back(p.cam_pitch_rad * kRadToDeg);
    height_m.push_back(p.cam_z_m);
  }
  s.figures = {
      NumberFigure("roll_std_deg", "roll std", StdDev(roll_deg), "deg"),
      NumberFigure("pitch_std_deg", "pitch std", StdDev(pitch_deg), "deg"),
      NumberFigure("height_std_m", "height std", StdDev(height_m), "m"),
      NumberFigure("roll_frame_to_frame_rms_deg", "roll change frame to frame, RMS", RmsFrameToFrame(roll_deg), "deg"),
      NumberFigure("pitch_frame_to_frame_rms_deg", "pitch change frame to frame, RMS", RmsFrameToFrame(pitch_deg),
                   "deg"),
  };
  return s;
}

InspectSection PeopleSection(const std::vector<FramePersons>& persons, int frames) {
  InspectSection s{"people", "People in view", {}};
  const std::vector<int> per_frame = PeoplePerFrame(persons, frames);
  InspectFigure occlusion;
  occlusion.key = "occlusion_histogram";
  occlusion.label = "people by occlusion fraction";
  occlusion.bin_edges = {0.0, 0.2, 0.4, 0.6, 0.8, 1.0};  // the last bin includes 1
  occlusion.counts.assign(5, 0);
  for (const FramePersons& f : persons) {
    for (const PersonRecord& p : f.persons) {
      const int bin = std::clamp(static_cast<int>(p.occlusion_fraction / 0.2), 0, 4);
      ++occlusion.counts[bin];
    }
  }
  double mean = 0;
  for (int n : per_frame) mean += n;
  mean = per_frame.empty() ? 0 : mean / per_frame.size();
  const auto [lo, hi] = std::minmax_element(per_frame.begin(), per_frame.end());
  s.figures = {
      NumberFigure("per_frame_mean", "people in view per frame, mean", mean, ""),
      NumberFigure("per_frame_min", "people in view per frame, min", per_frame.empty() ? 0 : *lo, ""),
      NumberFigure("per_frame_max", "people in view per frame, max", per_frame.empty() ? 0 : *hi, ""),
      occlusion,
  };
  return s;
}

std::vector<InspectRun> InspectRuns(const std::vector<RunRecord>& runs, const std::vector<PoseRecord>& poses,
                                    const std::vector<FramePersons>* persons) {
  std::vector<InspectRun> out;
  if (runs.size() < 2) return out;
  const std::vector<int> laps = LapIndexFromPoses(poses);
  const std::vector<int> people =
      persons ? PeoplePerFrame(*persons, static_cast<int>(poses.size())) : std::vector<int>();
  for (size_t k = 0; k < runs.size(); ++k) {
    InspectRun r;
    r.run = static_cast<int>(k);
    r.record = runs[k];
    const int first = r.record.first_frame, last = r.record.end_frame() - 1;
    HOILCD_CHECK(first >= 0 && last < static_cast<int>(poses.size()) && first <= last);
    r.laps = laps[last] - laps[first] + 1;
    double people_sum = 0;
    for (int f = first; f <= last; ++f) {
      if (f > first) r.path_length_m += std::hypot(poses[f].x_m - poses[f - 1].x_m, poses[f].y_m - poses[f - 1].y_m);
      if (persons) people_sum += people[f];
    }
    if (persons) r.people_per_frame_mean = people_sum / r.record.frames;
    r.odometry_drift_end_m = std::hypot(poses[last].odo_x_m - poses[last].x_m, poses[last].odo_y_m - poses[last].y_m);
    r.odometry_drift_end_pct = r.path_length_m > 0 ? 100 * r.odometry_drift_end_m / r.path_length_m : 0;
    out.push_back(r);
  }
  return out;
}

std::vector<int> SampledViewFrames(const Dataset& dataset) {
  const int frames = dataset.num_frames();
  const int step = std::max(1, (frames + kViewFramesSampled - 1) / kViewFramesSampled);
  std::vector<int> sampled;
  for (int f = 0; f < frames; f += step) sampled.push_back(f);
  return sampled;
}

InspectSection ViewSection(const Dataset& dataset, int threads) {
  InspectSection s{"views", "What the camera sees (true temperature, EXR)", {}};
  const std::vector<int> sampled = SampledViewFrames(dataset);
  std::vector<QueryConditions> views(sampled.size());
  ParallelFor(static_cast<int64_t>(sampled.size()), threads, [&](int64_t i) {
    views[static_cast<size_t>(i)] = ImageConditionsOf(dataset, sampled[static_cast<size_t>(i)]);
  });
  std::vector<double> spread, contrast;
  int blank = 0, bare = 0, people = 0;
  for (const QueryConditions& c : views) {
    blank += c.blank;
    bare += c.structure_only_classes;
    people += c.person_pixels > 0;
    spread.push_back(c.temperature_spread_k);
    contrast.push_back(100 * c.structure_contrast_fraction);
  }
  const double n = std::max<double>(1, static_cast<double>(views.size()));
  s.figures = {
      NumberFigure("frames_sampled", "frames sampled (evenly spaced)", static_cast<double>(views.size()), ""),
      NumberFigure("blank_percent",
                   "blank views (spread < " + ShortestDouble(kBlankSpreadK) + " K, walls/floor/ceiling only)",
                   100 * blank / n, "%"),
      NumberFigure("bare_percent", "bare views (walls/floor/ceiling only, whatever their spread)", 100 * bare / n, "%"),
      NumberFigure("with_people_percent", "views with a person", 100 * people / n, "%"),
      NumberFigure("spread_median_k", "true temperature spread (p98 - p2), median", Median(spread), "K"),
      NumberFigure("static_contrast_median_percent", "static pixels with contrast, median", Median(contrast), "%"),
  };
  return s;
}

InspectSection ReflectionSection(const Dataset& dataset, int threads) {
  InspectSection s{"reflections", "Reflections in glossy surfaces (true temperature, EXR)", {}};
  const std::vector<int> sampled = SampledViewFrames(dataset);
  for (InspectFigure& f : ReflectionFigures(dataset, sampled, threads)) s.figures.push_back(std::move(f));
  return s;
}

InspectSection LabelSection(const std::vector<PoseRecord>& poses, const ProtocolOptions& protocol) {
  InspectSection s{"labels", "Ground truth: odometry vs true poses", {}};
  ProtocolOptions odometry = protocol;
  odometry.ground_truth = "odometry";
  const std::vector<Query> by_odometry = BuildQueries(poses, odometry);
  const std::vector<Query> by_truth = RelabelQueries(by_odometry, poses, odometry, "true");
  const LabelDisagreement d = CompareLabels(by_odometry, by_truth);
  int scored_odometry = 0, scored_truth = 0;
  for (size_t i = 0; i < by_odometry.size(); ++i) {
    scored_odometry += by_odometry[i].NumTrueMatches() > 0;
    scored_truth += by_truth[i].NumTrueMatches() > 0;
  }
  s.figures = {
      NumberFigure("queries", "queries (" + protocol.protocol + " protocol, laps from odometry)", d.queries, ""),
      NumberFigure("queries_with_match_odometry", "queries with a true match, odometry labels", scored_odometry, ""),
      NumberFigure("queries_with_match_true", "queries with a true match, true labels", scored_truth, ""),
      NumberFigure("queries_differing", "queries whose true matches differ", d.queries_differing, ""),
      NumberFigure("queries_differing_pct", "queries whose true matches differ, %",
                   d.queries ? 100.0 * d.queries_differing / d.queries : 0, "%"),
      NumberFigure("pairs_differing", "query-database pairs labelled differently",
                   static_cast<double>(d.pairs_differing), ""),
  };
  return s;
}

InspectReport InspectDataset(const Dataset& dataset, const ProtocolOptions& protocol, int threads) {
  if (const std::string problem = protocol.Check(); !problem.empty()) throw InputError("inspect", problem);
  CheckProtocolFits(dataset, protocol);
  InspectReport r;
  r.sections.push_back(TrajectorySection(dataset.poses()));
  r.sections.push_back(CameraSection(dataset.poses()));
  // People ground truth is optional (render --outputs without persons): no people section then.
  if (dataset.manifest().outputs.persons) r.sections.push_back(PeopleSection(dataset.persons(), dataset.num_frames()));
  if (dataset.manifest().outputs.exr) {
    r.sections.push_back(ViewSection(dataset, threads));
    r.sections.push_back(WallSection(dataset, threads));
    r.sections.push_back(ReflectionSection(dataset, threads));
    r.sections.push_back(ClothingSection(dataset, threads));
  }
  // Heat traces of left seats, when people left (turnover) and the EXRs show them.
  const bool left = std::any_of(dataset.events().begin(), dataset.events().end(),
                                [](const DatasetEvent& e) { return e.type == "leave"; });
  if (dataset.manifest().outputs.exr && left)
    r.sections.push_back(HeatTraceSection(MeasureHeatTraces(dataset, threads)));
  r.sections.push_back(LabelSection(dataset.poses(), protocol));
  // The synthetic side of `hoilcd realism`'s statistics, from the frames themselves.
  if (dataset.manifest().outputs.radiometric || dataset.manifest().outputs.thermal) {
    r.sections.push_back(FrameStatisticsSection(dataset, threads));
  }
  CameraOutputOptions camera;
  camera.threads = threads;
  r.sections.push_back(CameraOutputSection(MeasureCameraOutput(dataset, camera)));
  const bool persons = dataset.manifest().outputs.persons;
  r.runs = InspectRuns(dataset.runs(), dataset.poses(), persons ? &dataset.persons() : nullptr);
  return r;
}

void CheckInspectFolder(const std::string& dir) { CheckOutputFolder(dir, InspectMarker()); }

void WriteInspectFolder(const InspectReport& report, const std::string& dir) {
  CheckInspectFolder(dir);
  const FolderLock lock(dir, FolderLock::IfBusy::kWait);
  WriteFileAtomic(dir + "/" + InspectMarker().file, report.ToJson().dump(2) + "\n");
}

}  // namespace hoilcd
