#include "hoilcd/sim/robot/robot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <utility>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/random.h"
#include "hoilcd/core/util/sizes.h"

namespace hoilcd {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
// Grid step of the precomputed speed profile along the route.
constexpr double kProfileStepM = 0.01;
// The speed profile brakes at this fraction of max_accel, leaving margin for the controller.
constexpr double kBrakeFraction = 0.8;
// Window of the closest-point search around the previous position along the route.
constexpr double kSearchBackM = 0.1;
constexpr double kSearchAheadM = 0.6;
// A localisation fix's error is truncated at this many sds per component (a bounded error: a
// localiser that is further off is lost, which the model does not simulate).
constexpr double kFixBoundSd = 2.0;

double WrapAngle(double a) {
  a = std::remainder(a, 2.0 * M_PI);
  return a <= -M_PI ? a + 2.0 * M_PI : a;
}

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

std::string FormatNumber(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// A straight line or a circular arc of the rounded route, parameterised by arc length u.
struct Piece {
  bool is_arc = false;
  double length_m = 0;
  double s0_m = 0;                                   // start along the loop
  Eigen::Vector2d start = Eigen::Vector2d::Zero();   // line
  Eigen::Vector2d dir = Eigen::Vector2d::UnitX();    // line, unit
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // arc
  double radius_m = 0;                               // arc
  double start_angle_rad = 0;                        // arc: angle of the start point about center
  double turn_sign = 1;                              // arc: +1 counter-clockwise, -1 clockwise

  Eigen::Vector2d Point(double u) const {
    if (!is_arc) return start + dir * u;
    const double a = start_angle_rad + turn_sign * u / radius_m;
    return center + radius_m * Eigen::Vector2d(std::cos(a), std::sin(a));
  }
  double Curvature() const { return is_arc ? turn_sign / radius_m : 0.0; }
  // Arc length in [lo, hi] of the point closest to p.
  double Project(const Eigen::Vector2d& p, double lo, double hi) const {
    double u;
    if (!is_arc) {
      u = (p - start).dot(dir);
    } else {
      const double sweep = length_m / radius_m;
      const Eigen::Vector2d d = p - center;
      const double mid = start_angle_rad + turn_sign * 0.5 * sweep;
      const double rel = WrapAngle(turn_sign * (std::atan2(d.y(), d.x()) - mid));
      u = (rel + 0.5 * sweep) * radius_m;
    }
    return std::clamp(u, lo, hi);
  }
};

// The route with rounded corners. Global arc length s starts at the first waypoint: a lead-in
// line of length lead_m reaches the exit of corner 0's arc, then the closed loop repeats forever.
class RoutePath {
 public:
  RoutePath(const std::vector<Eigen::Vector2d>& waypoints, double corner_radius_m) {
    const int n = static_cast<int>(waypoints.size());
    std::vector<Eigen::Vector2d> dirs(n);
    std::vector<double> seg_len(n);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d d = waypoints[(i + 1) % n] - waypoints[i];
      seg_len[i] = d.norm();
      dirs[i] = d / seg_len[i];
    }
    // Corner i sits at waypoint i, between segment i-1 (in) and segment i (out).
    std::vector<double> tangent(n), turn(n);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d& in = dirs[(i + n - 1) % n];
      const Eigen::Vector2d& out = dirs[i];
      turn[i] = std::atan2(Cross(in, out), in.dot(out));
      if (std::abs(turn[i]) > M_PI - 1e-3) {
        throw InputError("route", "waypoint " + std::to_string(i) + " turns back on itself");
      }
      tangent[i] = corner_radius_m * std::tan(0.5 * std::abs(turn[i]));
    }
    for (int i = 0; i < n; ++i) {
      const double needed = tangent[i] + tangent[(i + 1) % n];
      if (needed > seg_len[i] + 1e-12) {
        throw InputError("route", "corner_radius_m " + FormatNumber(corner_radius_m) + " does not fit segment " +
                                      std::to_string(i) + " (" + FormatNumber(seg_len[i]) + " m long)");
      }
    }
    double s = 0;
    for (int k = 0; k < n; ++k) {
      // Straight part of segment k, then the arc of corner k + 1.
      Piece line;
      line.start = waypoints[k] + dirs[k] * tangent[k];
      line.dir = dirs[k];
      line.length_m = seg_len[k] - tangent[k] - tangent[(k + 1) % n];
      line.s0_m = s;
      s += line.length_m;
      if (line.length_m > 0) pieces_.push_back(line);
      const int c = (k + 1) % n;
      if (tangent[c] > 0) {
        Piece arc;
        arc.is_arc = true;
        arc.turn_sign = turn[c] > 0 ? 1.0 : -1.0;
        arc.radius_m = corner_radius_m;
        const Eigen::Vector2d entry = waypoints[c] - dirs[k] * tangent[c];
        const Eigen::Vector2d left(-dirs[k].y(), dirs[k].x());
        arc.center = entry + arc.turn_sign * corner_radius_m * left;
        const Eigen::Vector2d r = entry - arc.center;
        arc.start_angle_rad = std::atan2(r.y(), r.x());
        arc.length_m = corner_radius_m * std::abs(turn[c]);
        arc.s0_m = s;
        s += arc.length_m;
        pieces_.push_back(arc);
      }
    }
    loop_m_ = s;
    lead_.start = waypoints[0];
    lead_.dir = dirs[0];
    lead_.length_m = tangent[0];
    for (const double t : turn) total_turn_rad_ += t;
  }

  double loop_m() const { return loop_m_; }
  double lead_m() const { return lead_.length_m; }
  double total_turn_rad() const { return total_turn_rad_; }

  Eigen::Vector2d Point(double s) const {
    if (s < lead_.length_m) return lead_.Point(s);
    const auto [piece, u] = Locate(s);
    return piece->Point(u);
  }
  // Signed curvature of the loop at loop coordinate sigma in [0, loop_m).
  double LoopCurvature(double sigma) const { return Locate(sigma + lead_.length_m).first->Curvature(); }

