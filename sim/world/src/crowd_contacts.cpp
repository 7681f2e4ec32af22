// The crowd's contact heat (docs/models/contact_heat.md): turns the plan (who sits where and
// when, in which posture, typing or drinking) into prints on chairs, tables, laptops and cup
// handles, and into cups' pouring and laptops' opening times; and sets them at a time. Every
// value is a closed-form function of the plan and the time (contact_heat.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "hoilcd/sim/world/crowd.h"

namespace hoilcd {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A contact that began when the run began had begun long before: it is in steady state.
double ContactStart(double start_s) { return start_s <= 0 ? -kInf : start_s; }
double ContactEnd(double end_s) { return end_s >= 1e29 ? kInf : end_s; }

// An ellipse on a surface: semi-axes along `along` (horizontal or any unit vector) and across it
// in the surface, `band_m` either side of the surface along its normal.
PrintShape Ellipse(const Eigen::Vector3d& center_m, const Eigen::Vector3d& along, const Eigen::Vector3d& normal,
                   double half_along_m, double half_across_m, double band_m) {
  PrintShape shape;
  shape.center_m = center_m.cast<float>();
  const Eigen::Vector3d u = along.normalized(), n = normal.normalized();
  shape.axes.col(0) = u.cast<float>();
  shape.axes.col(1) = n.cross(u).normalized().cast<float>();
  shape.axes.col(2) = n.cast<float>();
  shape.half_m = Eigen::Vector3d(half_along_m, half_across_m, band_m).cast<float>();
  return shape;
}

// `contacts` with the times in `gaps` taken out (both sorted; contacts not overlapping).
std::vector<ContactInterval> Without(const std::vector<ContactInterval>& contacts,
                                     const std::vector<ContactInterval>& gaps) {
  std::vector<ContactInterval> out;
  for (ContactInterval c : contacts) {
    for (const ContactInterval& g : gaps) {
      if (g.end_s <= c.start_s || g.start_s >= c.end_s) continue;
      if (g.start_s > c.start_s) out.push_back({c.start_s, g.start_s});
      c.start_s = g.end_s;
    }
    if (c.start_s < c.end_s) out.push_back(c);
  }
  return out;
}

// The bounds of an asset's vertices inside `box` (object frame).
Eigen::AlignedBox3f VerticesIn(const Asset& asset, const Eigen::AlignedBox3f& box) {
  Eigen::AlignedBox3f found;
  for (const Eigen::Vector3f& v : asset.mesh.positions_m)
    if (box.contains(v)) found.extend(v);
  return found;
}

bool LeansOnBackrest(const std::string& posture) {
  return posture == "seated_upright" || posture == "seated_leaning_back";
}
bool ArmsOnTable(const std::string& posture) {
  return posture == "seated_leaning" || posture == "seated_arms_on_table";
}

// A drink's temperature at t, poured at poured_s at cup_fill_c and refilled whenever it has
// cooled to cup_refill_c (Newton's law toward the room in between).
double DrinkC(const ContactHeatOptions& o, double room_c, double poured_s, double time_s) {
  double age_s = std::max(0.0, time_s - poured_s);
  if (o.cup_refill_c > room_c + 0.1) {
    const double period_s = o.cup_time_constant_s * std::log((o.cup_fill_c - room_c) / (o.cup_refill_c - room_c));
    age_s = std::fmod(age_s, period_s);
  }
  return room_c + (o.cup_fill_c - room_c) * std::exp(-age_s / o.cup_time_constant_s);
}

// The times a seated person's arm on `side` (0 left, 1 right) is away from the table top:
// drinking with it, or talking with it (a talker gestures with the hand on the roomier side).
std::vector<ContactInterval> ArmAway(const Person& p, int side) {
  std::vector<ContactInterval> away;
  for (const ActivityEpisode& e : p.activities) {
    int moved = e.side;
    if (e.name == "talking" && p.side_room_m[e.side] < p.side_room_m[1 - e.side]) moved = 1 - e.side;
    if ((e.name == "drinking" || e.name == "talking") && moved == side) away.push_back({e.start_s, e.end_s});
  }
  return away;
}

// The print of a forearm and hand resting on the table top (top_m up), from the elbow and wrist
// (seat frame) along the forearm to 8 cm past the wrist, in the table's frame.
PrintShape ForearmPrint(const Person& p, const Eigen::Vector3d& elbow, const Eigen::Vector3d& wrist, float top_m) {
  Eigen::Vector3d a = p.table_from_seat.topLeftCorner<3, 3>() * elbow + p.table_from_seat.topRightCorner<3, 1>();
  Eigen::Vector3d b = p.table_from_seat.topLeftCorner<3, 3>() * wrist + p.table_from_seat.topRightCorner<3, 1>();
  a.z() = b.z() = top_m;
  const Eigen::Vector3d along = (b - a).normalized(), hand_end = b + 0.08 * along;
  return Ellipse(0.5 * (a + hand_end), along, Eigen::Vector3d::UnitZ(), 0.5 * (hand_end - a).norm() + 0.02, 0.045,
                 0.02);
}

// The times a person types long enough to rest their hands, less half a blend at each end.
std::vector<ContactInterval> TypingTimes(const Person& p, double blend_s) {
  std::vector<ContactInterval> typing;
  for (const ActivityEpisode& e : p.activities)
    if (e.name == "typing" && e.end_s - e.start_s > blend_s)
      typing.push_back({e.start_s + 0.5 * blend_s, e.end_s - 0.5 * blend_s});
  return typing;
}

}  // namespace

