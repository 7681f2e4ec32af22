#include "hoilcd/sim/robot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <utility>

#include "hoilcd/core/error.h"
#include "hoilcd/core/random.h"

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

double WrapAngle(double a) {
  a = std::remainder(a, 2.0 * M_PI);
  return a <= -M_PI ? a + 2.0 * M_PI : a;
}

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

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
        throw InputError("route", "corner_radius_m " + FormatNumber(corner_radius_m) +
                                      " does not fit segment " + std::to_string(i) + " (" +
                                      FormatNumber(seg_len[i]) + " m long)");
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
  double LoopCurvature(double sigma) const {
    return Locate(sigma + lead_.length_m).first->Curvature();
  }

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
    const auto it = std::upper_bound(pieces_.begin(), pieces_.end(), sigma,
                                     [](double v, const Piece& p) { return v < p.s0_m; });
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
  SpeedProfile(const RoutePath& path, double cruise_m_s, double max_lateral_accel_m_s2,
               double brake_m_s2)
      : path_(path) {
    const int n = std::max(1, static_cast<int>(std::ceil(path.loop_m() / kProfileStepM)));
    step_m_ = path.loop_m() / n;
    limit_.resize(n);
    for (int i = 0; i < n; ++i) {
      const double k =
          std::max(std::abs(path.LoopCurvature(i * step_m_)),
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

// Exact integration of the tricycle kinematics for constant wheel speed and steering angle.
void Propagate(Pose2& pose, double speed_m_s, double steer_rad, double wheelbase_m, double dt_s) {
  const double ds = speed_m_s * std::cos(steer_rad) * dt_s;
  const double dtheta = speed_m_s * std::sin(steer_rad) / wheelbase_m * dt_s;
  if (std::abs(dtheta) < 1e-9) {
    const double mid = pose.theta_rad + 0.5 * dtheta;
    pose.x_m += ds * std::cos(mid);
    pose.y_m += ds * std::sin(mid);
  } else {
    const double r = ds / dtheta;
    pose.x_m += r * (std::sin(pose.theta_rad + dtheta) - std::sin(pose.theta_rad));
    pose.y_m += r * (std::cos(pose.theta_rad) - std::cos(pose.theta_rad + dtheta));
  }
  pose.theta_rad += dtheta;
}

// The robot footprint as an oriented rectangle.
struct Box {
  Eigen::Vector2d center;
  Eigen::Vector2d half;
  Eigen::Matrix2d axes;  // columns: local x and y in world
};

Box FootprintBox(const Pose2& pose, const TricycleOptions& o) {
  Box box;
  box.axes << std::cos(pose.theta_rad), -std::sin(pose.theta_rad), std::sin(pose.theta_rad),
      std::cos(pose.theta_rad);
  box.half = Eigen::Vector2d(0.5 * o.length_m, 0.5 * o.width_m);
  box.center =
      Eigen::Vector2d(pose.x_m, pose.y_m) + box.axes.col(0) * (0.5 * o.length_m - o.base_to_rear_m);
  return box;
}

Box ObstacleBox(const Obstacle2D& ob) {
  Box box;
  box.center = ob.center_m;
  box.half = ob.half_size_m;
  box.axes << std::cos(ob.yaw_rad), -std::sin(ob.yaw_rad), std::sin(ob.yaw_rad),
      std::cos(ob.yaw_rad);
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
      const double ra = a.half.x() * std::abs(axis.dot(a.axes.col(0))) +
                        a.half.y() * std::abs(axis.dot(a.axes.col(1)));
      const double rb = b.half.x() * std::abs(axis.dot(b.axes.col(0))) +
                        b.half.y() * std::abs(axis.dot(b.axes.col(1)));
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
    if (ob.shape == Obstacle2D::Shape::kRectangle &&
        !(ob.half_size_m.x() > 0 && ob.half_size_m.y() > 0)) {
      return label + ": half_size_m must be positive";
    }
  }
  return "";
}

void ThrowIfBad(const char* where, const std::string& message) {
  if (!message.empty()) throw InputError(where, message);
}

}  // namespace

double TricycleOptions::MinTurnRadiusM() const {
  return wheelbase_m / std::tan(max_steer_deg * kDegToRad);
}

std::string TricycleOptions::Check() const {
  if (!(wheelbase_m > 0)) return "wheelbase_m must be positive";
  if (!(max_steer_deg > 0 && max_steer_deg < 89)) return "max_steer_deg must be in (0, 89)";
  if (!(max_steer_rate_deg_s > 0)) return "max_steer_rate_deg_s must be positive";
  if (!(max_speed_m_s > 0)) return "max_speed_m_s must be positive";
  if (!(max_accel_m_s2 > 0)) return "max_accel_m_s2 must be positive";
  if (!(integration_rate_hz >= 1 && integration_rate_hz <= 100000)) {
    return "integration_rate_hz must be in [1, 100000]";
  }
  if (!(length_m > 0) || !(width_m > 0)) return "length_m and width_m must be positive";
  if (!(base_to_rear_m >= 0 && base_to_rear_m < length_m)) {
    return "base_to_rear_m must be in [0, length_m)";
  }
  if (!std::isfinite(camera_forward_m) || !std::isfinite(camera_lateral_m) ||
      !std::isfinite(camera_height_m)) {
    return "camera offsets must be finite";
  }
  if (!(std::abs(camera_pitch_deg) < 90)) return "camera_pitch_deg must be in (-90, 90)";
  if (!std::isfinite(camera_yaw_deg) || !std::isfinite(camera_roll_deg)) {
    return "camera_yaw_deg and camera_roll_deg must be finite";
  }
  return "";
}

std::vector<Eigen::Vector2d> PaperRoomWaypoints() {
  return {{0.40, 0.40}, {0.40, 2.60}, {6.60, 2.60}, {6.60, 0.40}};
}

std::string RouteOptions::Check() const {
  if (waypoints_m.size() < 3) {
    return "waypoints_m needs at least 3 points, has " + std::to_string(waypoints_m.size());
  }
  for (size_t i = 0; i < waypoints_m.size(); ++i) {
    if (!waypoints_m[i].allFinite()) return "waypoint " + std::to_string(i) + " is not finite";
    if ((waypoints_m[(i + 1) % waypoints_m.size()] - waypoints_m[i]).norm() < 1e-6) {
      return "waypoint " + std::to_string(i) + " repeats the next one";
    }
  }
  if (frames < 0) return "frames must be >= 0";
  if (frames == 0 && !(laps > 0 && laps <= 1000)) return "laps must be in (0, 1000]";
  if (!(cruise_speed_m_s > 0)) return "cruise_speed_m_s must be positive";
  if (!(lookahead_m > 0)) return "lookahead_m must be positive";
  if (!(max_lateral_accel_m_s2 > 0)) return "max_lateral_accel_m_s2 must be positive";
  if (!(corner_radius_m > 0)) return "corner_radius_m must be positive";
  return "";
}

std::string OdometryNoiseOptions::Check() const {
  if (!(encoder_noise_frac >= 0 && encoder_noise_frac < 0.5)) {
    return "encoder_noise_frac must be in [0, 0.5)";
  }
  if (!(steer_noise_deg >= 0 && steer_noise_deg < 10)) return "steer_noise_deg must be in [0, 10)";
  if (!(std::abs(steer_bias_deg) < 10)) return "steer_bias_deg must be in (-10, 10)";
  if (!(slip_frac >= 0 && slip_frac < 0.5)) return "slip_frac must be in [0, 0.5)";
  return "";
}

Obstacle2D Obstacle2D::Rectangle(std::string name, const Eigen::Vector2d& center_m,
                                 const Eigen::Vector2d& size_m, double yaw_rad) {
  Obstacle2D ob;
  ob.name = std::move(name);
  ob.shape = Shape::kRectangle;
  ob.center_m = center_m;
  ob.half_size_m = 0.5 * size_m;
  ob.yaw_rad = yaw_rad;
  return ob;
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

RobotRun SimulateRobot(const TricycleOptions& robot, const RouteOptions& route,
                       const OdometryNoiseOptions& odometry,
                       const std::vector<Obstacle2D>& obstacles, double frame_rate_hz,
                       uint64_t seed) {
  ThrowIfBad("robot", robot.Check());
  ThrowIfBad("route", route.Check());
  ThrowIfBad("odometry", odometry.Check());
  ThrowIfBad("obstacles", CheckObstacles(obstacles));
  if (!(frame_rate_hz > 0 && frame_rate_hz <= robot.integration_rate_hz)) {
    throw InputError("frame_rate_hz", "must be positive and at most integration_rate_hz");
  }
  if (route.corner_radius_m < robot.MinTurnRadiusM()) {
    throw InputError("route", "corner_radius_m " + FormatNumber(route.corner_radius_m) +
                                  " is below the robot's minimum turning radius " +
                                  FormatNumber(robot.MinTurnRadiusM()) + " m");
  }
  if (route.cruise_speed_m_s > robot.max_speed_m_s) {
    throw InputError("route", "cruise_speed_m_s exceeds the robot's max_speed_m_s");
  }
  const RoutePath path(route.waypoints_m, route.corner_radius_m);
  const SpeedProfile profile(path, route.cruise_speed_m_s, route.max_lateral_accel_m_s2,
                             kBrakeFraction * robot.max_accel_m_s2);

  const double dt = 1.0 / robot.integration_rate_hz;
  const double max_steer = robot.max_steer_deg * kDegToRad;
  const double max_steer_step = robot.max_steer_rate_deg_s * kDegToRad * dt;
  const double max_speed_step = robot.max_accel_m_s2 * dt;
  const double max_curvature = std::tan(max_steer) / robot.wheelbase_m;
  const double slip_scale = 1.0 + odometry.slip_frac;
  const double steer_bias = odometry.steer_bias_deg * kDegToRad;
  const double steer_sd = odometry.steer_noise_deg * kDegToRad;
  // Generous bound on the simulated time, so a route the robot cannot follow fails loudly.
  const double planned_m = route.frames > 0 ? 0.0 : route.laps * path.loop_m() + path.lead_m();
  const double max_time_s = route.frames > 0 ? route.frames / frame_rate_hz
                                             : 60.0 + 20.0 * planned_m / route.cruise_speed_m_s;

  RobotRun run;
  run.min_obstacle_distance_m = std::numeric_limits<double>::infinity();
  run.obstacle_distance_m.assign(obstacles.size(), std::numeric_limits<double>::infinity());

  const Eigen::Vector2d start = route.waypoints_m[0];
  const Eigen::Vector2d heading = route.waypoints_m[1] - start;
  Pose2 truth{start.x(), start.y(), std::atan2(heading.y(), heading.x())};
  Pose2 odo = truth;
  const double theta0 = truth.theta_rad;
  double speed = 0, steer = 0, s = 0, travelled_m = 0;

  auto check_pose = [&](const Pose2& pose, double time_s) {
    const Box footprint = FootprintBox(pose, robot);
    const Eigen::Vector2d base(pose.x_m, pose.y_m);
    for (size_t j = 0; j < obstacles.size(); ++j) {
      if (FootprintHits(footprint, obstacles[j])) {
        char when[64];
        std::snprintf(when, sizeof(when), "%.2f", time_s);
        throw InputError("route",
                         "robot collides with '" + obstacles[j].name + "' at t = " + when + " s");
      }
      const double d = DistanceToObstacle(base, obstacles[j]);
      run.obstacle_distance_m[j] = std::min(run.obstacle_distance_m[j], d);
      if (d < run.min_obstacle_distance_m) {
        run.min_obstacle_distance_m = d;
        run.closest_obstacle = obstacles[j].name;
      }
    }
  };
  check_pose(truth, 0.0);

  int frame = 0;
  for (long step = 0;; ++step) {
    const double t = step * dt;
    if (t > max_time_s + dt) {
      throw InputError("route",
                       "robot did not finish the route within " + FormatNumber(max_time_s) + " s");
    }
    // Pure pursuit on the rounded route.
    double tracking_error = 0;
    s = path.Project({truth.x_m, truth.y_m}, std::max(0.0, s - kSearchBackM),
                     s + kSearchAheadM + route.lookahead_m, &tracking_error);
    run.max_tracking_error_m = std::max(run.max_tracking_error_m, tracking_error);
    const Eigen::Vector2d target = path.Point(s + route.lookahead_m);
    const double c = std::cos(truth.theta_rad), sn = std::sin(truth.theta_rad);
    const Eigen::Vector2d rel = target - Eigen::Vector2d(truth.x_m, truth.y_m);
    const double lateral = -sn * rel.x() + c * rel.y();
    const double curvature = std::clamp(2.0 * lateral / std::max(rel.squaredNorm(), 1e-12),
                                        -max_curvature, max_curvature);
    run.max_curvature_per_m = std::max(run.max_curvature_per_m, std::abs(curvature));
    const double steer_cmd = std::atan(curvature * robot.wheelbase_m);
    steer = std::clamp(steer + std::clamp(steer_cmd - steer, -max_steer_step, max_steer_step),
                       -max_steer, max_steer);
    const double base_limit = std::min(profile.At(s), profile.At(s + route.lookahead_m));
    const double speed_cmd = std::min(robot.max_speed_m_s, base_limit / std::cos(steer));
    speed = std::clamp(speed + std::clamp(speed_cmd - speed, -max_speed_step, max_speed_step), 0.0,
                       robot.max_speed_m_s);

    // What the odometry measures during this step.
    double odo_speed = speed, odo_steer = steer;
    if (odometry.enabled) {
      Rng rng = KeyedRng(seed, "robot.odometry", step);
      odo_speed = speed * slip_scale * (1.0 + odometry.encoder_noise_frac * rng.Normal());
      odo_steer = steer + steer_bias + steer_sd * rng.Normal();
    }

    // Frames falling inside [t, t + dt) are sampled by integrating part of this step.
    bool done = false;
    while (true) {
      const double frame_t = frame / frame_rate_hz;
      if (frame_t >= t + dt - 1e-12 * (1.0 + t)) break;
      const double part = std::max(0.0, frame_t - t);
      RobotSample sample;
      sample.frame = frame;
      sample.time_s = frame_t;
      Pose2 base = truth;
      Propagate(base, speed, steer, robot.wheelbase_m, part);
      Pose2 odo_now = odo;
      Propagate(odo_now, odo_speed, odo_steer, robot.wheelbase_m, part);
      double ignored = 0;
      const double s_frame = path.Project({base.x_m, base.y_m}, std::max(0.0, s - kSearchBackM),
                                          s + kSearchAheadM, &ignored);
      sample.lap = s_frame / path.loop_m();
      sample.camera = CameraPoseFromBase(base, robot);
      sample.speed_m_s = speed;
      sample.steer_rad = steer;
      run.path_length_m = travelled_m + speed * std::cos(steer) * part;
      run.heading_change_rad = base.theta_rad - theta0;
      run.laps = sample.lap;
      base.theta_rad = WrapAngle(base.theta_rad);
      odo_now.theta_rad = WrapAngle(odo_now.theta_rad);
      sample.base = base;
      sample.odometry = odo_now;
      run.samples.push_back(sample);
      ++frame;
      done = route.frames > 0 ? frame >= route.frames : sample.lap >= route.laps;
      if (done) break;
    }
    if (done) break;

    Propagate(truth, speed, steer, robot.wheelbase_m, dt);
    Propagate(odo, odo_speed, odo_steer, robot.wheelbase_m, dt);
    travelled_m += speed * std::cos(steer) * dt;
    check_pose(truth, t + dt);
  }
  return run;
}

}  // namespace hoilcd
