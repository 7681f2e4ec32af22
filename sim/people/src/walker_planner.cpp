#include "hoilcd/sim/people/walker_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include <Eigen/Geometry>

#include "hoilcd/sim/assets/skeleton.h"

namespace hoilcd {
namespace {

using Vec2 = Eigen::Vector2d;

// Margin beyond the grown footprints where graph corners sit, m (keeps them strictly free).
constexpr double kCornerMarginM = 0.02;
// Time step of the clearance checks against the robot and other walkers, s.
constexpr double kCheckStepS = 0.1;
// Extra gap kept between two walkers' footprints, m.
constexpr double kWalkerGapM = 0.05;
// A walker out of the room stays out at least this long before it comes back in, s.
constexpr double kMinOutS = 1.0;
// Outside a door a walker's body is this much beyond its radius behind the wall (hidden by it), m.
constexpr double kBehindWallM = 0.2;

// Distance from point p to the segment ab.
double PointSegmentDistance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double f = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + f * d - p).norm();
}

// Distance from segment ab to an obstacle's footprint (0 when they touch or cross).
double SegmentObstacleDistance(const Vec2& a, const Vec2& b, const Obstacle2D& o) {
  if (o.shape == Obstacle2D::Shape::kCircle) return std::max(0.0, PointSegmentDistance(o.center_m, a, b) - o.radius_m);
  // In the rectangle's frame: clip the segment against the box (Liang-Barsky); if nothing is
  // left, the nearest points are an end of the segment or a corner of the box.
  const Eigen::Rotation2Dd to_box(-o.yaw_rad);
  const Vec2 p = to_box * (a - o.center_m), q = to_box * (b - o.center_m);
  const Vec2 h = o.half_size_m, d = q - p;
  double lo = 0, hi = 1;
  bool crosses = true;
  for (int k = 0; k < 2 && crosses; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      crosses = std::abs(p[k]) <= h[k];
      continue;
    }
    double t0 = (-h[k] - p[k]) / d[k], t1 = (h[k] - p[k]) / d[k];
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
    crosses = lo <= hi;
  }
  if (crosses) return 0.0;
  auto box_distance = [&](const Vec2& v) { return (v.cwiseAbs() - h).cwiseMax(0.0).norm(); };
  double best = std::min(box_distance(p), box_distance(q));
  for (int sx : {-1, 1})
    for (int sy : {-1, 1}) best = std::min(best, PointSegmentDistance(Vec2(sx * h.x(), sy * h.y()), p, q));
  return best;
}

double PolylineLength(const std::vector<Vec2>& path) {
  double length = 0;
  for (size_t i = 1; i < path.size(); ++i) length += (path[i] - path[i - 1]).norm();
  return length;
}

// The point at arc length s along a polyline (clamped to its ends).
Vec2 PointAlong(const std::vector<Vec2>& path, double s) {
  for (size_t i = 1; i < path.size(); ++i) {
    const double step = (path[i] - path[i - 1]).norm();
    if (s <= step) return path[i - 1] + (step > 0 ? s / step : 0.0) * (path[i] - path[i - 1]);
    s -= step;
  }
  return path.back();
}

// The facing at arc length s along a path: each corner's turn spread evenly over the `window_m`
// either side of it, so a sharp corner (a path wrapping round a table's end) turns at a bounded
// rate instead of flipping where the chord across it vanishes.
double HeadingAlong(const std::vector<Vec2>& path, double s, double window_m) {
  double heading = 0, corner_s = 0, previous = 0;
  bool first = true;
  for (size_t i = 1; i < path.size(); ++i) {
    const Vec2 step = path[i] - path[i - 1];
    if (step.norm() < 1e-9) continue;
    const double h = std::atan2(step.y(), step.x());
    if (first) {
      heading = h;
      first = false;
    } else {
      const double turn = std::remainder(h - previous, 2 * M_PI);
      heading += turn * std::clamp((s - corner_s + window_m) / (2 * window_m), 0.0, 1.0);
    }
    previous = h;
    corner_s += step.norm();
  }
  return heading;
}

// True when the segment keeps clear of the robot and of every other walker present.
bool ClearOfRobotAndWalkers(const WalkerSegment& segment, const WalkerPlan& plan, const RobotTrack& robot,
                            const std::vector<WalkerPlan>& others, bool check_robot) {
  const double radius_m = plan.radius_m;
  const WalkerPlan single{{segment}, radius_m, plan.space, plan.lateral_m};
  for (double x = segment.start_s; x <= segment.end_s; x += kCheckStepS) {
    const WalkerPlacement me = PlaceWalker(single, robot, x);
    if (!me.present) continue;
    if (check_robot && (me.at_m - robot.At(x)).norm() < kWalkerRobotClearanceM) return false;
    for (const WalkerPlan& other : others) {
      const WalkerPlacement them = PlaceWalker(other, robot, x);
      if (them.present && (me.at_m - them.at_m).norm() < radius_m + other.radius_m + kWalkerGapM) return false;
    }
  }
  return true;
}