Crowd::PostureSpans Crowd::PostureSpansOf(const Person& p) const {
  const double posture_blend_s = options_.activity.posture_blend_s;
  const double from_s = ContactStart(p.arrive_s), to_s = ContactEnd(p.leave_s);
  std::vector<std::pair<ContactInterval, std::string>> postures;
  for (size_t k = 0; k < p.postures.size(); ++k) {
    const double start = k == 0 ? from_s : p.postures[k].first + 0.5 * posture_blend_s;
    const double end = k + 1 < p.postures.size() ? p.postures[k + 1].first + 0.5 * posture_blend_s : to_s;
    if (start < end) postures.push_back({{start, end}, p.postures[k].second});
  }
  return postures;
}

BodyPose Crowd::RestPose(const Person& still, const ContactInterval& c) const {
  const double posture_blend_s = options_.activity.posture_blend_s;
  const double at = std::isfinite(c.start_s) ? c.start_s + posture_blend_s : std::max(still.arrive_s, 0.0);
  Eigen::Matrix4d world_from_person, seat_from_cup;
  std::string activity;
  return PoseAt(still, std::isfinite(c.end_s) ? std::min(at, 0.5 * (c.start_s + c.end_s)) : at, &world_from_person,
                &seat_from_cup, &activity);
}

PrintField& Crowd::PrintsOn(int instance) {
  std::unique_ptr<PrintField>& f = prints_[instance];
  if (f == nullptr) f = std::make_unique<PrintField>(HashCombine(seed_, HashString("contact_heat.print"), instance));
  return *f;
}

