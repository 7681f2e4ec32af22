// Tricycle-drive robot (steered, driven front wheel; two passive rear wheels) following a closed
// waypoint route by pure pursuit on the pose it believes (wheel odometry, by default corrected by
// periodic localisation fixes with a bounded error), sampled at
// the camera rate: true base and camera poses (with mount vibration), the odometry, and footprint
// collision checks against 2-D obstacles (SPEC.md 5.1). Error model: docs/models/robot.md.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/geometry/camera.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// A planar pose: position of the robot base (rear-axle midpoint) and heading, REP 103 (yaw
// counter-clockwise positive, 0 = along world +x).
struct Pose2 {
  double x_m = 0, y_m = 0, theta_rad = 0;
};

// Camera mount vibration: roll, pitch and height of the camera each follow a damped second-order
// mount (natural frequency, damping ratio) driven by floor roughness (white noise whose level
// grows linearly with speed, scaled so the stationary sd at reference_speed_m_s is the given
// value) and pulled by the robot's acceleration (longitudinal -> pitch, lateral -> roll).
// Noise from KeyedRng(seed, "robot.vibration", integration step): keyed by time, not thread.
struct VibrationOptions {
  bool enabled;                        // false: the camera is rigidly mounted
  double natural_frequency_hz;         // Hz, mast resonance
  double damping_ratio;                // dimensionless, of the mount
  double roll_sd_deg;                  // deg, roughness-driven roll sd at the reference speed
  double pitch_sd_deg;                 // deg, roughness-driven pitch sd at the reference speed
  double height_sd_m;                  // m, roughness-driven height sd at the reference speed
  double reference_speed_m_s;          // m/s, speed at which the sds above hold
  double pitch_per_accel_deg_s2_m;     // deg of nose-up pitch per m/s^2 of acceleration
  double roll_per_lat_accel_deg_s2_m;  // deg of outward roll per m/s^2 lateral accel.

  VibrationOptions();  // the registered defaults
  // Every field once: JSON name (the scene's /robot/vibration), unit, default, range, description.
  static const OptionTable<VibrationOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// Localisation model for navigation kLocalized: every interval_s the robot replaces the pose it
// steers on with a fix from a map-based localiser (AMCL or lidar scan matching), the true pose
// plus an error; between fixes it advances that belief with its wheel odometry. The fix error is
// a first-order Gauss-Markov process (correlation time correlation_s: a localiser's error changes
// slowly with the scene it matches), each component truncated at 2 sd so it stays bounded; draws
// from KeyedRng(seed, "robot.localization", fix index). Independent of odometry.error_scale.
// Defaults and their sources: docs/models/robot.md.
struct LocalizationOptions {
  double interval_s;      // s, time between localisation fixes
  double position_sd_m;   // m, sd of a fix's error along x and along y
  double heading_sd_deg;  // deg, sd of a fix's heading error
  double correlation_s;   // s, correlation time of the fix error (0: independent fixes)

  LocalizationOptions();  // the registered defaults
  // Every field once: JSON name (the scene's /robot/localization), unit, default, range, description.
  static const OptionTable<LocalizationOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// Kinematic limits, footprint and camera mount. Kinematics: x' = v cos(d) cos(theta),
// y' = v cos(d) sin(theta), theta' = v sin(d) / L, with v the front-wheel speed and d the
// steering angle; the base's path curvature is tan(d) / L.
struct TricycleOptions {
  double wheelbase_m;           // m, rear axle to front wheel (L)
  double max_steer_deg;         // deg, |steering angle| limit
  double max_steer_rate_deg_s;  // deg/s, steering rate limit
  double max_speed_m_s;         // m/s, front-wheel speed limit
  double max_accel_m_s2;        // m/s^2, front-wheel acceleration and deceleration limit
  double integration_rate_hz;   // Hz, internal control and integration rate
  double length_m;              // m, footprint length along the body x axis
  double width_m;               // m, footprint width
  double base_to_rear_m;        // m, footprint rear edge behind the base origin
  double camera_forward_m;      // m, camera ahead of the base origin
  double camera_lateral_m;      // m, camera to the left of the base origin
  double camera_height_m;       // m, camera above the floor
  double camera_pitch_deg;      // deg, camera pitch; positive looks down (REP 103)
  double camera_yaw_deg;        // deg, camera yaw relative to the body, counter-clockwise
  double camera_roll_deg;       // deg, camera roll about its optical axis
  VibrationOptions vibration;   // camera mount vibration
  // What the path follower steers on: kLocalized (wheel odometry corrected by periodic
  // localisation fixes, `localization`), kOdometry (pure dead reckoning from the wheel and
  // steering encoders) or kGroundTruth (the true pose: an ideal robot). The recorded odometry is
  // the raw wheel odometry in every mode.
  enum class Navigation { kLocalized, kOdometry, kGroundTruth };
  Navigation navigation;
  LocalizationOptions localization;  // fixes used by kLocalized