// A route-following walker's floor position at time t (heading_rad: the route's there).
Vec2 OnRoute(const WalkerSegment& s, const FreeSpace* space, const RobotTrack& robot, double time_s, double lateral_m,
             double* heading_rad) {
  const double u = std::clamp(s.u_start + s.rate * (time_s - s.start_s), robot.start_s(), robot.end_s());
  double heading = 0;
  const Vec2 on_route = robot.At(u, &heading);
  double offset = lateral_m;
  if (s.pass_offset_m != 0) {
    // Overtaking: aside while within 0.8 m of route of the robot, back on the route from 1.6 m.
    const double gap = std::abs(robot.DistanceAt(u) - robot.DistanceAt(time_s));
    offset += s.pass_offset_m * SmoothStep((1.6 - gap) / 0.8);
  }
  if (heading_rad != nullptr) *heading_rad = heading;
  const Vec2 left(-std::sin(heading), std::cos(heading));
  const Vec2 at = on_route + offset * left;
  if (space == nullptr) return at;
  return space->FreeAlong(at, left, kWalkerMaxSidestepM).value_or(at);
}

// A crossing of the robot's path 1-3 s of route beyond `lead` ahead of it: from a free point
// 0.6-2 m on one side of the route to one 0.6-2 m on the other, on the shortest free path between
// them, finished while the robot is still at least kMinWalkerLeadS short of the crossing.
std::optional<WalkerSegment> PlanCross(const FreeSpace& space, const RobotTrack& robot, double t, double lead,
                                       Rng* rng) {
  const double u_cross = t + lead + rng->Uniform(1.0, 3.0);
  const double angle = rng->Uniform(-0.5, 0.5);
  const double sign = rng->Uniform() < 0.5 ? 1.0 : -1.0;
  const double speed = rng->Uniform(1.0, 1.3);  // m/s, an ordinary walking pace
  if (u_cross > robot.end_s()) return std::nullopt;
  double heading = 0;
  const Vec2 c = robot.At(u_cross, &heading);
  const Vec2 dir = sign * (Eigen::Rotation2Dd(heading + M_PI / 2 + angle) * Vec2::UnitX());
  // The longest crossing that fits: each end as far out as the furniture allows.
  constexpr std::array<double, 6> kReachM = {2.0, 1.6, 1.3, 1.0, 0.8, 0.6};
  for (double reach_a : kReachM) {
    for (double reach_b : kReachM) {
      const Vec2 a = c - reach_a * dir, b = c + reach_b * dir;
      if (space.Clearance(a) < kCornerMarginM || space.Clearance(b) < kCornerMarginM) continue;
      std::vector<Vec2> path = space.ShortestPath(a, b);
      const double length = PolylineLength(path);
      if (path.empty() || length > 1.5 * (reach_a + reach_b)) continue;  // a detour round the furniture is no crossing
      WalkerSegment s;
      s.behaviour = "cross";
      s.start_s = t;
      s.end_s = t + length / speed + 0.5;  // and a breath at the far side
      s.path_m = std::move(path);
      s.speed_m_s = speed;
      s.rate = speed / robot.cruise_speed_m_s();
      s.u_start = t + lead;
      if (s.end_s > u_cross - kMinWalkerLeadS) continue;  // the robot would be upon the crossing
      return s;
    }
  }
  return std::nullopt;
}

// An overtaking: from 3-5 s of route behind the robot to 3-5 s ahead at ~1.1 m/s, stepping
// aside (left or right, wherever the furniture leaves room) while level with it.
std::optional<WalkerSegment> PlanOvertake(const FreeSpace& space, const RobotTrack& robot, double t, Rng* rng) {
  const double lag = rng->Uniform(3.0, 5.0), lead_after = rng->Uniform(3.0, 5.0), rate = rng->Uniform(2.2, 2.8);
  const double first_side = rng->Uniform() < 0.5 ? 1.0 : -1.0;
  WalkerSegment s;
  s.behaviour = "overtake";
  s.start_s = t;
  s.end_s = t + (lag + lead_after) / (rate - 1);
  s.u_start = t - lag;
  s.rate = rate;
  if (s.u_start < robot.start_s() || s.u_start + rate * (s.end_s - t) > robot.end_s()) return std::nullopt;
  for (double side : {first_side, -first_side}) {
    s.pass_offset_m = side * (kWalkerRobotClearanceM + 0.08);
    const WalkerPlan plan{{s}, space.radius_m(), nullptr};
    bool free = true;
    for (double x = s.start_s; x <= s.end_s && free; x += kCheckStepS) {
      const Vec2 at = PlaceWalker(plan, robot, x).at_m;
      free = space.Clearance(at) >= 0 && (at - robot.At(x)).norm() >= kWalkerRobotClearanceM;
    }
    if (free) return s;
  }
  return std::nullopt;
}