  // Arc length in [lo, hi] (lo >= 0) of the route point closest to p; its distance in *distance.
  double Project(const Eigen::Vector2d& p, double lo, double hi, double* distance) const {
    double best_s = lo, best_d = std::numeric_limits<double>::infinity();
    auto consider = [&](const Piece& piece, double offset) {
      const double a = std::max(lo - offset, 0.0), b = std::min(hi - offset, piece.length_m);
      if (a > b) return;
      const double u = piece.Project(p, a, b);
      const double d = (piece.Point(u) - p).norm();
      if (d < best_d) {
        best_d = d;
        best_s = offset + u;
      }
    };
    consider(lead_, 0.0);
    const double first_lap = std::floor(std::max(lo - lead_.length_m, 0.0) / loop_m_);
    for (double lap = first_lap; lead_.length_m + lap * loop_m_ <= hi; lap += 1.0) {
      for (const Piece& piece : pieces_) {
        consider(piece, lead_.length_m + lap * loop_m_ + piece.s0_m);
      }
    }
    *distance = best_d;
    return best_s;
  }

 private:
  std::pair<const Piece*, double> Locate(double s) const {
    const double sigma = std::fmod(s - lead_.length_m, loop_m_);
    const auto it =
        std::upper_bound(pieces_.begin(), pieces_.end(), sigma, [](double v, const Piece& p) { return v < p.s0_m; });
    const Piece* piece = it == pieces_.begin() ? &pieces_.front() : &*(it - 1);
    return {piece, std::clamp(sigma - piece->s0_m, 0.0, piece->length_m)};
  }

  std::vector<Piece> pieces_;
  Piece lead_;
  double loop_m_ = 0;
  double total_turn_rad_ = 0;
};

// Base speed limit along the loop: cruise speed, capped by lateral acceleration in the arcs and
// by braking ahead of them (a backward pass, run twice around the closed loop).
class SpeedProfile {
 public:
  SpeedProfile(const RoutePath& path, double cruise_m_s, double max_lateral_accel_m_s2, double brake_m_s2)
      : path_(path) {
    const int n = std::max(1, static_cast<int>(std::ceil(path.loop_m() / kProfileStepM)));
    step_m_ = path.loop_m() / n;
    limit_.resize(n);
    for (int i = 0; i < n; ++i) {
      const double k = std::max(std::abs(path.LoopCurvature(i * step_m_)),
                                std::abs(path.LoopCurvature(std::min((i + 1) * step_m_, path.loop_m() - 1e-9))));
      limit_[i] = k > 0 ? std::min(cruise_m_s, std::sqrt(max_lateral_accel_m_s2 / k)) : cruise_m_s;
    }
    for (int pass = 0; pass < 2; ++pass) {
      for (int i = n - 1; i >= 0; --i) {
        const double next = limit_[(i + 1) % n];
        limit_[i] = std::min(limit_[i], std::sqrt(next * next + 2.0 * brake_m_s2 * step_m_));
      }
    }
  }

  // Speed limit at global arc length s (the lead-in shares the first straight's limit).
  double At(double s) const {
    const double sigma = std::max(s - path_.lead_m(), 0.0);
    const int n = static_cast<int>(limit_.size());
    const long i = static_cast<long>(std::floor(sigma / step_m_));
    return std::min(limit_[i % n], limit_[(i + 1) % n]);
  }

 private:
  const RoutePath& path_;
  double step_m_ = 1;
  std::vector<double> limit_;
};

// Moves a pose along a circular arc: the base travels forward_m while the heading turns by
// dtheta_rad (exact for a constant curvature within the step).
void Advance(Pose2& pose, double forward_m, double dtheta_rad) {
  if (std::abs(dtheta_rad) < 1e-9) {
    const double mid = pose.theta_rad + 0.5 * dtheta_rad;
    pose.x_m += forward_m * std::cos(mid);
    pose.y_m += forward_m * std::sin(mid);
  } else {
    const double r = forward_m / dtheta_rad;
    pose.x_m += r * (std::sin(pose.theta_rad + dtheta_rad) - std::sin(pose.theta_rad));
    pose.y_m += r * (std::cos(pose.theta_rad) - std::cos(pose.theta_rad + dtheta_rad));
  }
  pose.theta_rad += dtheta_rad;
}

// One integration step of a tricycle: the front wheel rolls wheel_m at steering angle steer_rad.
struct Motion {
  double forward_m = 0;  // base travel
  double dtheta_rad = 0;
};
Motion TricycleMotion(double wheel_m, double steer_rad, double wheelbase_m) {
  return {wheel_m * std::cos(steer_rad), wheel_m * std::sin(steer_rad) / wheelbase_m};
}

// A damped second-order mount x'' = w^2 (target - x) - 2 z w x' + w^2 g n / sqrt(dt), integrated
// semi-implicitly; g = sd * sqrt(4 z / w) gives the stationary sd `sd` for unit white noise n.
struct MountAxis {
  double x = 0, v = 0;
  void Step(double target, double sd, double noise, double omega, double zeta, double dt) {
    const double gain = sd * std::sqrt(4.0 * zeta / omega);
    v += dt * (omega * omega * (target - x) - 2.0 * zeta * omega * v) + omega * omega * gain * noise * std::sqrt(dt);
    x += dt * v;
  }
};

// The error of successive localisation fixes: a first-order Gauss-Markov process per component
// (x, y, heading), stationary from the first fix, each applied value truncated at kFixBoundSd sd.
class FixError {
 public:
  FixError(const LocalizationOptions& o, uint64_t seed)
      : position_sd_m_(o.position_sd_m),
        heading_sd_rad_(o.heading_sd_deg * kDegToRad),
        keep_(o.correlation_s > 0 ? std::exp(-o.interval_s / o.correlation_s) : 0.0),
        seed_(seed) {}

  // The error of fix number `index` (0, 1, 2, ... in order).
  Pose2 Next(uint64_t index) {
    Rng rng = KeyedRng(seed_, "robot.localization", index);
    const double fresh = index == 0 ? 1.0 : std::sqrt(1.0 - keep_ * keep_);
    const double keep = index == 0 ? 0.0 : keep_;
    for (double& n : state_) n = keep * n + fresh * rng.Normal();
    auto bounded = [](double n) { return std::clamp(n, -kFixBoundSd, kFixBoundSd); };
    return {position_sd_m_ * bounded(state_[0]), position_sd_m_ * bounded(state_[1]),
            heading_sd_rad_ * bounded(state_[2])};
  }