  // Smallest radius the base can turn on: L / tan(max_steer).
  double MinTurnRadiusM() const;
  TricycleOptions();  // the registered defaults
  // Every field once: JSON name (the scene's /robot), unit, default, range, description.
  static const OptionTable<TricycleOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

// The paper room's route (clockwise around the table row, 0.4 m from the walls).
std::vector<Eigen::Vector2d> PaperRoomWaypoints();

// A closed waypoint polygon driven in waypoint order (the paper's route is clockwise). Corners are
// rounded with arcs of corner_radius_m; pure pursuit tracks that path at a curvature-limited speed.
// The defaults drive 1.99 laps of the paper room in 1996 frames at 25 Hz, keeping the base at
// least 0.32 m from the furniture (tests/sim/robot_test.cpp).
struct RouteOptions {
  std::vector<Eigen::Vector2d> waypoints_m;  // m, polygon corners, in order
  double laps;                               // laps to drive when frames == 0
  int frames;                                // frames to simulate; > 0 overrides laps
  double cruise_speed_m_s;                   // m/s, speed of the base on straight stretches
  double lookahead_m;                        // m, pure-pursuit lookahead along the path
  double max_lateral_accel_m_s2;             // m/s^2, bounds speed in turns: v^2 * curvature
  double corner_radius_m;                    // m, radius of the arcs rounding the polygon corners

  RouteOptions();  // the registered defaults
  // Every field once: JSON name (the scene's /route), unit, default, range, description.
  static const OptionTable<RouteOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
  // (Limits shared with the robot are checked by SimulateRobot.)
};

// How the true motion differs from what the encoders report (docs/models/robot.md derives the defaults
// from published figures). The drive motor is servoed on the wheel encoder and the steering motor
// on the steering encoder, so the commanded motion is what odometry integrates (with the nominal
// wheel radius and wheelbase); the true motion is
//   travel = encoder rotation * r_true * (1 - slip),  slip = k_a * a * (1 + slip_noise * n1)
//   steer  = measured steering + steer_offset
//   turn   = travel * tan(steer) / L_true * (1 - k_t * |a_lat| * (1 + slip_noise * n2))
//            + heading_noise * sqrt(travel) * n3
// with n1..n3 standard normal from KeyedRng(seed, "robot.odometry", integration step). The encoder
// counts are quantised (counts_per_rev). error_scale multiplies every error term.
struct OdometryErrorOptions {
  bool enabled;                         // false: the true motion is the measured motion
  double error_scale;                   // multiplies every error below (0: perfect)
  double wheel_radius_error_frac;       // true / nominal driven-wheel radius - 1
  double steer_offset_deg;              // deg, true steering angle minus the measured one
  double wheelbase_error_frac;          // true / nominal wheelbase - 1
  double encoder_counts_per_rev;        // drive-wheel encoder counts per revolution
  double wheel_radius_m;                // m, nominal driven-wheel radius
  double slip_per_accel_s2_m;           // longitudinal slip per m/s^2 of acceleration
  double turn_slip_per_lat_accel_s2_m;  // yaw-rate shortfall per m/s^2 of lateral accel.
  double slip_noise_frac;               // relative sd of both slips
  double heading_noise_deg_sqrt_m;      // deg/sqrt(m), random heading walk (floor)