// A route-following bout from time t with the robot `lead` seconds of route behind: its rate and
// length drawn for the behaviour; never past the robot's last place on the route (the walker
// would wait there for the robot to drive into it). nullopt when too little of the run is left.
std::optional<WalkerSegment> PlanRouteBout(const std::string& behaviour, const RobotTrack& robot, double t, double lead,
                                           Rng* rng) {
  WalkerSegment seg;
  seg.behaviour = behaviour;
  seg.start_s = t;
  seg.u_start = t + lead;
  double length = 0;
  if (behaviour == "ahead") {
    seg.rate = rng->Uniform(0.9, 1.1);
    length = rng->Uniform(4, 10);
    if (seg.rate < 1) length = std::min(length, (lead - kMinWalkerLeadS) / (1 - seg.rate));
  } else if (behaviour == "away") {
    seg.rate = rng->Uniform(2.2, 2.8);      // ~1.1 m/s against the robot's ~0.45 m/s
    length = (20 - lead) / (seg.rate - 1);  // until 20 s of route ahead: out of sight
  } else if (behaviour == "approach") {
    seg.rate = -rng->Uniform(1.2, 1.6);  // towards the robot at ~0.6 m/s
    length = (lead - kMinWalkerLeadS - 0.5) / (1 - seg.rate);
  } else {
    seg.rate = 0;  // standing, chatting with someone at a table
    length = std::min(rng->Uniform(4, 9), lead - kMinWalkerLeadS - 0.5);
  }
  length = std::max(length, 0.5);
  const double last_u = robot.end_s() - 0.1;
  if (seg.rate > 0) length = std::min(length, (last_u - seg.u_start) / seg.rate);
  if (seg.u_start > last_u || length < 0.5) return std::nullopt;
  seg.end_s = t + length;
  return seg;
}

// Where a walker stands outside a door: its whole body behind the wall.
Vec2 BehindDoor(const Doorway& door, double radius_m) {
  return door.center_m - (radius_m + kBehindWallM) * door.inward;
}

// A walk through a door at speed_m_s between behind it and `inside` (in: arriving at `inside` at
// time_s, starting no earlier than earliest_s; out: leaving `inside` at time_s), through the door
// with the shortest free walk that keeps clear of the robot and the other walkers.
std::optional<WalkerSegment> PlanDoorWalk(bool in, const Vec2& inside, double time_s, double earliest_s,
                                          double speed_m_s, const std::vector<Doorway>& doors, const WalkerPlan& plan,
                                          const RobotTrack& robot, const std::vector<WalkerPlan>& others) {
  std::vector<std::pair<double, std::vector<Vec2>>> ways;  // length, path (in the walking order)
  for (const Doorway& door : doors) {
    const std::vector<Vec2> free = plan.space->ShortestPath(DoorThreshold(door, plan.radius_m), inside);
    if (free.empty()) continue;
    std::vector<Vec2> path{BehindDoor(door, plan.radius_m)};
    path.insert(path.end(), free.begin(), free.end());
    if (!in) std::reverse(path.begin(), path.end());
    ways.emplace_back(PolylineLength(path), std::move(path));
  }
  std::stable_sort(ways.begin(), ways.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& [length, path] : ways) {
    WalkerSegment s;
    s.behaviour = in ? "enter" : "leave";
    s.start_s = in ? time_s - length / speed_m_s : time_s;
    s.end_s = s.start_s + length / speed_m_s;
    if (s.start_s < earliest_s) continue;
    s.path_m = std::move(path);
    s.speed_m_s = speed_m_s;
    s.rate = speed_m_s / robot.cruise_speed_m_s();
    if (ClearOfRobotAndWalkers(s, plan, robot, others, true)) return s;
  }
  return std::nullopt;
}

// A bout's first and last floor positions.
Vec2 StartOf(const WalkerSegment& s, const WalkerPlan& plan, const RobotTrack& robot) {
  return PlaceWalker(WalkerPlan{{s}, plan.radius_m, plan.space, plan.lateral_m}, robot, s.start_s).at_m;
}
Vec2 EndOf(const WalkerSegment& s, const WalkerPlan& plan, const RobotTrack& robot) {
  return PlaceWalker(WalkerPlan{{s}, plan.radius_m, plan.space, plan.lateral_m}, robot, s.end_s - 1e-9).at_m;
}

// One behaviour drawn by weight (the first with weight when the draw falls past the end).
size_t DrawBehaviour(const std::array<double, kWalkerBehaviourCount>& w, Rng* rng) {
  double total = 0;
  for (double x : w) total += x;
  double pick = rng->Uniform() * total;
  for (size_t i = 0; i < w.size(); ++i) {
    pick -= w[i];
    if (pick < 0 && w[i] > 0) return i;
  }
  for (size_t i = 0; i < w.size(); ++i)
    if (w[i] > 0) return i;
  return 0;
}

}  // namespace

const std::array<const char*, kWalkerBehaviourCount> kWalkerBehaviours = {"ahead",        "away",  "approach",
                                                                          "stop_to_chat", "cross", "overtake"};

