#include "hoilcd/bench/report/inspect_heat_traces.h"

#include <algorithm>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/util/json_reader.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/stats.h"

namespace hoilcd {
namespace {

constexpr double kWarmK = 1.0;      // a trace is "warm" while at least this far above the room
constexpr double kSeatTopM = 0.45;  // a chair's seat height (assets/README.md)

struct LeftSeat {
  std::string seat;
  int leave_frame = 0, until_frame = 0;  // [leave, until): the seat stays free
  const FootprintRecord* chair = nullptr;
};

std::vector<LeftSeat> LeftSeats(const Dataset& dataset) {
  std::vector<LeftSeat> out;
  for (const DatasetEvent& e : dataset.events()) {
    if (e.type != "leave") continue;
    LeftSeat s{e.seat, e.frame, dataset.num_frames(), nullptr};
    for (const DatasetEvent& later : dataset.events())
      if ((later.type == "arrive" || later.type == "swap") && later.seat == e.seat && later.frame >= e.frame)
        s.until_frame = std::min(s.until_frame, later.frame);
    for (const FootprintRecord& f : dataset.footprints())
      if (f.name == "chair " + e.seat) s.chair = &f;
    if (s.chair != nullptr && s.until_frame > s.leave_frame) out.push_back(s);
  }
  return out;
}

// The chair's pixels in one frame: their T_true minus the room's air, p90, and their count.
HeatTraceSample Sight(const Dataset& dataset, const LeftSeat& seat, int frame, double room_c) {
  const ExrChannels exr = ReadDatasetExr(dataset, frame);
  const std::string path = DatasetExrPath(dataset, frame);
  const cv::Mat& t_true = ExrChannel(exr, "T_true", path);
  const cv::Mat& depth = ExrChannel(exr, "Z", path);
  const cv::Mat& cls = ExrChannel(exr, "class", path);
  const int chair_class = dataset.manifest().ClassId("chair");
  const CameraIntrinsics& k = dataset.manifest().intrinsics;
  const Rigid3 world_from_cam = dataset.poses().at(frame).Camera().WorldFromCam();
  const FootprintRecord& f = *seat.chair;
  const Eigen::Rotation2Dd chair_from_world(-f.yaw_deg * M_PI / 180);
  constexpr double kMarginM = 0.02;
  std::vector<double> excess;
  for (int v = 0; v < t_true.rows; ++v) {
    for (int u = 0; u < t_true.cols; ++u) {
      if (static_cast<int>(cls.at<float>(v, u)) != chair_class) continue;
      const double z = depth.at<float>(v, u);
      if (!std::isfinite(z) || z <= 0) continue;
      const Eigen::Vector3d p = world_from_cam * (k.Unproject(u, v) * z);
      const Eigen::Vector2d local = chair_from_world * (p.head<2>() - Eigen::Vector2d(f.centre_m[0], f.centre_m[1]));
      if (std::abs(local.x()) > f.half_size_m[0] + kMarginM || std::abs(local.y()) > f.half_size_m[1] + kMarginM)
        continue;
      if (p.z() < kSeatTopM - 0.05 || p.z() > kSeatTopM + 0.05)
        continue;  // the seat's top, not the legs or the backrest
      excess.push_back(t_true.at<float>(v, u) - room_c);
    }
  }
  HeatTraceSample s;
  s.frame = frame;
  s.since_leave_s = (frame - seat.leave_frame) / dataset.manifest().frame_rate_hz;
  s.pixels = static_cast<int>(excess.size());
  s.excess_k = excess.empty() ? NAN : Quantile(excess, 0.9);
  return s;
}

}  // namespace

std::vector<HeatTrace> MeasureHeatTraces(const Dataset& dataset, int threads, int max_frames) {
  dataset.RequireOutput("exr", "heat traces");
  const nlohmann::json scene = ParseJsonOrDiscarded(dataset.scene_json());
  double room_c = 22.0;
  if (scene.is_object() && scene.contains("room") && scene["room"].contains("environment_temperature_c"))
    room_c = scene["room"]["environment_temperature_c"].get<double>();
  std::vector<HeatTrace> traces;
  for (const LeftSeat& seat : LeftSeats(dataset)) {
    const int span = seat.until_frame - seat.leave_frame;
    const int step = std::max(1, (span + max_frames - 1) / max_frames);
    std::vector<int> frames;
    for (int f = seat.leave_frame; f < seat.until_frame; f += step) frames.push_back(f);
    std::vector<HeatTraceSample> sights(frames.size());
    ParallelFor(static_cast<int64_t>(frames.size()), threads, [&](int64_t i) {
      sights[static_cast<size_t>(i)] = Sight(dataset, seat, frames[static_cast<size_t>(i)], room_c);
    });
    HeatTrace trace{seat.seat, seat.leave_frame, {}};
    for (const HeatTraceSample& s : sights)
      if (s.pixels >= kHeatTraceMinPixels) trace.samples.push_back(s);
    traces.push_back(std::move(trace));
  }
  return traces;
}

ExponentialFit FitExponentialDecay(const std::vector<HeatTraceSample>& samples, double min_excess_k) {
  std::vector<double> t, y;
  for (const HeatTraceSample& s : samples) {
    if (!(s.excess_k >= min_excess_k)) continue;
    t.push_back(s.since_leave_s);
    y.push_back(std::log(s.excess_k));
  }
  ExponentialFit fit;
  fit.samples = static_cast<int>(t.size());
  if (t.size() < 3 || *std::max_element(t.begin(), t.end()) - *std::min_element(t.begin(), t.end()) < 1.0) return fit;
  const double n = static_cast<double>(t.size());
  double mt = 0, my = 0;
  for (size_t i = 0; i < t.size(); ++i) mt += t[i] / n, my += y[i] / n;
  double stt = 0, sty = 0;
  for (size_t i = 0; i < t.size(); ++i) stt += (t[i] - mt) * (t[i] - mt), sty += (t[i] - mt) * (y[i] - my);
  const double slope = sty / stt;
  fit.tau_s = slope < 0 ? -1.0 / slope : INFINITY;
  fit.amplitude_k = std::exp(my - slope * mt);
  return fit;
}

InspectSection HeatTraceSection(const std::vector<HeatTrace>& traces) {
  InspectSection s{"heat_traces", "Heat traces of left seats (EXR T_true above the room)", {}};
  int seen = 0, sightings = 0, warm = 0;
  double last_warm_s = -1, first_cool_s = -1;
  std::vector<HeatTraceSample> pooled;
  for (const HeatTrace& trace : traces) {
    seen += !trace.samples.empty();
    for (const HeatTraceSample& x : trace.samples) {
      ++sightings;
      pooled.push_back(x);
      if (x.excess_k >= kWarmK) {
        ++warm;
        last_warm_s = std::max(last_warm_s, x.since_leave_s);
      } else if (first_cool_s < 0 || x.since_leave_s < first_cool_s) {
        first_cool_s = x.since_leave_s;
      }
    }
  }
  const ExponentialFit fit = FitExponentialDecay(pooled, 0.1);
  const double lifetime_s =
      std::isfinite(fit.tau_s) && fit.amplitude_k > kWarmK ? fit.tau_s * std::log(fit.amplitude_k / kWarmK) : 0;
  s.figures = {
      NumberFigure("left_seats", "left seats nobody takes again", static_cast<double>(traces.size()), ""),
      NumberFigure("left_seats_seen", "left seats seen afterwards", seen, ""),
      NumberFigure("sightings", "frames seeing a left seat", sightings, ""),
      NumberFigure("warm_percent", "sightings at least 1 K above the room", sightings ? 100.0 * warm / sightings : 0,
                   "%"),
      NumberFigure("last_warm_s", "latest sighting at least 1 K above the room, after the leave (-1: none)",
                   last_warm_s, "s"),
      NumberFigure("first_cool_s", "earliest sighting less than 1 K above the room, after the leave (-1: none)",
                   first_cool_s, "s"),
      NumberFigure("fitted_amplitude_k", "exponential fit over the sightings: excess at the leave",
                   std::isfinite(fit.amplitude_k) ? fit.amplitude_k : -1, "K"),
      NumberFigure("fitted_tau_s", "exponential fit over the sightings: time constant (-1: too few)",
                   std::isfinite(fit.tau_s) ? fit.tau_s : -1, "s"),
      NumberFigure("lifetime_s", "lifetime at least 1 K above the room, from the fit", lifetime_s, "s"),
  };
  return s;
}

}  // namespace hoilcd