void Crowd::PlanSeatPrints(const Person& p, const Person& still, const PostureSpans& postures) {
  const auto seat =
      std::find_if(seats_.begin(), seats_.end(), [&](const Seat& s) { return s.table == p.table && s.seat == p.seat; });
  if (seat == seats_.end() || postures.empty()) return;
  const ContactHeatOptions& o = options_.contact_heat;
  const bool chair = seat->chair_instance >= 0;
  const int touched = chair ? seat->chair_instance : table_instance_.at(p.table);
  const Eigen::Matrix4d object_from_seat = chair ? Eigen::Matrix4d::Identity() : p.table_from_seat;
  const Eigen::Matrix3d turn = object_from_seat.topLeftCorner<3, 3>();
  auto at = [&](const Eigen::Vector3d& in_seat) -> Eigen::Vector3d {
    return turn * in_seat + object_from_seat.topRightCorner<3, 1>();
  };
  const Asset& asset = *stage_.MutableInstance(touched).asset;
  const BodyPose pose = RestPose(still, postures.front().first);
  const double s = p.height_scale, seat_top_m = 0.45;
  const ContactResponse seat_response{seat_warmth_c_, o.seat_warm_time_constant_s, options_.heat_print_time_constant_s};
  PrintsOn(touched).Add({Ellipse(at({pose.pelvis_m.x() + 0.05, pose.pelvis_m.y(), seat_top_m}),
                                 turn * Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(), 0.17 * s, 0.15 * s, 0.02),
                         seat_response,
                         {{ContactStart(p.arrive_s), ContactEnd(p.leave_s)}}});
  // The backrest's front face: the foremost vertices behind the place, at back height (the
  // meshes are boxes: their vertices are corners, so the search spans the piece's width).
  const float place_x = static_cast<float>(at(Eigen::Vector3d::Zero()).x());
  const Eigen::AlignedBox3f backrest =
      VerticesIn(asset, Eigen::AlignedBox3f(Eigen::Vector3f(-2, -2, 0.55f), Eigen::Vector3f(place_x, 2, 0.8f)));
  std::vector<ContactInterval> leaning;
  for (const auto& [c, name] : postures)
    if (LeansOnBackrest(name)) leaning.push_back(c);
  if (backrest.isEmpty() || leaning.empty()) return;
  // Chairs and sofas face their frame's +x: the face is at the box's largest x.
  Eigen::Vector3d centre = at({0, pose.pelvis_m.y(), 0.66});
  centre.x() = backrest.max().x();
  const ContactResponse back_response{o.back_excess_k, o.seat_warm_time_constant_s,
                                      options_.heat_print_time_constant_s};
  PrintsOn(touched).Add(
      {Ellipse(centre, turn * Eigen::Vector3d::UnitY(), turn * Eigen::Vector3d::UnitX(), 0.15 * s, 0.12 * s, 0.05),
       back_response, leaning});
}

void Crowd::PlanTablePrints(const Person& p, const Person& still, const PostureSpans& postures) {
  const ContactHeatOptions& o = options_.contact_heat;
  const ContactResponse table_response{o.table_excess_k, o.table_warm_time_constant_s, o.table_cool_time_constant_s};
  const float top_m = table_bounds_m_.at(p.table).max().z();
  for (const auto& [c, name] : postures) {
    if (!ArmsOnTable(name)) continue;
    const auto keypoints = skeleton_->Keypoints(skeleton_->PartTransforms(RestPose(still, c)));
    for (int side = 0; side < 2; ++side) {
      const Eigen::Vector3d elbow = keypoints[kLeftElbow + side], wrist = keypoints[kLeftWrist + side];
      if (!ForearmOnTable(p, wrist)) continue;  // as SetTime's table contacts
      PrintsOn(table_instance_.at(p.table))
          .Add({ForearmPrint(p, elbow, wrist, top_m), table_response, Without({c}, ArmAway(p, side))});
    }
  }
}

void Crowd::PlanKeyboardPrints(const Person& p) {
  const std::vector<ContactInterval> typing = TypingTimes(p, options_.activity.blend_s);
  if (typing.empty()) return;
  const ContactHeatOptions& o = options_.contact_heat;
  const ContactResponse keyboard_response{o.keyboard_excess_k, o.keyboard_warm_time_constant_s,
                                          o.keyboard_cool_time_constant_s};
  for (const double y : {-0.09, 0.09}) {
    PrintsOn(p.laptop).Add(
        {Ellipse({0.06, y, 0.018}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(), 0.06, 0.04, 0.012),
         keyboard_response, typing});
  }
}

void Crowd::PlanCupHeat(const Person& p, double first_s, double drink_age_s) {
  const ContactHeatOptions& o = options_.contact_heat;
  PropHeat cup{p.cup, true, first_s <= 0 ? -drink_age_s : first_s, kInf, stage_.MutableInstance(p.cup).materials};
  prop_heat_.push_back(cup);
  // The hand on the handle while drinking (held from 10 % to 92 % of the episode).
  const Asset& asset = *stage_.MutableInstance(p.cup).asset;
  const float body_radius = asset.bounds_m.max().y();
  const Eigen::AlignedBox3f handle =
      VerticesIn(asset, Eigen::AlignedBox3f(Eigen::Vector3f(-1, -1, -1), Eigen::Vector3f(1, -body_radius - 0.002f, 1)));
  if (handle.isEmpty()) return;
  float hottest_c = -1e9f;
  for (const InstanceMaterial& m : cup.steady) hottest_c = std::max(hottest_c, m.temperature_c);
  for (const ActivityEpisode& e : p.activities) {
    if (e.name != "drinking") continue;
    const double d = e.end_s - e.start_s;
    // The handle's surface, as the cup's ceramic at that time, is drawn toward the skin.
    const double drink_c = DrinkC(o, room_c_, cup.from_s, e.start_s);
    const double ceramic_c =
        room_c_ + (drink_c - room_c_) * (cup.steady.front().temperature_c - room_c_) / (hottest_c - room_c_);
    const ContactResponse response{o.handle_contact_fraction * (options_.skin_temperature_c - ceramic_c),
                                   o.handle_warm_time_constant_s, o.handle_cool_time_constant_s};
    PrintShape shape;
    shape.center_m = handle.center();
    shape.half_m = 0.5f * handle.sizes() + Eigen::Vector3f::Constant(0.006f);
    PrintsOn(p.cup).Add({shape, response, {{e.start_s + 0.1 * d, e.start_s + 0.92 * d}}});
  }
}