RobotTrack::RobotTrack(const std::vector<RobotSample>& samples) {
  double distance_m = 0;
  for (const RobotSample& s : samples) {
    if (!samples_.empty()) distance_m += std::hypot(s.base.x_m - samples_.back().x_m, s.base.y_m - samples_.back().y_m);
    samples_.push_back({s.time_s, s.base.x_m, s.base.y_m, s.base.theta_rad, distance_m});
  }
  std::vector<double> speeds;
  for (size_t i = 1; i < samples_.size(); ++i) {
    const double v = (samples_[i].distance_m - samples_[i - 1].distance_m) /
                     std::max(1e-9, samples_[i].time_s - samples_[i - 1].time_s);
    if (v > 0.05) speeds.push_back(v);
  }
  if (!speeds.empty()) {
    std::nth_element(speeds.begin(), speeds.begin() + static_cast<long>(speeds.size() / 2), speeds.end());
    cruise_speed_m_s_ = speeds[speeds.size() / 2];
  }
}

size_t RobotTrack::After(double time_s) const {
  const auto it = std::lower_bound(samples_.begin(), samples_.end(), time_s,
                                   [](const Sample& s, double v) { return s.time_s < v; });
  return static_cast<size_t>(it - samples_.begin());
}

Eigen::Vector2d RobotTrack::At(double time_s, double* heading_rad) const {
  if (samples_.empty()) return Vec2(-1e3, -1e3);
  const size_t i = After(time_s);
  const Sample& b = i == samples_.size() ? samples_.back() : samples_[i];
  const Sample& a = i == 0 || i == samples_.size() ? b : samples_[i - 1];
  const double f = b.time_s > a.time_s ? (time_s - a.time_s) / (b.time_s - a.time_s) : 0.0;
  if (heading_rad != nullptr) *heading_rad = a.theta_rad + f * std::remainder(b.theta_rad - a.theta_rad, 2 * M_PI);
  return Vec2(a.x_m + f * (b.x_m - a.x_m), a.y_m + f * (b.y_m - a.y_m));
}

double RobotTrack::DistanceAt(double time_s) const {
  if (samples_.empty()) return 0;
  const size_t i = After(time_s);
  const Sample& b = i == samples_.size() ? samples_.back() : samples_[i];
  const Sample& a = i == 0 || i == samples_.size() ? b : samples_[i - 1];
  const double f = b.time_s > a.time_s ? (time_s - a.time_s) / (b.time_s - a.time_s) : 0.0;
  return a.distance_m + f * (b.distance_m - a.distance_m);
}

FreeSpace::FreeSpace(std::vector<Obstacle2D> obstacles, double radius_m)
    : obstacles_(std::move(obstacles)), radius_m_(radius_m) {
  // Corners of each footprint grown by the radius (circles: an octagon around the grown circle);
  // shortest paths among polygons bend only at such corners.
  const double grow = radius_m_ + kCornerMarginM;
  for (const Obstacle2D& o : obstacles_) {
    if (o.shape == Obstacle2D::Shape::kCircle) {
      const double r = (o.radius_m + grow) / std::cos(M_PI / 8);
      for (int k = 0; k < 8; ++k)
        nodes_.push_back(o.center_m + r * Vec2(std::cos(k * M_PI / 4), std::sin(k * M_PI / 4)));
      continue;
    }
    const Eigen::Rotation2Dd rot(o.yaw_rad);
    for (int sx : {-1, 1})
      for (int sy : {-1, 1})
        nodes_.push_back(o.center_m + rot * Vec2(sx * (o.half_size_m.x() + grow), sy * (o.half_size_m.y() + grow)));
  }
  nodes_.erase(std::remove_if(nodes_.begin(), nodes_.end(), [&](const Vec2& p) { return Clearance(p) < 0; }),
               nodes_.end());
  edges_.resize(nodes_.size());
  for (size_t i = 0; i < nodes_.size(); ++i) {
    for (size_t j = i + 1; j < nodes_.size(); ++j) {
      if (!SegmentFree(nodes_[i], nodes_[j])) continue;
      const double d = (nodes_[i] - nodes_[j]).norm();
      edges_[i].emplace_back(static_cast<int>(j), d);
      edges_[j].emplace_back(static_cast<int>(i), d);
    }
  }
}

double FreeSpace::Clearance(const Eigen::Vector2d& p, std::string* nearest) const {
  double best = std::numeric_limits<double>::infinity();
  for (const Obstacle2D& o : obstacles_) {
    const double d = DistanceToObstacle(p, o);
    if (d < best) {
      best = d;
      if (nearest != nullptr) *nearest = o.name;
    }
  }
  return best - radius_m_;
}

bool FreeSpace::SegmentFree(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
  return std::all_of(obstacles_.begin(), obstacles_.end(),
                     [&](const Obstacle2D& o) { return SegmentObstacleDistance(a, b, o) >= radius_m_; });
}