 private:
  double position_sd_m_, heading_sd_rad_, keep_;
  uint64_t seed_;
  double state_[3] = {0, 0, 0};  // unit-variance processes
};

// The robot footprint as an oriented rectangle.
struct Box {
  Eigen::Vector2d center;
  Eigen::Vector2d half;
  Eigen::Matrix2d axes;  // columns: local x and y in world
};

Box FootprintBox(const Pose2& pose, const TricycleOptions& o) {
  Box box;
  box.axes << std::cos(pose.theta_rad), -std::sin(pose.theta_rad), std::sin(pose.theta_rad), std::cos(pose.theta_rad);
  box.half = Eigen::Vector2d(0.5 * o.length_m, 0.5 * o.width_m);
  box.center = Eigen::Vector2d(pose.x_m, pose.y_m) + box.axes.col(0) * (0.5 * o.length_m - o.base_to_rear_m);
  return box;
}

Box ObstacleBox(const Obstacle2D& ob) {
  Box box;
  box.center = ob.center_m;
  box.half = ob.half_size_m;
  box.axes << std::cos(ob.yaw_rad), -std::sin(ob.yaw_rad), std::sin(ob.yaw_rad), std::cos(ob.yaw_rad);
  return box;
}

double DistancePointBox(const Eigen::Vector2d& p, const Box& box) {
  const Eigen::Vector2d local = box.axes.transpose() * (p - box.center);
  const Eigen::Vector2d outside = (local.cwiseAbs() - box.half).cwiseMax(0.0);
  return outside.norm();
}

// Separating-axis test between two oriented rectangles; touching does not count as overlap.
// Hand-written: cv::rotatedRectangleIntersection works in float and builds the overlap polygon.
bool BoxesOverlap(const Box& a, const Box& b) {
  const Eigen::Vector2d d = b.center - a.center;
  for (const Box* box : {&a, &b}) {
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d axis = box->axes.col(k);
      const double ra = a.half.x() * std::abs(axis.dot(a.axes.col(0))) + a.half.y() * std::abs(axis.dot(a.axes.col(1)));
      const double rb = b.half.x() * std::abs(axis.dot(b.axes.col(0))) + b.half.y() * std::abs(axis.dot(b.axes.col(1)));
      if (std::abs(d.dot(axis)) >= ra + rb) return false;
    }
  }
  return true;
}

bool FootprintHits(const Box& footprint, const Obstacle2D& ob) {
  if (ob.shape == Obstacle2D::Shape::kCircle) {
    return DistancePointBox(ob.center_m, footprint) < ob.radius_m;
  }
  return BoxesOverlap(footprint, ObstacleBox(ob));
}

std::string CheckObstacles(const std::vector<Obstacle2D>& obstacles) {
  for (size_t i = 0; i < obstacles.size(); ++i) {
    const Obstacle2D& ob = obstacles[i];
    const std::string label = "obstacle " + std::to_string(i) + " ('" + ob.name + "')";
    if (!ob.center_m.allFinite() || !std::isfinite(ob.yaw_rad)) return label + ": not finite";
    if (ob.shape == Obstacle2D::Shape::kCircle && !(ob.radius_m > 0)) {
      return label + ": radius_m must be positive";
    }
    if (ob.shape == Obstacle2D::Shape::kRectangle && !(ob.half_size_m.x() > 0 && ob.half_size_m.y() > 0)) {
      return label + ": half_size_m must be positive";
    }
  }
  return "";
}

void ThrowIfBad(const char* where, const std::string& message) {
  if (!message.empty()) throw InputError(where, message);
}

}  // namespace

double TricycleOptions::MinTurnRadiusM() const { return wheelbase_m / std::tan(max_steer_deg * kDegToRad); }

VibrationOptions::VibrationOptions() { Table().FillDefaults(this); }

const OptionTable<VibrationOptions>& VibrationOptions::Table() {
  using O = VibrationOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("enabled", &O::enabled, true, "false: the camera is rigidly mounted")
          .Add("natural_frequency_hz", &O::natural_frequency_hz, 4.0, "Hz", R().Above(0).AtMost(1000), "mast resonance")
          .Add("damping_ratio", &O::damping_ratio, 0.3, "", R().Above(0).AtMost(10), "damping ratio of the mount")
          .Add("roll_sd_deg", &O::roll_sd_deg, 0.3, "deg", R::Closed(0, 10),
               "roughness-driven roll sd at the reference speed")
          .Add("pitch_sd_deg", &O::pitch_sd_deg, 0.4, "deg", R::Closed(0, 10),
               "roughness-driven pitch sd at the reference speed")
          .Add("height_sd_m", &O::height_sd_m, 0.002, "m", R::Closed(0, 0.1),
               "roughness-driven height sd at the reference speed")
          .Add("reference_speed_m_s", &O::reference_speed_m_s, 0.43, "m/s", R().Above(0),
               "speed at which the sds above hold")
          .Add("pitch_per_accel_deg_s2_m", &O::pitch_per_accel_deg_s2_m, 1.0, "deg per m/s^2", R::Closed(-20, 20),
               "nose-up pitch per unit of acceleration")
          .Add("roll_per_lat_accel_deg_s2_m", &O::roll_per_lat_accel_deg_s2_m, 1.0, "deg per m/s^2", R::Closed(-20, 20),
               "outward roll per unit of lateral acceleration");
  return table;
}

std::string VibrationOptions::Check() const { return Table().FirstProblem(*this); }

LocalizationOptions::LocalizationOptions() { Table().FillDefaults(this); }

const OptionTable<LocalizationOptions>& LocalizationOptions::Table() {
  using O = LocalizationOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("interval_s", &O::interval_s, 0.5, "s", R().Above(0).AtMost(3600), "time between localisation fixes")
          .Add("position_sd_m", &O::position_sd_m, 0.035, "m", R::Closed(0, 1),
               "sd of a fix's error along x and along y")
          .Add("heading_sd_deg", &O::heading_sd_deg, 1.0, "deg", R::Closed(0, 30), "sd of a fix's heading error")
          .Add("correlation_s", &O::correlation_s, 5.0, "s", R::Closed(0, 3600),
               "correlation time of the fix error (0: independent fixes)");
  return table;
}

std::string LocalizationOptions::Check() const { return Table().FirstProblem(*this); }