  OdometryErrorOptions();  // the registered defaults
  // Every field once: JSON name (the scene's /odometry), unit, default, range, description.
  static const OptionTable<OdometryErrorOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
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

  static Obstacle2D Rectangle(std::string name, const Eigen::Vector2d& center_m, const Eigen::Vector2d& size_m,
                              double yaw_rad = 0);
  static Obstacle2D Circle(std::string name, const Eigen::Vector2d& center_m, double radius_m);
};

// The footprints as the dataset records them (footprints.json), in input order.
std::vector<FootprintRecord> FootprintRecordsOf(const std::vector<Obstacle2D>& obstacles);

// Euclidean distance from a point to the obstacle's footprint (0 inside).
double DistanceToObstacle(const Eigen::Vector2d& point_m, const Obstacle2D& obstacle);

// Whether two footprints overlap (touching counts as overlapping).
bool FootprintsOverlap(const Obstacle2D& a, const Obstacle2D& b);

// Every pair (i, j), i < j, of `footprints` that overlap (FootprintsOverlap), in increasing order:
// a sweep along x over their bounding discs tests only footprints whose discs meet in x, so
// thousands of footprints spread over a floor take O(n log n) plus the pairs found, not n^2 tests.
std::vector<std::pair<size_t, size_t>> OverlappingFootprints(const std::vector<Obstacle2D>& footprints);

// The camera's world pose for a base pose (rigid front mount from the options).
CameraPose CameraPoseFromBase(const Pose2& base, const TricycleOptions& options);

// The camera's deviation from its rigid mount (vibration).
struct MountMotion {
  double roll_rad = 0, pitch_rad = 0, height_m = 0;
};

struct RobotSample {
  int frame = 0;
  double time_s = 0;      // s, frame / frame_rate_hz
  Pose2 base;             // ground truth; theta wrapped to (-pi, pi]
  CameraPose camera;      // ground truth camera pose, vibration included
  MountMotion vibration;  // the camera's deviation from its rigid mount
  Pose2 odometry;         // wheel odometry; theta wrapped to (-pi, pi]
  double speed_m_s = 0;   // m/s, front-wheel speed
  double steer_rad = 0;   // rad, steering angle
  double lap = 0;         // laps completed: distance along the rounded route / its length
};

struct RobotRun {
  std::vector<RobotSample> samples;
  double min_obstacle_distance_m = 0;       // m, over all obstacles and integration steps (base point)
  std::string closest_obstacle;             // name of the obstacle reaching that minimum
  std::vector<double> obstacle_distance_m;  // m, per obstacle (input order): its minimum
  double max_curvature_per_m = 0;           // 1/m, largest |commanded curvature|
  double max_tracking_error_m = 0;          // m, largest distance of the steered-on pose from the route
  int localization_fixes = 0;               // number of localisation fixes applied (kLocalized)
  double max_route_deviation_m = 0;         // m, largest distance of the true base from the route
  double path_length_m = 0;                 // m, distance travelled by the base
  double heading_change_rad = 0;            // rad, total signed heading change (-2 pi per clockwise lap)
  double laps = 0;                          // laps completed at the last sample
};

// Simulates from t = 0; frame k is at t = k / frame_rate_hz. The robot starts at rest on the first
// waypoint, heading towards the second. If route.frames == 0 it runs until `laps` laps are done
// (the first frame reaching them is the last; laps as the robot believes them). Throws InputError
// on invalid or infeasible options and on any footprint overlap with an obstacle at an integration
// step (naming the frame, the obstacle and the drift from the route).
RobotRun SimulateRobot(const TricycleOptions& robot, const RouteOptions& route, const OdometryErrorOptions& odometry,
                       const std::vector<Obstacle2D>& obstacles, double frame_rate_hz, uint64_t seed);

// The dataset's poses.csv rows for the first `frames` samples (all when frames < 0).
std::vector<PoseRecord> PoseRecordsOf(const RobotRun& run, int frames = -1);

}  // namespace hoilcd