std::optional<Eigen::Vector2d> FreeSpace::FreeAlong(const Eigen::Vector2d& p, const Eigen::Vector2d& direction,
                                                    double max_shift_m) const {
  if (Clearance(p) >= 0) return p;
  for (double shift = 0.005; shift <= max_shift_m + 1e-9; shift += 0.005) {
    for (double sign : {1.0, -1.0}) {
      const Vec2 q = p + sign * shift * direction;
      if (Clearance(q) >= 0) return q;
    }
  }
  return std::nullopt;
}

std::vector<Eigen::Vector2d> FreeSpace::ShortestPath(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
  if (Clearance(a) < 0 || Clearance(b) < 0) return {};
  if (SegmentFree(a, b)) return {a, b};
  // Dijkstra over the corners, with a as source (index n) and b as target (index n + 1).
  const int n = static_cast<int>(nodes_.size()), source = n, target = n + 1;
  auto point = [&](int i) -> const Vec2& { return i == source ? a : i == target ? b : nodes_[static_cast<size_t>(i)]; };
  std::vector<double> cost(static_cast<size_t>(n + 2), std::numeric_limits<double>::infinity());
  std::vector<int> previous(static_cast<size_t>(n + 2), -1);
  std::vector<char> sees_target(static_cast<size_t>(n), 0);
  for (int i = 0; i < n; ++i) sees_target[static_cast<size_t>(i)] = SegmentFree(nodes_[static_cast<size_t>(i)], b);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  cost[static_cast<size_t>(source)] = 0;
  queue.emplace(0.0, source);
  while (!queue.empty()) {
    const double c = queue.top().first;  // named locals, not a structured binding: C++17 lambdas
    const int i = queue.top().second;    // cannot capture bindings (clang refuses; the fuzz build)
    queue.pop();
    if (c > cost[static_cast<size_t>(i)]) continue;
    if (i == target) break;
    auto relax = [&](int j, double d) {
      if (c + d < cost[static_cast<size_t>(j)]) {
        cost[static_cast<size_t>(j)] = c + d;
        previous[static_cast<size_t>(j)] = i;
        queue.emplace(c + d, j);
      }
    };
    if (i == source) {
      for (int j = 0; j < n; ++j)
        if (SegmentFree(a, nodes_[static_cast<size_t>(j)])) relax(j, (a - nodes_[static_cast<size_t>(j)]).norm());
      continue;
    }
    for (const auto& [j, d] : edges_[static_cast<size_t>(i)]) relax(j, d);
    if (sees_target[static_cast<size_t>(i)]) relax(target, (point(i) - b).norm());
  }
  if (previous[static_cast<size_t>(target)] < 0) return {};
  std::vector<Vec2> path;
  for (int i = target; i >= 0; i = previous[static_cast<size_t>(i)]) path.push_back(point(i));
  std::reverse(path.begin(), path.end());
  return path;
}

const WalkerSegment& WalkerPlan::At(double time_s) const {
  for (const WalkerSegment& s : segments)
    if (time_s < s.end_s) return s;
  return segments.back();
}

double WalkerPlan::RouteTime(double time_s) const {
  const WalkerSegment& s = At(time_s);
  return s.u_start + s.rate * (time_s - s.start_s);
}

double WalkerPlan::Walked(double time_s) const {
  double walked = 0;
  for (const WalkerSegment& s : segments) {
    double walking_until = std::min(time_s, s.end_s);
    if (!s.path_m.empty()) walking_until = std::min(walking_until, s.start_s + PolylineLength(s.path_m) / s.speed_m_s);
    walked += std::abs(s.rate) * std::max(0.0, walking_until - s.start_s);
    if (time_s < s.end_s) break;
  }
  return walked;
}

Eigen::Vector2d DoorThreshold(const Doorway& door, double radius_m) {
  return door.center_m + (radius_m + kCornerMarginM + 0.01) * door.inward;
}