TricycleOptions::TricycleOptions() { Table().FillDefaults(this); }

const OptionTable<TricycleOptions>& TricycleOptions::Table() {
  using O = TricycleOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("wheelbase_m", &O::wheelbase_m, 0.30, "m", R().Above(0), "rear axle to front wheel (L)")
          .Add("max_steer_deg", &O::max_steer_deg, 60.0, "deg", R().Above(0).Below(89), "|steering angle| limit")
          .Add("max_steer_rate_deg_s", &O::max_steer_rate_deg_s, 120.0, "deg/s", R().Above(0), "steering rate limit")
          .Add("max_speed_m_s", &O::max_speed_m_s, 0.6, "m/s", R().Above(0), "front-wheel speed limit")
          .Add("max_accel_m_s2", &O::max_accel_m_s2, 0.5, "m/s^2", R().Above(0),
               "front-wheel acceleration and deceleration limit")
          .Add("integration_rate_hz", &O::integration_rate_hz, 200.0, "Hz", R::Closed(1, 100000),
               "internal control and integration rate")
          .Add("length_m", &O::length_m, 0.42, "m", R().Above(0), "footprint length along the body x axis")
          .Add("width_m", &O::width_m, 0.34, "m", R().Above(0), "footprint width")
          .Add("base_to_rear_m", &O::base_to_rear_m, 0.08, "m", R().AtLeast(0),
               "footprint rear edge behind the base origin")
          .Rule("base_to_rear_m",
                [](const O& o) { return o.base_to_rear_m < o.length_m ? "" : "must be below length_m"; })
          .Add("camera_forward_m", &O::camera_forward_m, 0.20, "m", R::Any(), "camera ahead of the base origin")
          .Add("camera_lateral_m", &O::camera_lateral_m, 0.0, "m", R::Any(), "camera to the left of the base origin")
          .Add("camera_height_m", &O::camera_height_m, 0.95, "m", R().Above(0), "camera above the floor")
          .Add("camera_pitch_deg", &O::camera_pitch_deg, 8.0, "deg", R::Closed(-89, 89),
               "camera pitch; positive looks down (REP 103)")
          .Add("camera_yaw_deg", &O::camera_yaw_deg, 0.0, "deg", R::Closed(-180, 180),
               "camera yaw relative to the body, counter-clockwise")
          .Add("camera_roll_deg", &O::camera_roll_deg, 0.0, "deg", R::Closed(-180, 180),
               "camera roll about its optical axis")
          .AddEnum("navigation", &O::navigation, Navigation::kLocalized,
                   {{"localized", Navigation::kLocalized},
                    {"odometry", Navigation::kOdometry},
                    {"ground_truth", Navigation::kGroundTruth}},
                   "what the path follower steers on: localised odometry, dead reckoning or the true pose")
          .Nest("localization", &O::localization, LocalizationOptions::Table())
          .Nest("vibration", &O::vibration, VibrationOptions::Table());
  return table;
}

std::string TricycleOptions::Check() const { return Table().FirstProblem(*this); }

std::vector<Eigen::Vector2d> PaperRoomWaypoints() { return {{0.38, 0.38}, {0.38, 2.62}, {6.62, 2.62}, {6.62, 0.38}}; }

RouteOptions::RouteOptions() : waypoints_m(PaperRoomWaypoints()) { Table().FillDefaults(this); }

const OptionTable<RouteOptions>& RouteOptions::Table() {
  using O = RouteOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .External("waypoints_m", "m, the route's polygon corners [x, y], in driving order")
          .Rule("waypoints_m",
                [](const O& o) -> std::string {
                  if (o.waypoints_m.size() < 3) {
                    return "needs at least 3 points, has " + std::to_string(o.waypoints_m.size());
                  }
                  for (size_t i = 0; i < o.waypoints_m.size(); ++i) {
                    if (!o.waypoints_m[i].allFinite()) return "waypoint " + std::to_string(i) + " is not finite";
                    if ((o.waypoints_m[(i + 1) % o.waypoints_m.size()] - o.waypoints_m[i]).norm() < 1e-6) {
                      return "waypoint " + std::to_string(i) + " repeats the next one";
                    }
                  }
                  return "";
                })
          .Add("laps", &O::laps, 2.0, "", R().Above(0).AtMost(1000), "laps to drive when frames is 0")
          .CodeOnly()
          .Add("frames", &O::frames, 0, "", R::Closed(0, kMaxFrames),
               "frames to simulate; > 0 overrides laps (the scene's frames)")
          .CodeOnly()
          .Add("cruise_speed_m_s", &O::cruise_speed_m_s, 0.43, "m/s", R().Above(0),
               "speed of the base on straight stretches")
          .Add("lookahead_m", &O::lookahead_m, 0.20, "m", R().Above(0), "pure-pursuit lookahead along the path")
          .Add("max_lateral_accel_m_s2", &O::max_lateral_accel_m_s2, 0.35, "m/s^2", R().Above(0),
               "bounds the speed in turns: v^2 * curvature")
          .Add("corner_radius_m", &O::corner_radius_m, 0.30, "m", R().Above(0),
               "radius of the arcs rounding the polygon corners");
  return table;
}

std::string RouteOptions::Check() const { return Table().FirstProblem(*this); }

OdometryErrorOptions::OdometryErrorOptions() { Table().FillDefaults(this); }