void Crowd::PlanProps(const Person& p) {
  double first_s = kInf, last_s = -kInf;
  for (const Person& q : people_) {
    if (q.person_id != p.person_id || !q.seated) continue;
    first_s = std::min(first_s, q.arrive_s);
    last_s = std::max(last_s, ContactEnd(q.leave_s));
  }
  const ContactHeatOptions& o = options_.contact_heat;
  Rng rng = KeyedRng(seed_, "contact_heat.props", p.person_id);
  const double drink_age_s = rng.Uniform(
      0, o.cup_time_constant_s * std::log((o.cup_fill_c - room_c_) / std::max(0.1, o.cup_refill_c - room_c_)));
  const double laptop_age_s = rng.Uniform(0, o.laptop_on_before_max_s);
  if (p.cup >= 0) PlanCupHeat(p, first_s, drink_age_s);
  if (p.laptop >= 0) {
    prop_heat_.push_back(
        {p.laptop, false, first_s <= 0 ? -laptop_age_s : first_s, last_s, stage_.MutableInstance(p.laptop).materials});
  }
}

void Crowd::PlanContactHeat() {
  prints_.clear();
  prop_heat_.clear();
  if (!options_.contact_heat.enabled) return;
  for (const Person& p : people_) {
    if (!p.seated) continue;
    const PostureSpans postures = PostureSpansOf(p);
    // The body as it rests in a posture (no activity), a moment after it was taken.
    Person still = p;
    still.activities.clear();
    PlanSeatPrints(p, still, postures);
    if (p.at_table_top) PlanTablePrints(p, still, postures);
    if (p.laptop >= 0) PlanKeyboardPrints(p);
  }
  // Cups and laptops: each person's are one cup and one laptop, carried to a new seat.
  for (const Person& p : people_)
    if (p.seated) PlanProps(p);
  // The prints show on the touched instances' non-metal materials.
  for (auto& [instance, f] : prints_) {
    for (InstanceMaterial& m : stage_.MutableInstance(instance).materials)
      if (!m.specular) m.field = f.get();
  }
}

void Crowd::UpdateContactHeat(double time_s) {
  for (auto& [instance, f] : prints_) f->SetTime(time_s);
  const ContactHeatOptions& o = options_.contact_heat;
  for (const PropHeat& prop : prop_heat_) {
    // How far from the room toward the asset's temperatures: a cup by its drink (the asset's
    // hottest material is its drink), a laptop by its warm-up and cool-down.
    double fraction = 0;
    if (prop.cup) {
      float hottest_c = -1e9f;
      for (const InstanceMaterial& m : prop.steady) hottest_c = std::max(hottest_c, m.temperature_c);
      fraction = (DrinkC(o, room_c_, prop.from_s, time_s) - room_c_) / (hottest_c - room_c_);
    } else {
      fraction = ContactExcessK({{prop.from_s, prop.to_s}},
                                {1.0, o.laptop_warm_time_constant_s, o.laptop_cool_time_constant_s}, time_s);
    }
    std::vector<InstanceMaterial>& materials = stage_.MutableInstance(prop.instance).materials;
    for (size_t m = 0; m < materials.size(); ++m) {
      materials[m].temperature_c = static_cast<float>(room_c_ + fraction * (prop.steady[m].temperature_c - room_c_));
      materials[m].temperature_top_c = materials[m].temperature_c;
      stage_.Finish(&materials[m]);
    }
  }
}

}  // namespace hoilcd