namespace {

// Where segment s puts the walker at time t, facing the way that segment goes.
WalkerPlacement PlaceOnSegment(const WalkerPlan& plan, const WalkerSegment& s, const RobotTrack& robot, double time_s) {
  const double lateral_m = plan.lateral_m;
  WalkerPlacement out;
  if (robot.empty() || s.behaviour == "gone") return out;
  if (!s.path_m.empty()) {
    // On a free path: rounding each corner from 0.3 m before it to 0.3 m after it.
    const double length = PolylineLength(s.path_m);
    const double along = std::clamp(s.speed_m_s * (time_s - s.start_s), 0.0, length);
    out.at_m = PointAlong(s.path_m, along);
    out.heading_rad = HeadingAlong(s.path_m, along, 0.3);
    out.speed_m_s = along < length ? s.speed_m_s : 0.0;
    out.present = true;
    return out;
  }
  out.present = true;
  double route_heading = 0;
  out.at_m = OnRoute(s, plan.space.get(), robot, time_s, lateral_m, &route_heading);
  // Facing: along the route, back towards the robot when approaching it, to the tables (on the
  // right of a clockwise lap) when stopping to chat; overtaking, along the way it steps aside.
  out.heading_rad = route_heading + (s.rate < 0 ? M_PI : 0.0) + (s.behaviour == "stop_to_chat" ? -M_PI / 2 : 0.0);
  if (s.pass_offset_m != 0) {
    const Vec2 d = OnRoute(s, plan.space.get(), robot, time_s + 0.1, lateral_m, nullptr) - out.at_m;
    if (d.norm() > 1e-6) out.heading_rad = std::atan2(d.y(), d.x());
  }
  out.speed_m_s = std::abs(s.rate) * robot.cruise_speed_m_s();
  return out;
}

// Segment `index`'s placement at time t, with the turn from the facing the walker had when it
// began (itself still turning, if the segment before was short).
WalkerPlacement PlaceTurning(const WalkerPlan& plan, size_t index, const RobotTrack& robot, double time_s) {
  const WalkerSegment& s = plan.segments[index];
  WalkerPlacement out = PlaceOnSegment(plan, s, robot, time_s);
  // Where one segment hands over to the next (a door walk joining the route, turning back
  // towards the robot, stopping to chat), the walker turns from the facing it had at a brisk
  // pace (180° in a second), easing in and out, instead of snapping round.
  constexpr double kTurnRateRadS = M_PI;
  if (!out.present || index == 0 || time_s - s.start_s >= M_PI / kTurnRateRadS) return out;
  const WalkerPlacement before = PlaceTurning(plan, index - 1, robot, s.start_s);
  if (!before.present) return out;
  // The turn's direction is the shorter way at the hand-over; the facing it turns towards may go
  // on changing (a corner of the route), and is followed continuously from there.
  const double start_heading = PlaceOnSegment(plan, s, robot, s.start_s).heading_rad;
  const double start_turn = std::remainder(start_heading - before.heading_rad, 2 * M_PI);
  const double turn_s = std::abs(start_turn) / kTurnRateRadS;
  if (time_s - s.start_s >= turn_s) return out;
  const double turn = start_turn + std::remainder(out.heading_rad - start_heading, 2 * M_PI);
  out.heading_rad = before.heading_rad + turn * SmoothStep((time_s - s.start_s) / turn_s);
  return out;
}

}  // namespace

WalkerPlacement PlaceWalker(const WalkerPlan& plan, const RobotTrack& robot, double time_s) {
  const WalkerSegment& s = plan.At(time_s);
  return PlaceTurning(plan, static_cast<size_t>(&s - plan.segments.data()), robot, time_s);
}

namespace {

// One walker's plan, bout by bout: in the room, another bout on the route or out through a door;
// out of it, the next bout walked into from a door, taken only when a way out from its end exists.
class WalkerPlanner {
 public:
  WalkerPlanner(const std::map<std::string, double>& weights, uint64_t seed, int walker, double duration_s,
                std::shared_ptr<const FreeSpace> space, const RobotTrack& robot, const std::vector<WalkerPlan>& others,
                const std::vector<Doorway>& doors, double lateral_m)
      : weights_(weights),
        duration_s_(duration_s),
        space_(*space),
        robot_(robot),
        others_(others),
        doors_(doors),
        rng_(KeyedRng(seed, "crowd.walker_plan", static_cast<uint64_t>(walker))) {
    plan_.radius_m = space->radius_m();
    plan_.space = space;
    plan_.lateral_m = lateral_m;
    door_speed_m_s_ = rng_.Uniform(1.0, 1.3);  // its pace in and out, an ordinary walk
    lead_ = rng_.Uniform(4.0, 9.0);
    door_passes_ = DoorPasses();
  }

  WalkerPlan Plan() {
    while (t_ < duration_s_ + 1) {
      if (inside_) {
        NextBoutInside();
      } else {
        NextBoutFromOutside();
      }
    }
    return std::move(plan_);
  }

 private:
  // Route times at which the robot passes closest to a door (within 1.5 m), ascending.
  std::vector<double> DoorPasses() const {
    auto nearest_door_m = [&](double u) {
      double best = 1e9;
      for (const Doorway& door : doors_)
        best = std::min(best, (robot_.At(u) - DoorThreshold(door, plan_.radius_m)).norm());
      return best;
    };
    std::vector<double> passes;
    for (double u = robot_.start_s() + 0.1; u + 0.1 <= robot_.end_s(); u += 0.1) {
      const double d = nearest_door_m(u);
      if (d < 1.5 && d <= nearest_door_m(u - 0.1) && d < nearest_door_m(u + 0.1)) passes.push_back(u);
    }
    return passes;
  }

  void PushGone(double until_s) {
    if (until_s <= t_) return;
    WalkerSegment gone;
    gone.behaviour = "gone";
    gone.start_s = t_;
    gone.end_s = until_s;
    plan_.segments.push_back(gone);
    t_ = until_s;
  }