const OptionTable<OdometryErrorOptions>& OdometryErrorOptions::Table() {
  using O = OdometryErrorOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("enabled", &O::enabled, true, "false: the true motion is the measured motion")
          .Add("error_scale", &O::error_scale, 1.0, "", R::Closed(0, 100), "multiplies every error below (0: perfect)")
          .Add("wheel_radius_error_frac", &O::wheel_radius_error_frac, 0.001, "", R().Above(-0.2).Below(0.2),
               "true / nominal driven-wheel radius - 1")
          .Add("steer_offset_deg", &O::steer_offset_deg, 0.01, "deg", R().Above(-10).Below(10),
               "true steering angle minus the measured one")
          .Add("wheelbase_error_frac", &O::wheelbase_error_frac, 0.002, "", R().Above(-0.2).Below(0.2),
               "true / nominal wheelbase - 1")
          .Add("encoder_counts_per_rev", &O::encoder_counts_per_rev, 2048, "", R::Closed(1, 1e7),
               "drive-wheel encoder counts per revolution")
          .Add("wheel_radius_m", &O::wheel_radius_m, 0.05, "m", R().Above(0).Below(10), "nominal driven-wheel radius")
          .Add("slip_per_accel_s2_m", &O::slip_per_accel_s2_m, 0.01, "per m/s^2", R::Closed(0, 1),
               "longitudinal slip per unit of acceleration")
          .Add("turn_slip_per_lat_accel_s2_m", &O::turn_slip_per_lat_accel_s2_m, 0.01, "per m/s^2", R::Closed(0, 1),
               "yaw-rate shortfall per unit of lateral acceleration")
          .Add("slip_noise_frac", &O::slip_noise_frac, 0.5, "", R::Closed(0, 10), "relative sd of both slips")
          .Add("heading_noise_deg_sqrt_m", &O::heading_noise_deg_sqrt_m, 0.03, "deg/sqrt(m)", R::Closed(0, 10),
               "random heading walk (floor)");
  return table;
}

std::string OdometryErrorOptions::Check() const { return Table().FirstProblem(*this); }

Obstacle2D Obstacle2D::Rectangle(std::string name, const Eigen::Vector2d& center_m, const Eigen::Vector2d& size_m,
                                 double yaw_rad) {
  Obstacle2D ob;
  ob.name = std::move(name);
  ob.shape = Shape::kRectangle;
  ob.center_m = center_m;
  ob.half_size_m = 0.5 * size_m;
  ob.yaw_rad = yaw_rad;
  return ob;
}

std::vector<FootprintRecord> FootprintRecordsOf(const std::vector<Obstacle2D>& obstacles) {
  std::vector<FootprintRecord> out;
  for (const Obstacle2D& o : obstacles) {
    FootprintRecord f;
    f.name = o.name;
    f.centre_m = {o.center_m.x(), o.center_m.y()};
    if (o.shape == Obstacle2D::Shape::kCircle) {
      f.kind = "circle";
      f.radius_m = o.radius_m;
    } else {
      f.kind = "rectangle";
      f.half_size_m = {o.half_size_m.x(), o.half_size_m.y()};
      f.yaw_deg = o.yaw_rad / kDegToRad;
    }
    out.push_back(std::move(f));
  }
  return out;
}

Obstacle2D Obstacle2D::Circle(std::string name, const Eigen::Vector2d& center_m, double radius_m) {
  Obstacle2D ob;
  ob.name = std::move(name);
  ob.shape = Shape::kCircle;
  ob.center_m = center_m;
  ob.radius_m = radius_m;
  return ob;
}

double DistanceToObstacle(const Eigen::Vector2d& point_m, const Obstacle2D& obstacle) {
  if (obstacle.shape == Obstacle2D::Shape::kCircle) {
    return std::max(0.0, (point_m - obstacle.center_m).norm() - obstacle.radius_m);
  }
  return DistancePointBox(point_m, ObstacleBox(obstacle));
}

bool FootprintsOverlap(const Obstacle2D& a, const Obstacle2D& b) {
  using Shape = Obstacle2D::Shape;
  if (a.shape == Shape::kCircle && b.shape == Shape::kCircle)
    return (a.center_m - b.center_m).norm() <= a.radius_m + b.radius_m;
  if (a.shape == Shape::kCircle) return DistanceToObstacle(a.center_m, b) <= a.radius_m;
  if (b.shape == Shape::kCircle) return DistanceToObstacle(b.center_m, a) <= b.radius_m;
  // Two rectangles: the separating-axis test.
  const Eigen::Vector2d d = b.center_m - a.center_m;
  for (const Obstacle2D* owner : {&a, &b}) {
    for (int axis = 0; axis < 2; ++axis) {
      const double angle = owner->yaw_rad + axis * M_PI / 2;
      const Eigen::Vector2d n(std::cos(angle), std::sin(angle));
      double reach = 0;
      for (const Obstacle2D* r : {&a, &b}) {
        const Eigen::Vector2d u(std::cos(r->yaw_rad), std::sin(r->yaw_rad));
        const Eigen::Vector2d v(-u.y(), u.x());
        reach += r->half_size_m.x() * std::abs(n.dot(u)) + r->half_size_m.y() * std::abs(n.dot(v));
      }
      if (std::abs(n.dot(d)) > reach) return false;
    }
  }
  return true;
}

