// Tricycle-drive robot (steered, driven front wheel; two passive rear wheels) following a closed
// waypoint route by pure pursuit, sampled at the camera rate: ground-truth base and camera poses,
// noisy wheel odometry, and footprint collision checks against 2-D obstacles (SPEC.md 5.1).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "hoilcd/core/camera.h"

namespace hoilcd {

// A planar pose: position of the robot base (rear-axle midpoint) and heading, REP 103 (yaw
// counter-clockwise positive, 0 = along world +x).
struct Pose2 {
  double x_m = 0, y_m = 0, theta_rad = 0;
};

// Kinematic limits, footprint and camera mount. Kinematics: x' = v cos(d) cos(theta),
// y' = v cos(d) sin(theta), theta' = v sin(d) / L, with v the front-wheel speed and d the
// steering angle; the base's path curvature is tan(d) / L.
struct TricycleOptions {
  double wheelbase_m = 0.30;            // m, rear axle to front wheel (L)
  double max_steer_deg = 60.0;          // deg, |steering angle| limit
  double max_steer_rate_deg_s = 120.0;  // deg/s, steering rate limit
  double max_speed_m_s = 0.6;           // m/s, front-wheel speed limit
  double max_accel_m_s2 = 0.5;          // m/s^2, front-wheel acceleration and deceleration limit
  double integration_rate_hz = 200.0;   // Hz, internal control and integration rate
  double length_m = 0.42;               // m, footprint length along the body x axis
  double width_m = 0.34;                // m, footprint width
  double base_to_rear_m = 0.08;         // m, footprint rear edge behind the base origin
  double camera_forward_m = 0.20;       // m, camera ahead of the base origin
  double camera_lateral_m = 0.0;        // m, camera to the left of the base origin
  double camera_height_m = 0.55;        // m, camera above the floor
  double camera_pitch_deg = 5.0;        // deg, camera pitch; positive looks down (REP 103)
  double camera_yaw_deg = 0.0;          // deg, camera yaw relative to the body, counter-clockwise
  double camera_roll_deg = 0.0;         // deg, camera roll about its optical axis

  // Smallest radius the base can turn on: L / tan(max_steer).
  double MinTurnRadiusM() const;
  // Empty string when valid, else what is wrong.
  std::string Check() const;
};

// The paper room's route (clockwise around the table row, 0.4 m from the walls).
std::vector<Eigen::Vector2d> PaperRoomWaypoints();

// A closed waypoint polygon driven in waypoint order (the paper's route is clockwise). Corners are
// rounded with arcs of corner_radius_m; pure pursuit tracks that path at a curvature-limited speed.
// The defaults drive 1.99 laps of the paper room in 1996 frames at 25 Hz, keeping the base at
// least 0.32 m from the furniture (tests/sim/robot_test.cpp).
struct RouteOptions {
  std::vector<Eigen::Vector2d> waypoints_m = PaperRoomWaypoints();  // m, polygon corners, in order
  double laps = 2.0;                     // laps to drive when frames == 0
  int frames = 0;                        // frames to simulate; > 0 overrides laps
  double cruise_speed_m_s = 0.43;        // m/s, speed of the base on straight stretches
  double lookahead_m = 0.20;             // m, pure-pursuit lookahead along the path
  double max_lateral_accel_m_s2 = 0.35;  // m/s^2, bounds speed in turns: v^2 * curvature
  double corner_radius_m = 0.30;         // m, radius of the arcs rounding the polygon corners

  // Empty string when valid, else what is wrong (limits shared with the robot are checked by
  // SimulateRobot).
  std::string Check() const;
};

// What the wheel odometry measures. Per integration step: wheel travel is scaled by
// (1 + slip_frac) * (1 + encoder_noise_frac * n1) and the steering angle reads
// d + steer_bias_deg + steer_noise_deg * n2, with n1, n2 standard normal from
// KeyedRng(seed, "robot.odometry", step). Odometry integrates those with the true kinematics.
struct OdometryNoiseOptions {
  double encoder_noise_frac = 0.01;  // relative sd of wheel travel per integration step
  double steer_noise_deg = 0.2;      // deg, sd of white steering-angle noise per step
  double steer_bias_deg = 0.05;      // deg, constant steering-angle measurement bias
  double slip_frac = 0.005;          // fraction by which the driven wheel over-reports travel
  bool enabled = true;               // false: odometry equals ground truth

  // Empty string when valid, else what is wrong.
  std::string Check() const;
};

// A 2-D obstacle footprint on the floor: an oriented rectangle or a circle.
struct Obstacle2D {
  enum class Shape { kRectangle, kCircle };
  std::string name;  // named in collision errors
  Shape shape = Shape::kRectangle;
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();     // m, world position of the centre
  Eigen::Vector2d half_size_m = Eigen::Vector2d::Zero();  // m, rectangle half extents (local x, y)
  double yaw_rad = 0;                                     // rad, rectangle orientation
  double radius_m = 0;                                    // m, circle radius

  static Obstacle2D Rectangle(std::string name, const Eigen::Vector2d& center_m,
                              const Eigen::Vector2d& size_m, double yaw_rad = 0);
  static Obstacle2D Circle(std::string name, const Eigen::Vector2d& center_m, double radius_m);
};

// Euclidean distance from a point to the obstacle's footprint (0 inside).
double DistanceToObstacle(const Eigen::Vector2d& point_m, const Obstacle2D& obstacle);

// The camera's world pose for a base pose (rigid front mount from the options).
CameraPose CameraPoseFromBase(const Pose2& base, const TricycleOptions& options);

struct RobotSample {
  int frame = 0;
  double time_s = 0;     // s, frame / frame_rate_hz
  Pose2 base;            // ground truth; theta wrapped to (-pi, pi]
  CameraPose camera;     // ground truth camera pose
  Pose2 odometry;        // noisy wheel odometry; theta wrapped to (-pi, pi]
  double speed_m_s = 0;  // m/s, front-wheel speed
  double steer_rad = 0;  // rad, steering angle
  double lap = 0;        // laps completed: distance along the rounded route / its length
};

struct RobotRun {
  std::vector<RobotSample> samples;
  double min_obstacle_distance_m = 0;  // m, over all obstacles and integration steps (base point)
  std::string closest_obstacle;        // name of the obstacle reaching that minimum
  std::vector<double> obstacle_distance_m;  // m, per obstacle (input order): its minimum
  double max_curvature_per_m = 0;           // 1/m, largest |commanded curvature|
  double max_tracking_error_m = 0;  // m, largest distance of the base from the rounded route
  double path_length_m = 0;         // m, distance travelled by the base
  double heading_change_rad = 0;    // rad, total signed heading change (-2 pi per clockwise lap)
  double laps = 0;                  // laps completed at the last sample
};

// Simulates from t = 0; frame k is at t = k / frame_rate_hz. The robot starts at rest on the first
// waypoint, heading towards the second. If route.frames == 0 it runs until `laps` laps are done
// (the first frame reaching them is the last). Throws InputError on invalid or infeasible options
// and on any footprint overlap with an obstacle at an integration step.
RobotRun SimulateRobot(const TricycleOptions& robot, const RouteOptions& route,
                       const OdometryNoiseOptions& odometry,
                       const std::vector<Obstacle2D>& obstacles, double frame_rate_hz,
                       uint64_t seed);

}  // namespace hoilcd