  void GoOut() {
    plan_.segments.insert(plan_.segments.end(), way_out_->begin(), way_out_->end());
    t_ = way_out_->empty() ? duration_s_ + 1 : way_out_->back().end_s;
    way_out_.reset();
    inside_ = false;
    last_bout_.clear();
  }

  // Behaviours possible from a lead: approach needs room to come closer; keeping pace needs a
  // walker's following distance and is never done twice in a row (nobody strolls at a robot's
  // pace in front of it for long: they go on to somewhere).
  std::array<double, kWalkerBehaviourCount> Possible(double from_lead) const {
    std::array<double, kWalkerBehaviourCount> w{};
    for (size_t i = 0; i < w.size(); ++i) {
      const std::string b = kWalkerBehaviours[i];
      const bool possible = (b != "approach" || from_lead >= 8) && (b != "stop_to_chat" || from_lead >= 6) &&
                            (b != "ahead" || (from_lead >= kMinAheadLeadS && last_bout_ != "ahead"));
      w[i] = possible ? weights_.at(b) : 0.0;
    }
    return w;
  }

  // The way out after a bout: straight to a door, or first on along the route ahead of the robot
  // (briskly, as "away") until a door can be reached without meeting it; none needed when the run
  // is over by then.
  std::optional<std::vector<WalkerSegment>> ExitAfter(const WalkerSegment& bout) const {
    if (bout.end_s >= duration_s_) return std::vector<WalkerSegment>{};
    if (auto out = PlanDoorWalk(false, EndOf(bout, plan_, robot_), bout.end_s, bout.end_s, door_speed_m_s_, doors_,
                                plan_, robot_, others_))
      return std::vector<WalkerSegment>{*out};
    if (!bout.path_m.empty()) return std::nullopt;
    WalkerSegment on;
    on.behaviour = "away";
    on.start_s = bout.end_s;
    on.u_start = bout.u_start + bout.rate * (bout.end_s - bout.start_s);
    on.rate = 2.4;  // ~1.1 m/s
    for (double walk_s = 1; walk_s <= 30; walk_s += 1) {
      on.end_s = on.start_s + walk_s;
      if (on.end_s >= duration_s_) return std::vector<WalkerSegment>{on};
      if (on.u_start + on.rate * walk_s > robot_.end_s() - 0.1 ||
          !ClearOfRobotAndWalkers(on, plan_, robot_, others_, false))
        break;
      if (auto out = PlanDoorWalk(false, EndOf(on, plan_, robot_), on.end_s, on.end_s, door_speed_m_s_, doors_, plan_,
                                  robot_, others_))
        return std::vector<WalkerSegment>{on, *out};
    }
    return std::nullopt;
  }

  // Takes the bout (walked into by `in` unless the run starts with it) if a way out from its end exists.
  bool Place(const std::optional<WalkerSegment>& in, const WalkerSegment& bout) {
    const std::optional<std::vector<WalkerSegment>> out = ExitAfter(bout);
    if (!out) return false;
    if (in) {
      PushGone(in->start_s);
      plan_.segments.push_back(*in);
    }
    plan_.segments.push_back(bout);
    last_bout_ = bout.behaviour;
    t_ = bout.end_s;
    way_out_ = out;
    inside_ = true;
    lead_ = bout.u_start + bout.rate * (bout.end_s - bout.start_s) - bout.end_s;
    if (bout.behaviour == "cross" || bout.behaviour == "away") GoOut();
    return true;
  }

  // In the room: another bout on the route from where it is, or out through a door.
  void NextBoutInside() {
    const std::string behaviour = kWalkerBehaviours[DrawBehaviour(Possible(lead_), &rng_)];
    if (behaviour == "cross" || behaviour == "overtake") {  // these start elsewhere
      wanted_ = behaviour;
      GoOut();
      return;
    }
    const std::optional<WalkerSegment> bout = PlanRouteBout(behaviour, robot_, t_, lead_, &rng_);
    std::optional<std::vector<WalkerSegment>> out;
    if (bout && ClearOfRobotAndWalkers(*bout, plan_, robot_, others_, false)) out = ExitAfter(*bout);
    if (!out) {  // no room for it here and now: out through the door
      GoOut();
      return;
    }
    plan_.segments.push_back(*bout);
    last_bout_ = bout->behaviour;
    way_out_ = out;
    t_ = bout->end_s;
    lead_ = bout->u_start + bout->rate * (bout->end_s - bout->start_s) - bout->end_s;
    if (behaviour == "away") GoOut();
  }