std::vector<std::pair<size_t, size_t>> OverlappingFootprints(const std::vector<Obstacle2D>& footprints) {
  const auto reach = [](const Obstacle2D& o) {
    return o.shape == Obstacle2D::Shape::kCircle ? o.radius_m : o.half_size_m.norm();
  };
  std::vector<size_t> order(footprints.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto left = [&](size_t i) { return footprints[i].center_m.x() - reach(footprints[i]); };
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return left(a) < left(b) || (left(a) == left(b) && a < b); });
  std::vector<std::pair<size_t, size_t>> pairs;
  for (size_t k = 0; k < order.size(); ++k) {
    const Obstacle2D& a = footprints[order[k]];
    const double right = a.center_m.x() + reach(a);
    for (size_t m = k + 1; m < order.size() && left(order[m]) <= right; ++m) {
      const Obstacle2D& b = footprints[order[m]];
      if (std::abs(a.center_m.y() - b.center_m.y()) > reach(a) + reach(b)) continue;
      if (FootprintsOverlap(a, b)) pairs.emplace_back(std::min(order[k], order[m]), std::max(order[k], order[m]));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

CameraPose CameraPoseFromBase(const Pose2& base, const TricycleOptions& o) {
  const double c = std::cos(base.theta_rad), s = std::sin(base.theta_rad);
  CameraPose cam;
  cam.x_m = base.x_m + c * o.camera_forward_m - s * o.camera_lateral_m;
  cam.y_m = base.y_m + s * o.camera_forward_m + c * o.camera_lateral_m;
  cam.z_m = o.camera_height_m;
  cam.yaw_rad = WrapAngle(base.theta_rad + o.camera_yaw_deg * kDegToRad);
  cam.pitch_rad = o.camera_pitch_deg * kDegToRad;
  cam.roll_rad = o.camera_roll_deg * kDegToRad;
  return cam;
}

namespace {

// What SimulateRobot needs beyond each options struct's own checks: options that must agree.
void CheckRobotInputs(const TricycleOptions& robot, const RouteOptions& route, const OdometryErrorOptions& odometry,
                      const std::vector<Obstacle2D>& obstacles, double frame_rate_hz) {
  ThrowIfBad("robot", robot.Check());
  ThrowIfBad("route", route.Check());
  ThrowIfBad("odometry", odometry.Check());
  ThrowIfBad("obstacles", CheckObstacles(obstacles));
  if (std::abs(odometry.steer_offset_deg * odometry.error_scale) >= robot.max_steer_deg) {
    throw InputError("odometry",
                     "steer_offset_deg (times error_scale) must stay below the robot's "
                     "max_steer_deg " +
                         FormatNumber(robot.max_steer_deg));
  }
  if (!(frame_rate_hz > 0 && frame_rate_hz <= robot.integration_rate_hz)) {
    throw InputError("frame_rate_hz",
                     "must be positive and at most /robot/integration_rate_hz, the rate the robot's "
                     "motion is integrated at (" +
                         FormatNumber(robot.integration_rate_hz) +
                         " Hz here, 200 by default): lower the frame rate or raise "
                         "robot.integration_rate_hz");
  }
  if (route.corner_radius_m < robot.MinTurnRadiusM()) {
    throw InputError("route", "corner_radius_m " + FormatNumber(route.corner_radius_m) +
                                  " is below the robot's minimum turning radius " +
                                  FormatNumber(robot.MinTurnRadiusM()) + " m");
  }
  if (route.cruise_speed_m_s > robot.max_speed_m_s) {
    throw InputError("route", "cruise_speed_m_s exceeds the robot's max_speed_m_s");
  }
}

// One run of SimulateRobot: the model's fixed quantities, the robot's state, and one integration
// step at a time (navigate, move the wheels, shake the mount, sample frames, advance).
class RobotSimulator {
 public:
  RobotSimulator(const TricycleOptions& robot, const RouteOptions& route, const OdometryErrorOptions& odometry,
                 const std::vector<Obstacle2D>& obstacles, double frame_rate_hz, uint64_t seed)
      : robot_(robot),
        route_(route),
        odometry_(odometry),
        obstacles_(obstacles),
        frame_rate_hz_(frame_rate_hz),
        seed_(seed),
        path_(route.waypoints_m, route.corner_radius_m),
        profile_(path_, route.cruise_speed_m_s, route.max_lateral_accel_m_s2, kBrakeFraction * robot.max_accel_m_s2),
        dt_(1.0 / robot.integration_rate_hz),
        max_steer_(robot.max_steer_deg * kDegToRad),
        max_steer_step_(robot.max_steer_rate_deg_s * kDegToRad * dt_),
        max_speed_step_(robot.max_accel_m_s2 * dt_),
        max_curvature_(std::tan(max_steer_) / robot.wheelbase_m),
        k_(odometry.enabled ? odometry.error_scale : 0.0),
        true_radius_scale_(1.0 + k_ * odometry.wheel_radius_error_frac),
        steer_offset_(k_ * odometry.steer_offset_deg * kDegToRad),
        true_wheelbase_(robot.wheelbase_m * (1.0 + k_ * odometry.wheelbase_error_frac)),
        slip_per_accel_(k_ * odometry.slip_per_accel_s2_m),
        turn_slip_per_lat_accel_(k_ * odometry.turn_slip_per_lat_accel_s2_m),
        heading_noise_(k_ * odometry.heading_noise_deg_sqrt_m * kDegToRad),
        metres_per_count_(2.0 * M_PI * odometry.wheel_radius_m / odometry.encoder_counts_per_rev),
        steer_on_truth_(robot.navigation == TricycleOptions::Navigation::kGroundTruth),
        localized_(robot.navigation == TricycleOptions::Navigation::kLocalized),
        fix_error_(robot.localization, seed),
        vib_omega_(2.0 * M_PI * robot.vibration.natural_frequency_hz) {
    // Generous bound on the simulated time, so a route the robot cannot follow fails loudly.
    const double planned_m = route.frames > 0 ? 0.0 : route.laps * path_.loop_m() + path_.lead_m();
    max_time_s_ = route.frames > 0 ? route.frames / frame_rate_hz : 60.0 + 20.0 * planned_m / route.cruise_speed_m_s;
    run_.min_obstacle_distance_m = std::numeric_limits<double>::infinity();
    run_.obstacle_distance_m.assign(obstacles.size(), std::numeric_limits<double>::infinity());
    const Eigen::Vector2d start = route.waypoints_m[0];
    const Eigen::Vector2d heading = route.waypoints_m[1] - start;
    truth_ = {start.x(), start.y(), std::atan2(heading.y(), heading.x())};
    odo_ = truth_;
    belief_ = truth_;
    theta0_ = truth_.theta_rad;
  }

  RobotRun Run() {
    CheckPose(truth_, 0.0);
    for (long step = 0;; ++step) {
      const double t = step * dt_;
      if (t > max_time_s_ + dt_) {
        throw InputError("route", "robot did not finish the route within " + FormatNumber(max_time_s_) + " s");
      }
      Localise(t);
      const double accel = Navigate();
      const Steps steps = MoveWheels(step, accel);
      ShakeMount(step, steps, accel);
      if (SampleFrames(t, steps)) break;
      Advance(truth_, steps.truth.forward_m, steps.truth.dtheta_rad);
      Advance(odo_, steps.odometry.forward_m, steps.odometry.dtheta_rad);
      Advance(belief_, steps.odometry.forward_m, steps.odometry.dtheta_rad);
      travelled_m_ += steps.truth.forward_m;
      CheckPose(truth_, t + dt_);
    }
    run_.localization_fixes = fixes_;
    return std::move(run_);
  }

 private:
  // One integration step's motion as the odometry reports it and as the robot truly moves.
  struct Steps {
    Motion odometry, truth;
    double base_speed_m_s = 0, lateral_accel_m_s2 = 0;  // true, for the mount
  };

  // A localisation fix replaces the belief with the true pose plus the fix error.
  void Localise(double t) {
    if (localized_ && t >= (fixes_ + 1) * robot_.localization.interval_s - 1e-9 * dt_) {
      const Pose2 e = fix_error_.Next(static_cast<uint64_t>(fixes_));
      belief_ = {truth_.x_m + e.x_m, truth_.y_m + e.y_m, truth_.theta_rad + e.theta_rad};
      ++fixes_;
    }
  }

  // Pure pursuit on the rounded route, from the pose the robot steers on: servoes steer_ and
  // speed_ towards their commands within the rate limits; returns the acceleration, m/s^2.
  double Navigate() {
    const Pose2& nav = steer_on_truth_ ? truth_ : localized_ ? belief_ : odo_;
    double tracking_error = 0;
    s_ = path_.Project({nav.x_m, nav.y_m}, std::max(0.0, s_ - kSearchBackM), s_ + kSearchAheadM + route_.lookahead_m,
                       &tracking_error);
    run_.max_tracking_error_m = std::max(run_.max_tracking_error_m, tracking_error);
    s_true_ = path_.Project({truth_.x_m, truth_.y_m}, std::max(0.0, s_true_ - kSearchBackM),
                            s_true_ + kSearchAheadM + route_.lookahead_m, &route_deviation_m_);
    run_.max_route_deviation_m = std::max(run_.max_route_deviation_m, route_deviation_m_);
    const Eigen::Vector2d target = path_.Point(s_ + route_.lookahead_m);
    const double c = std::cos(nav.theta_rad), sn = std::sin(nav.theta_rad);
    const Eigen::Vector2d rel = target - Eigen::Vector2d(nav.x_m, nav.y_m);
    const double lateral = -sn * rel.x() + c * rel.y();
    const double curvature =
        std::clamp(2.0 * lateral / std::max(rel.squaredNorm(), 1e-12), -max_curvature_, max_curvature_);
    run_.max_curvature_per_m = std::max(run_.max_curvature_per_m, std::abs(curvature));
    const double steer_cmd = std::atan(curvature * robot_.wheelbase_m);
    steer_ =
        std::clamp(steer_ + std::clamp(steer_cmd - steer_, -max_steer_step_, max_steer_step_), -max_steer_, max_steer_);
    const double base_limit = std::min(profile_.At(s_), profile_.At(s_ + route_.lookahead_m));
    const double speed_cmd = std::min(robot_.max_speed_m_s, base_limit / std::cos(steer_));
    const double previous_speed = speed_;
    speed_ = std::clamp(speed_ + std::clamp(speed_cmd - speed_, -max_speed_step_, max_speed_step_), 0.0,
                        robot_.max_speed_m_s);
    return (speed_ - previous_speed) / dt_;
  }

  // What the encoders report this step (steer and speed are servoed on them), and how the robot
  // truly moves: wheel radius and wheelbase errors, steering offset, slip, heading noise.
  Steps MoveWheels(long step, double accel) {
    const OdometryErrorOptions& o = odometry_;
    const double wheel_m = speed_ * dt_;
    wheel_turns_m_ += wheel_m;
    const int64_t new_counts = static_cast<int64_t>(std::floor(wheel_turns_m_ / metres_per_count_));
    const double odo_wheel_m = o.enabled ? (new_counts - counts_) * metres_per_count_ : wheel_m;
    counts_ = new_counts;
    Steps out;
    out.odometry = TricycleMotion(odo_wheel_m, steer_, robot_.wheelbase_m);
    Rng rng = KeyedRng(seed_, "robot.odometry", step);
    const double n1 = rng.Normal(), n2 = rng.Normal(), n3 = rng.Normal();
    const double slip = slip_per_accel_ * accel * (1.0 + o.slip_noise_frac * n1);
    const double true_wheel_m = wheel_m * true_radius_scale_ * (1.0 - slip);
    const double true_steer = steer_ + steer_offset_;
    out.truth = TricycleMotion(true_wheel_m, true_steer, true_wheelbase_);
    out.base_speed_m_s = speed_ * std::cos(true_steer);
    out.lateral_accel_m_s2 = out.base_speed_m_s * out.base_speed_m_s * std::tan(true_steer) / true_wheelbase_;
    out.truth.dtheta_rad *= 1.0 - std::min(1.0, turn_slip_per_lat_accel_ * std::abs(out.lateral_accel_m_s2) *
                                                    (1.0 + o.slip_noise_frac * n2));
    out.truth.dtheta_rad += heading_noise_ * std::sqrt(std::abs(out.truth.forward_m)) * n3;
    if (!o.enabled) out.truth = out.odometry;
    return out;
  }

  // Camera mount: roughness grows with speed; acceleration pitches, lateral acceleration rolls.
  void ShakeMount(long step, const Steps& steps, double accel) {
    const VibrationOptions& vib = robot_.vibration;
    if (!vib.enabled) return;
    Rng vrng = KeyedRng(seed_, "robot.vibration", step);
    const double level = steps.base_speed_m_s / vib.reference_speed_m_s;
    const double z = vib.damping_ratio;
    roll_.Step(vib.roll_per_lat_accel_deg_s2_m * kDegToRad * steps.lateral_accel_m_s2,
               level * vib.roll_sd_deg * kDegToRad, vrng.Normal(), vib_omega_, z, dt_);
    pitch_.Step(-vib.pitch_per_accel_deg_s2_m * kDegToRad * accel, level * vib.pitch_sd_deg * kDegToRad, vrng.Normal(),
                vib_omega_, z, dt_);
    height_.Step(0.0, level * vib.height_sd_m, vrng.Normal(), vib_omega_, z, dt_);
  }

  // Frames falling inside [t, t + dt) are sampled by interpolating this step's motion. Returns
  // whether the run is done (its frames, or its laps as the robot believes them).
  bool SampleFrames(double t, const Steps& steps) {
    const Motion& true_step = steps.truth;
    const Motion& odo_step = steps.odometry;
    while (true) {
      const double frame_t = frame_ / frame_rate_hz_;
      if (frame_t >= t + dt_ - 1e-12 * (1.0 + t)) return false;
      const double part = std::max(0.0, frame_t - t) / dt_;
      RobotSample sample;
      sample.frame = frame_;
      sample.time_s = frame_t;
      Pose2 base = truth_;
      Advance(base, part * true_step.forward_m, part * true_step.dtheta_rad);
      Pose2 odo_now = odo_;
      Advance(odo_now, part * odo_step.forward_m, part * odo_step.dtheta_rad);
      Pose2 belief_now = belief_;
      Advance(belief_now, part * odo_step.forward_m, part * odo_step.dtheta_rad);
      const Pose2& nav_now = steer_on_truth_ ? base : localized_ ? belief_now : odo_now;
      double ignored = 0;
      const double s_frame =
          path_.Project({nav_now.x_m, nav_now.y_m}, std::max(0.0, s_ - kSearchBackM), s_ + kSearchAheadM, &ignored);
      // Laps completed never run backwards (a localisation fix may move the belief back a little).
      sample.lap = std::max(s_frame / path_.loop_m(), run_.samples.empty() ? 0.0 : run_.samples.back().lap);
      sample.camera = CameraPoseFromBase(base, robot_);
      sample.vibration = {roll_.x, pitch_.x, height_.x};
      sample.camera.roll_rad += roll_.x;
      sample.camera.pitch_rad += pitch_.x;
      sample.camera.z_m += height_.x;
      sample.speed_m_s = speed_;
      sample.steer_rad = steer_;
      run_.path_length_m = travelled_m_ + part * true_step.forward_m;
      run_.heading_change_rad = base.theta_rad - theta0_;
      run_.laps = sample.lap;
      base.theta_rad = WrapAngle(base.theta_rad);
      odo_now.theta_rad = WrapAngle(odo_now.theta_rad);
      sample.base = base;
      sample.odometry = odo_now;
      run_.samples.push_back(sample);
      ++frame_;
      if (route_.frames > 0 ? frame_ >= route_.frames : sample.lap >= route_.laps) return true;
    }
  }

  // Throws when the footprint at `pose` overlaps an obstacle; records the closest approaches.
  void CheckPose(const Pose2& pose, double time_s) {
    const Box footprint = FootprintBox(pose, robot_);
    const Eigen::Vector2d base(pose.x_m, pose.y_m);
    for (size_t j = 0; j < obstacles_.size(); ++j) {
      if (FootprintHits(footprint, obstacles_[j])) ThrowCollision(pose, time_s, obstacles_[j]);
      const double d = DistanceToObstacle(base, obstacles_[j]);
      run_.obstacle_distance_m[j] = std::min(run_.obstacle_distance_m[j], d);
      if (d < run_.min_obstacle_distance_m) {
        run_.min_obstacle_distance_m = d;
        run_.closest_obstacle = obstacles_[j].name;
      }
    }
  }

  // The collision error: when, how far the robot drifted, and which setting to change.
  [[noreturn]] void ThrowCollision(const Pose2& pose, double time_s, const Obstacle2D& obstacle) const {
    char when[160];
    std::snprintf(when, sizeof(when),
                  "at frame %d (t = %.2f s), its true path %.2f m from the route and %.2f m from "
                  "its odometry",
                  static_cast<int>(std::floor(time_s * frame_rate_hz_ + 1e-9)), time_s, route_deviation_m_,
                  std::hypot(odo_.x_m - pose.x_m, odo_.y_m - pose.y_m));
    const std::string lower = localized_ ? "lower the localisation error (robot.localization.position_sd_m, "
                                           "robot.localization.heading_sd_deg)"
                                         : "lower the odometry error (odometry.error_scale)";
    throw InputError("route", "robot collides with '" + obstacle.name + "' " + when + "; " + lower +
                                  " or widen the route (route.waypoints_m further from the furniture)" +
                                  (robot_.navigation == TricycleOptions::Navigation::kOdometry
                                       ? ", or let the robot localise (robot.navigation \"localized\")"
                                       : ""));
  }

  const TricycleOptions& robot_;
  const RouteOptions& route_;
  const OdometryErrorOptions& odometry_;
  const std::vector<Obstacle2D>& obstacles_;
  const double frame_rate_hz_;
  const uint64_t seed_;
  const RoutePath path_;
  const SpeedProfile profile_;  // refers to path_
  const double dt_, max_steer_, max_steer_step_, max_speed_step_, max_curvature_;
  // The odometry error model, scaled by error_scale (OdometryErrorOptions).
  const double k_, true_radius_scale_, steer_offset_, true_wheelbase_, slip_per_accel_, turn_slip_per_lat_accel_,
      heading_noise_, metres_per_count_;
  const bool steer_on_truth_, localized_;
  FixError fix_error_;
  const double vib_omega_;
  double max_time_s_ = 0;

  RobotRun run_;
  Pose2 truth_, odo_;
  Pose2 belief_;  // what the robot steers on when localized: odometry between fixes
  int fixes_ = 0;
  double theta0_ = 0;
  double speed_ = 0, steer_ = 0, s_ = 0, s_true_ = 0, travelled_m_ = 0, route_deviation_m_ = 0;
  double wheel_turns_m_ = 0;  // drive-wheel rotation times the nominal radius, unquantised
  int64_t counts_ = 0;        // encoder counts so far
  MountAxis roll_, pitch_, height_;
  int frame_ = 0;
};

}  // namespace

RobotRun SimulateRobot(const TricycleOptions& robot, const RouteOptions& route, const OdometryErrorOptions& odometry,
                       const std::vector<Obstacle2D>& obstacles, double frame_rate_hz, uint64_t seed) {
  CheckRobotInputs(robot, route, odometry, obstacles, frame_rate_hz);
  return RobotSimulator(robot, route, odometry, obstacles, frame_rate_hz, seed).Run();
}

std::vector<PoseRecord> PoseRecordsOf(const RobotRun& run, int frames) {
  const size_t n = frames < 0 ? run.samples.size() : std::min(run.samples.size(), static_cast<size_t>(frames));
  std::vector<PoseRecord> poses;
  poses.reserve(n);
  for (size_t f = 0; f < n; ++f) {
    const RobotSample& s = run.samples[f];
    poses.push_back({s.frame, s.time_s, s.base.x_m, s.base.y_m, s.base.theta_rad, s.camera.x_m, s.camera.y_m,
                     s.camera.z_m, s.camera.yaw_rad, s.camera.pitch_rad, s.camera.roll_rad, s.odometry.x_m,
                     s.odometry.y_m, s.odometry.theta_rad});
  }
  return poses;
}

}  // namespace hoilcd
