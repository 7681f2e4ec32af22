#include "hoilcd/sim/people/crowd_motion.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

using Vec3 = Eigen::Vector3d;
constexpr double kDeg = M_PI / 180.0;
constexpr double kMinDwellS = 1.5;

// Where the mouth is on the head part, rest body frame (in front of and below the head centre).
const Vec3 kMouthRest(0.005 + 0.085, 0, 1.60 - 0.055);

}  // namespace

const std::array<const char*, 5> kActivityNames = {"idle", "head_turn", "talking", "drinking", "typing"};

ActivityOptions::ActivityOptions() { Table().FillDefaults(this); }

const OptionTable<ActivityOptions>& ActivityOptions::Table() {
  using O = ActivityOptions;
  using R = OptionRange;
  using Activities = std::map<std::string, ActivitySpec>;
  static const OptionTable<O> table = [] {
    // One entry per activity, each with its own defaults (crowd.activities.<name>).
    const std::array<ActivitySpec, kActivityNames.size()> defaults = {
        {{2.0, 6.0}, {1.5, 2.5}, {1.5, 8.0}, {0.6, 5.0}, {3.0, 20.0}}};
    OptionTable<Activities> activities;
    for (size_t i = 0; i < kActivityNames.size(); ++i) {
      const std::string name = kActivityNames[i];
      activities.Nest<ActivitySpec>(
          kActivityNames[i], [name](Activities* a) { return &(*a)[name]; },
          OptionTable<ActivitySpec>()
              .Add("weight", &ActivitySpec::weight, defaults[i].weight, "", R::Closed(0, 1000),
                   "relative frequency when a new activity is chosen")
              .Add("dwell_s", &ActivitySpec::dwell_s, defaults[i].dwell_s, "s", R::Closed(kMinDwellS, 600),
                   "mean duration (exponential)"));
    }
    return OptionTable<O>()
        .Nest("activities", &O::activities, activities)
        .Rule("activities",
              [](const O& o) -> std::string {
                for (const auto& [name, spec] : o.activities) {
                  if (std::find(kActivityNames.begin(), kActivityNames.end(), name) == kActivityNames.end()) {
                    return "unknown activity '" + name + "' (expected idle, head_turn, talking, drinking, typing)";
                  }
                }
                return "";
              })
        .Add("activity_blend_s", &O::blend_s, 0.8, "s", R().Above(0).AtMost(5), "ramp into and out of an activity")
        .Add("posture_blend_s", &O::posture_blend_s, 1.5, "s", R().Above(0).AtMost(10),
             "a posture change takes this long")
        .Add("cup_fraction", &O::cup_fraction, 0.5, "", R::Closed(0, 1), "seated people with a cup in front of them")
        .Add("laptop_fraction", &O::laptop_fraction, 0.25, "", R::Closed(0, 1),
             "seated people with a laptop in front of them");
  }();
  return table;
}

std::string ActivityOptions::Check() const { return Table().FirstProblem(*this); }

std::vector<ActivityEpisode> PlanActivities(const ActivityOptions& options, uint64_t seed, int person_id, double from_s,
                                            double to_s, bool has_cup, bool has_laptop) {
  Rng rng = KeyedRng(seed, "crowd.activity", static_cast<uint64_t>(person_id), static_cast<uint64_t>(from_s * 1000));
  std::vector<ActivityEpisode> out;
  std::string previous;
  for (double t = from_s; t < to_s;) {
    // Weights of what this person can do now; never the same activity twice in a row.
    double total = 0;
    std::array<double, kActivityNames.size()> w{};
    for (size_t i = 0; i < kActivityNames.size(); ++i) {
      const std::string name = kActivityNames[i];
      const bool possible = (name != "drinking" || has_cup) && (name != "typing" || has_laptop) && name != previous;
      w[i] = possible ? options.activities.at(name).weight : 0.0;
      total += w[i];
    }
    ActivityEpisode e;
    e.name = "idle";
    double pick = rng.Uniform() * total;
    for (size_t i = 0; i < w.size() && total > 0; ++i) {
      pick -= w[i];
      if (pick < 0 && w[i] > 0) {
        e.name = kActivityNames[i];
        break;
      }
    }
    const double dwell = options.activities.at(e.name).dwell_s;
    e.start_s = t;
    e.end_s = t + std::max(kMinDwellS, -dwell * std::log(1.0 - rng.Uniform()));
    e.toward_robot = rng.Uniform() < 0.4;
    e.neighbour_pick = rng.Uniform();
    e.lone_gaze_yaw_rad = rng.Uniform(-50, 50) * kDeg;
    e.gaze_yaw_rad = e.lone_gaze_yaw_rad;
    e.side = e.name == "drinking" ? 1 : static_cast<int>(rng.UniformInt(2));
    e.phase_rad = rng.Uniform(0, 2 * M_PI);
    previous = e.name;
    t = e.end_s;
    out.push_back(e);
  }
  return out;
}

void GazeAt(const std::vector<double>& neighbour_yaw_rad, ActivityEpisode* episode) {
  if (neighbour_yaw_rad.empty()) {
    episode->gaze_yaw_rad = episode->lone_gaze_yaw_rad;
    return;
  }
  const auto n = neighbour_yaw_rad.size();
  episode->gaze_yaw_rad =
      neighbour_yaw_rad[std::min(n - 1, static_cast<size_t>(episode->neighbour_pick * static_cast<double>(n)))];
}

