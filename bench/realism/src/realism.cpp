#include "hoilcd/bench/realism/realism.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "hoilcd/bench/evaluation/json_number.h"
#include "hoilcd/bench/realism/frame_size_groups.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/progress.h"
#include "hoilcd/core/util/safe_text.h"
#include "hoilcd/core/util/stats.h"

namespace hoilcd {
namespace {

constexpr const char* kNoiseKey = "temporal_noise_k";

std::vector<double> Known(const std::vector<double>& values) {
  std::vector<double> known;
  for (double v : values)
    if (std::isfinite(v)) known.push_back(v);
  return known;
}

SideSummary Summarise(const std::vector<double>& values) {
  SideSummary s;
  s.count = static_cast<int>(values.size());
  if (values.empty()) return s;
  s.median = Quantile(values, 0.5);
  s.p25 = Quantile(values, 0.25);
  s.p75 = Quantile(values, 0.75);
  return s;
}

StatisticComparison Compare(const std::vector<double>& synthetic, const std::vector<double>& real) {
  StatisticComparison c;
  c.synthetic = Summarise(synthetic);
  c.real = Summarise(real);
  if (c.real.count > 0 && c.synthetic.count > 0 && c.real.median != 0)
    c.median_ratio = c.synthetic.median / c.real.median;
  c.wasserstein1 = Wasserstein1(synthetic, real);
  return c;
}

nlohmann::json SideJson(const SideSummary& s) {
  return {{"count", s.count}, {"median", JsonNumber(s.median)}, {"p25", JsonNumber(s.p25)}, {"p75", JsonNumber(s.p75)}};
}

nlohmann::json ComparisonJson(const StatisticComparison& c) {
  return {{"synthetic", SideJson(c.synthetic)},
          {"real", SideJson(c.real)},
          {"median_ratio", JsonNumber(c.median_ratio)},
          {"wasserstein1", JsonNumber(c.wasserstein1)}};
}

nlohmann::json FrameJson(const std::string& frame, const FrameStatistics& s) {
  nlohmann::json j = {{"frame", SafeText(frame)},     {"width_px", s.width_px}, {"height_px", s.height_px},
                      {"radiometric", s.radiometric}, {"blank", s.blank},       {"wall_dominated", s.wall_dominated}};
  for (const StatisticInfo& info : FrameStatisticList()) j[info.key] = JsonNumber(info.value(s));
  j["temperature_p1_c"] = JsonNumber(s.p1_c);
  j["temperature_p99_c"] = JsonNumber(s.p99_c);
  return j;
}

nlohmann::json SetJson(const FrameSet& set) {
  nlohmann::json frames = nlohmann::json::array();
  for (size_t i = 0; i < set.frames.size(); ++i) frames.push_back(FrameJson(set.frames[i], set.statistics[i]));
  nlohmann::json skipped = nlohmann::json::array();
  for (const std::string& name : set.skipped) skipped.push_back(SafeText(name));
  const int n = static_cast<int>(set.frames.size());
  return {{"source", SafeText(set.source)},
          {"frames", n},
          {"radiometric", set.Radiometric()},
          {"blank", set.Blank()},
          {"blank_share",
           set.Radiometric() > 0 ? JsonNumber(static_cast<double>(set.Blank()) / set.Radiometric()) : nullptr},
          {"static_pairs", static_cast<int>(set.temporal_noise_k.size())},
          {"skipped", skipped},
          {"per_frame", frames}};
}

std::string Format(double v, int digits) {
  if (!std::isfinite(v)) return "–";
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

// Digits that show a statistic's scale: counts whole, fractions and kelvin to three places.
int DigitsOf(const StatisticRow& row) {
  if (row.key.find("corners") != std::string::npos) return 0;
  return row.unit == "°C" || row.key == "entropy_bits" || row.key == "spectrum_slope" ? 2 : 3;
}

std::string SideText(const SideSummary& s, int digits) {
  if (s.count == 0) return "–";
  return Format(s.median, digits) + " (" + Format(s.p25, digits) + "–" + Format(s.p75, digits) + ", n " +
         std::to_string(s.count) + ")";
}

constexpr const char* kSizeCaption =
    "Frames grouped by their native size (W×H), the only camera identity a .npy or PNG carries: cameras of one "
    "size share a row. Medians over the views that are not blank.";

void SizeRows(std::ostringstream& md, const char* side, const std::vector<FrameSizeGroup>& groups) {
  for (const FrameSizeGroup& g : groups) {
    md << "| " << side << " | " << g.width_px << "×" << g.height_px << " | " << g.views << " | " << g.not_blank << " | "
       << Format(g.spectrum_slope, 2) << " | " << Format(g.flat_noise_k, 3) << " | " << Format(g.flat_noise_lag1, 2)
       << " |\n";
  }
}

std::string Share(int part, int whole) {
  return whole > 0
             ? Format(100.0 * part / whole, 1) + " % (" + std::to_string(part) + " of " + std::to_string(whole) + ")"
             : "–";
}

}  // namespace

int FrameSet::Radiometric() const {
  return static_cast<int>(
      std::count_if(statistics.begin(), statistics.end(), [](const FrameStatistics& s) { return s.radiometric; }));
}

int FrameSet::Blank() const {
  return static_cast<int>(
      std::count_if(statistics.begin(), statistics.end(), [](const FrameStatistics& s) { return s.blank; }));
}

std::vector<int> StridedFrames(int frame_count, int stride) {
  HOILCD_CHECK(stride >= 1);
  std::vector<int> frames;
  for (int f = 0; f < frame_count; f += stride) frames.push_back(f);
  return frames;
}

bool IsStaticPair(const std::vector<PoseRecord>& poses, int frame) {
  if (frame < 0 || frame + 1 >= static_cast<int>(poses.size())) return false;
  const PoseRecord& a = poses[static_cast<size_t>(frame)];
  const PoseRecord& b = poses[static_cast<size_t>(frame) + 1];
  const double moved =
      std::sqrt((b.cam_x_m - a.cam_x_m) * (b.cam_x_m - a.cam_x_m) + (b.cam_y_m - a.cam_y_m) * (b.cam_y_m - a.cam_y_m) +
                (b.cam_z_m - a.cam_z_m) * (b.cam_z_m - a.cam_z_m));
  const auto turn = [](double from, double to) { return std::fabs(std::remainder(to - from, 2 * M_PI)); };
  return moved < kStaticMoveM && turn(a.cam_yaw_rad, b.cam_yaw_rad) < kStaticTurnRad &&
         turn(a.cam_pitch_rad, b.cam_pitch_rad) < kStaticTurnRad &&
         turn(a.cam_roll_rad, b.cam_roll_rad) < kStaticTurnRad;
}

FrameSet MeasureDatasetFrames(const Dataset& dataset, const std::vector<int>& frames, int threads) {
  const bool radiometric = dataset.manifest().outputs.radiometric;
  if (!radiometric) dataset.RequireOutput("thermal", "the frames' statistics (radiometric or thermal)");
  FrameSet set;
  set.name = "synthetic";
  set.source = dataset.dir();
  set.statistics.resize(frames.size());
  std::vector<double> noise(frames.size(), NAN);
  ProgressReporter progress("frame statistics", static_cast<int64_t>(frames.size()), "frames");
  ParallelFor(static_cast<int64_t>(frames.size()), threads, [&](int64_t i) {
    const int frame = frames[static_cast<size_t>(i)];
    if (!radiometric) {
      set.statistics[static_cast<size_t>(i)] = MeasureGreyFrame(dataset.Thermal(frame));
    } else {
      const cv::Mat t = dataset.RadiometricC(frame);
      set.statistics[static_cast<size_t>(i)] = MeasureTemperatureFrame(t);
      if (IsStaticPair(dataset.poses(), frame))
        noise[static_cast<size_t>(i)] = TemporalNoiseK(t, dataset.RadiometricC(frame + 1));
    }
    progress.Update();
  });
  progress.Done();
  for (int f : frames) set.frames.push_back(std::to_string(f));
  set.temporal_noise_k = Known(noise);
  return set;
}

FrameSet MeasureRealFrames(const std::string& dir, const RealFrameOptions& options, bool static_sequence, int threads) {
  if (const std::string problem = options.Check(); !problem.empty()) throw InputError("realism", problem);
  FrameSet set;
  set.name = "real";
  set.source = dir;
  set.frames = ListRealFrames(dir, &set.skipped);
  set.statistics.resize(set.frames.size());
  const auto path = [&](size_t i) { return (std::filesystem::path(dir) / set.frames[i]).string(); };
  ProgressReporter progress("real frames", static_cast<int64_t>(set.frames.size()), "frames");
  ParallelFor(static_cast<int64_t>(set.frames.size()), threads, [&](int64_t i) {
    const RealFrame f = ReadRealFrame(path(static_cast<size_t>(i)), options);
    set.statistics[static_cast<size_t>(i)] =
        f.radiometric ? MeasureTemperatureFrame(f.image) : MeasureGreyFrame(f.image);
    progress.Update();
  });
  progress.Done();
  if (static_sequence && set.frames.size() > 1) {
    // Each pair reads its two frames again: a long sequence is never held whole.
    std::vector<double> noise(set.frames.size() - 1, NAN);
    ParallelFor(static_cast<int64_t>(noise.size()), threads, [&](int64_t i) {
      const size_t k = static_cast<size_t>(i);
      if (!set.statistics[k].radiometric || !set.statistics[k + 1].radiometric) return;
      const RealFrame a = ReadRealFrame(path(k), options), b = ReadRealFrame(path(k + 1), options);
      if (a.image.size() == b.image.size()) noise[k] = TemporalNoiseK(a.image, b.image);
    });
    set.temporal_noise_k = Known(noise);
  }
  return set;
}

double Wasserstein1(std::vector<double> a, std::vector<double> b) {
  if (a.empty() || b.empty()) return NAN;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  // Walk the merged values: between consecutive ones both CDFs are constant.
  const double na = static_cast<double>(a.size()), nb = static_cast<double>(b.size());
  size_t i = 0, j = 0;
  double x = std::min(a[0], b[0]), area = 0;
  while (i < a.size() || j < b.size()) {
    const double next = j == b.size() || (i < a.size() && a[i] <= b[j]) ? a[i] : b[j];
    area += std::fabs(static_cast<double>(i) / na - static_cast<double>(j) / nb) * (next - x);
    x = next;
    while (i < a.size() && a[i] == x) ++i;
    while (j < b.size() && b[j] == x) ++j;
  }
  return area;
}

RealismComparison CompareFrameSets(FrameSet synthetic, FrameSet real) {
  RealismComparison c;
  const auto values = [](const FrameSet& set, const StatisticInfo& info, bool not_blank) {
    std::vector<double> v;
    for (const FrameStatistics& s : set.statistics) {
      if (not_blank && s.blank) continue;
      if (const double x = info.value(s); std::isfinite(x)) v.push_back(x);
    }
    return v;
  };
  for (const StatisticInfo& info : FrameStatisticList()) {
    StatisticRow row{info.key,
                     info.label,
                     info.unit,
                     values(synthetic, info, false),
                     values(real, info, false),
                     values(synthetic, info, true),
                     values(real, info, true),
                     {},
                     {}};
    row.all = Compare(row.synthetic, row.real);
    row.not_blank = Compare(row.synthetic_not_blank, row.real_not_blank);
    c.rows.push_back(std::move(row));
  }
  // Temporal noise is a property of the camera on static pairs, blank or not.
  StatisticRow noise{kNoiseKey,
                     "temporal noise on static views (robust std of a frame difference / sqrt 2)",
                     "K",
                     synthetic.temporal_noise_k,
                     real.temporal_noise_k,
                     synthetic.temporal_noise_k,
                     real.temporal_noise_k,
                     {},
                     {}};
  noise.all = Compare(noise.synthetic, noise.real);
  noise.not_blank = noise.all;
  c.rows.push_back(std::move(noise));
  c.synthetic = std::move(synthetic);
  c.real = std::move(real);
  return c;
}

nlohmann::json RealismComparison::ToJson() const {
  nlohmann::json statistics = nlohmann::json::array();
  for (const StatisticRow& row : rows) {
    statistics.push_back({{"key", row.key},
                          {"label", row.label},
                          {"unit", row.unit},
                          {"all_views", ComparisonJson(row.all)},
                          {"views_not_blank", ComparisonJson(row.not_blank)}});
  }
  return {{"hoilcd_version", HOILCD_VERSION},
          {"stretch",
           "each frame stretched from its 1st to its 99th percentile onto 0..255, resized to 256x192 (INTER_AREA); "
           "the spectrum slope of a frame smaller than 256x192 at its native size; the flat-region noise of every "
           "frame at its native size, unstretched"},
          {"blank_rule", "radiometric p95 - p5 below 2 K"},
          {"synthetic", SetJson(synthetic)},
          {"real", SetJson(real)},
          {"statistics", statistics},
          {"by_frame_size",
           {{"caption", kSizeCaption},
            {"real", FrameSizeGroupsJson(GroupByFrameSize(real.statistics))},
            {"synthetic", FrameSizeGroupsJson(GroupByFrameSize(synthetic.statistics))}}}};
}

std::string RealismComparison::ToMarkdown() const {
  std::ostringstream md;
  md << "# Rendered frames against real ones\n\n"
     << "- synthetic: `" << SafeText(synthetic.source) << "`, " << synthetic.frames.size() << " frames ("
     << synthetic.Radiometric() << " radiometric), " << synthetic.temporal_noise_k.size() << " static pairs\n"
     << "- real: `" << SafeText(real.source) << "`, " << real.frames.size() << " frames (" << real.Radiometric()
     << " radiometric, " << real.frames.size() - static_cast<size_t>(real.Radiometric())
     << " 8-bit: no temperature statistics for those), " << real.temporal_noise_k.size() << " static pairs\n";
  if (!real.skipped.empty()) md << "- skipped in the real folder (no frame file): " << real.skipped.size() << "\n";
  md << "- blank views (radiometric p95 - p5 < " << Format(kBlankViewSpreadK, 0) << " K): synthetic "
     << Share(synthetic.Blank(), synthetic.Radiometric()) << ", real " << Share(real.Blank(), real.Radiometric())
     << "\n\n"
     << "Every frame is stretched from its 1st to its 99th percentile onto 0–255 and resized to 256×192 before the "
        "image statistics; temperatures are resized the same way. The spectrum slope of a frame smaller than 256×192 "
        "is taken at its native size instead (upsampling would steepen it), and the flat-region noise of every frame "
        "at its native size, unstretched. Each cell: median (p25–p75, n frames). Ratio: synthetic median / real "
        "median; W1: Wasserstein-1 distance between the two sides' distributions, in the statistic's unit.\n";
  const auto table = [&](const char* title, bool not_blank) {
    md << "\n## " << title << "\n\n| statistic | real | synthetic | synthetic / real | W1 |\n|---|---|---|---|---|\n";
    for (const StatisticRow& row : rows) {
      const StatisticComparison& c = not_blank ? row.not_blank : row.all;
      const int digits = DigitsOf(row);
      md << "| " << row.label << (row.unit.empty() ? "" : ", " + row.unit) << " | " << SideText(c.real, digits) << " | "
         << SideText(c.synthetic, digits) << " | " << Format(c.median_ratio, 2) << " | "
         << Format(c.wasserstein1, digits + 1) << " |\n";
    }
  };
  table("Views that are not blank", true);
  table("Every view", false);
  md << "\n## By frame size\n\n"
     << kSizeCaption
     << "\n\n| side | frame size | views | not blank | spectrum slope | flat-region noise, K | flat-region noise lag-1 "
        "|\n|---|---|---|---|---|---|---|\n";
  SizeRows(md, "real", GroupByFrameSize(real.statistics));
  SizeRows(md, "synthetic", GroupByFrameSize(synthetic.statistics));
  md << "\nHistograms of both sides: `histograms/<statistic>.png`. Per-frame values: `realism.json`.\n";
  return md.str();
}

}  // namespace hoilcd