  // Out of the room (or at the start of the run, already in it): the next bout, walked into
  // from a door; taken only when a way out from its end exists too.
  void NextBoutFromOutside() {
    const bool at_start = plan_.segments.empty() && t_ == 0;
    if (!at_start) lead_ = rng_.Uniform(5.0, 10.0);
    const double out_s = at_start ? 0.0 : t_ + kMinOutS + rng_.Uniform(0.0, 2.0);  // walks in from then
    bool placed = PlaceDrawnBout(at_start, out_s);
    if (!placed && !at_start) placed = PlaceAtNextDoor();
    if (!placed && at_start && ++start_attempts_ < 6) {
      lead_ = rng_.Uniform(4.0, 16.0);  // another place on the route to start the run at
      return;
    }
    if (!placed) PushGone(t_ + 1.0);  // no bout fits now: a little later
  }

  // Draws behaviours (without replacement) until one's bout and the walk into it fit.
  bool PlaceDrawnBout(bool at_start, double out_s) {
    std::array<double, kWalkerBehaviourCount> w = Possible(lead_);
    while (std::any_of(w.begin(), w.end(), [](double x) { return x > 0; })) {
      size_t chosen = DrawBehaviour(w, &rng_);
      if (!wanted_.empty()) {
        chosen = static_cast<size_t>(std::find(kWalkerBehaviours.begin(), kWalkerBehaviours.end(), wanted_) -
                                     kWalkerBehaviours.begin());
        wanted_.clear();
      }
      const std::string behaviour = kWalkerBehaviours[chosen];
      w[chosen] = 0;
      const bool moves_by_robot = behaviour == "cross" || behaviour == "overtake";
      // The bout starts when the walk in ends: planned at a guess of that time, then again at the
      // time the walk in takes from out_s (twice: the bout's start moves with the robot).
      double bout_s = at_start ? 0.0 : out_s + 3.0;
      std::optional<WalkerSegment> bout, in;
      for (int attempt = 0; attempt < 3; ++attempt) {
        bout = behaviour == "cross"      ? PlanCross(space_, robot_, bout_s, lead_, &rng_)
               : behaviour == "overtake" ? PlanOvertake(space_, robot_, bout_s, &rng_)
                                         : PlanRouteBout(behaviour, robot_, bout_s, lead_, &rng_);
        if (!bout || !ClearOfRobotAndWalkers(*bout, plan_, robot_, others_, moves_by_robot)) {
          bout.reset();
          break;
        }
        if (at_start) break;
        in = PlanDoorWalk(true, StartOf(*bout, plan_, robot_), bout_s, -1e30, door_speed_m_s_, doors_, plan_, robot_,
                          others_);
        if (in && in->start_s >= t_ + kMinOutS && in->start_s <= out_s + 1.0) break;
        bout_s = out_s + (in ? in->end_s - in->start_s : 2.0 + 2.0 * attempt);
        in.reset();
      }
      if (!bout || (!at_start && !in)) continue;
      if (Place(in, *bout)) return true;
    }
    return false;
  }

  // Onto the route at the next door the robot has yet to pass, 4-10 s of route ahead of it: the
  // walk in is short and the robot is behind it.
  bool PlaceAtNextDoor() {
    for (const double pass_u : door_passes_) {
      if (pass_u < t_ + kMinOutS + kMinAheadLeadS + 0.5) continue;
      lead_ = std::min(rng_.Uniform(kMinAheadLeadS, 10.0), pass_u - t_ - kMinOutS - 0.5);
      const double bout_s = pass_u - lead_;
      const std::optional<WalkerSegment> bout = PlanRouteBout("ahead", robot_, bout_s, lead_, &rng_);
      if (bout && ClearOfRobotAndWalkers(*bout, plan_, robot_, others_, false)) {
        const std::optional<WalkerSegment> in = PlanDoorWalk(true, StartOf(*bout, plan_, robot_), bout_s, t_ + kMinOutS,
                                                             door_speed_m_s_, doors_, plan_, robot_, others_);
        if (in) return Place(in, *bout);
      }
      return false;
    }
    return false;
  }

  const std::map<std::string, double>& weights_;
  const double duration_s_;
  const FreeSpace& space_;
  const RobotTrack& robot_;
  const std::vector<WalkerPlan>& others_;
  const std::vector<Doorway>& doors_;
  Rng rng_;
  WalkerPlan plan_;
  double door_speed_m_s_ = 0;
  std::vector<double> door_passes_;
  double t_ = 0, lead_ = 0;
  std::string last_bout_;  // the behaviour of the bout before, in this stay in the room
  bool inside_ = false;
  int start_attempts_ = 0;
  // From where its last bout ends out through a door (checked; empty: the run ends first).
  std::optional<std::vector<WalkerSegment>> way_out_;
  std::string wanted_;  // a bout drawn in the room that starts elsewhere: tried first
};

}  // namespace

WalkerPlan PlanWalker(const std::map<std::string, double>& weights, uint64_t seed, int walker, double duration_s,
                      std::shared_ptr<const FreeSpace> space, const RobotTrack& robot,
                      const std::vector<WalkerPlan>& others, const std::vector<Doorway>& doors, double lateral_m) {
  return WalkerPlanner(weights, seed, walker, duration_s, std::move(space), robot, others, doors, lateral_m).Plan();
}

}  // namespace hoilcd