// 81 lines: one block per activity (head turn, talking, typing, drinking) over a shared envelope.
BodyPose ApplyActivity(const Skeleton& skeleton, const BodyPose& base, const ActivityEpisode& episode, double time_s,
                       double blend_s, const Props& props, double robot_yaw_rad, Eigen::Matrix4d* seat_from_cup) {
  Eigen::Matrix4d cup = Eigen::Matrix4d::Identity();
  cup.topRightCorner<3, 1>() = props.cup_at_m;
  *seat_from_cup = cup;
  const double duration = episode.end_s - episode.start_s;
  const double local = time_s - episode.start_s;
  const double ramp = std::min(blend_s, 0.3 * duration);
  const double envelope = SmoothStep(local / ramp) * SmoothStep((duration - local) / ramp);
  BodyPose p = base;
  const double t = time_s;
  const double phase = episode.phase_rad;
  if (episode.name == "head_turn" || episode.name == "talking") {
    const double yaw = std::remainder(
        episode.toward_robot && episode.name == "head_turn" ? robot_yaw_rad : episode.gaze_yaw_rad, 2 * M_PI);
    const double reach = std::clamp(yaw, -100 * kDeg, 100 * kDeg);  // beyond: look over the shoulder
    p.dof[kNeckTwist] += envelope * 0.85 * reach;
    p.dof[kLumbarTwist] += envelope * 0.12 * reach;
    p.dof[kNeckFlex] += envelope * 3 * kDeg * std::sin(2 * M_PI * 0.3 * t + phase);
  }
  if (episode.name == "talking") {
    // Nods and a gesturing hand (sum of incommensurate sines: no visible repetition).
    p.dof[kHeadNod] += envelope * 5 * kDeg * std::sin(2 * M_PI * 0.8 * t + phase);
    const int s = episode.side;
    const double sign = s == 0 ? 1 : -1;
    const Vec3 wobble(0.04 * std::sin(2 * M_PI * 1.1 * t + phase), 0.03 * std::sin(2 * M_PI * 0.7 * t + 2 * phase),
                      0.05 * std::sin(2 * M_PI * 1.6 * t + 3 * phase));
    ArmPose gesture{Vec3(0.22, sign * 0.22, 0.90) + wobble, Vec3(-0.2, sign, -1), Vec3(1, -sign * 0.2, 0.3),
                    Vec3(-0.3, sign * 0.3, 1)};
    BodyPose g = p;
    g.arm[s] = gesture;
    p = Blend(p, g, envelope);
  }
  if (episode.name == "typing") {
    BodyPose g = p;
    g.dof[kNeckFlex] += 14 * kDeg;
    g.dof[kLumbarFlex] = std::max(g.dof[kLumbarFlex], 6 * kDeg);
    for (int s = 0; s < 2; ++s) {
      const double sign = s == 0 ? 1 : -1;
      const double tap =
          0.004 * std::sin(2 * M_PI * 3.1 * t + phase + s * 1.9) + 0.003 * std::sin(2 * M_PI * 4.7 * t + 2 * phase);
      g.arm[s] = {props.laptop_at_m + Vec3(-0.13, sign * 0.09, 0.045 + tap), Vec3(0, sign, -0.5),
                  Vec3(1, -sign * 0.25, -0.08), Vec3(0, 0, 1)};
    }
    p = Blend(p, g, envelope);
  }
  if (episode.name == "drinking") {
    // Reach for the cup, lift it to the mouth, sip, put it back, let go.
    const int s = episode.side;
    const double sign = s == 0 ? 1 : -1;
    const double u = local / duration;
    const Vec3 grip(-0.03, sign * 0.07, 0.04);  // wrist relative to the cup's base, beside the cup
    const Vec3 mouth = skeleton.HeadPoint(base, kMouthRest);
    const Vec3 cup_at_mouth = mouth + Vec3(0.06, -sign * 0.02, -0.075);
    auto cup_base = [&](double w) -> Vec3 { return props.cup_at_m + SmoothStep(w) * (cup_at_mouth - props.cup_at_m); };
    Vec3 cup_pos = props.cup_at_m;
    double tilt = 0, hold = 0;
    if (u < 0.2) {
      hold = SmoothStep(u / 0.2);
    } else if (u < 0.35) {
      hold = 1, cup_pos = cup_base((u - 0.2) / 0.15);
    } else if (u < 0.65) {
      hold = 1, cup_pos = cup_at_mouth, tilt = 35 * kDeg * std::sin(M_PI * (u - 0.35) / 0.3);
    } else if (u < 0.85) {
      hold = 1, cup_pos = cup_base(1 - (u - 0.65) / 0.2);
    } else {
      hold = SmoothStep((1 - u) / 0.15);
    }
    BodyPose g = p;
    g.arm[s] = {cup_pos + grip, Vec3(-0.3, sign, -1), Vec3(1, 0, 0.1), Vec3(0, sign, 0)};
    g.dof[kNeckFlex] -= tilt * 0.4;
    p = Blend(p, g, hold);
    Eigen::Matrix4d held = Eigen::Matrix4d::Identity();
    held.topLeftCorner<3, 3>() = Eigen::AngleAxisd(-tilt, Vec3::UnitY()).toRotationMatrix();
    held.topRightCorner<3, 1>() = cup_pos;
    *seat_from_cup = held;
  }
  return p;
}

}  // namespace hoilcd
