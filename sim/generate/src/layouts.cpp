#include "layouts.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

// Hand-written: the families' rules are a few lines each; no Debian library lays out rooms by rule.

// Tables in a row: the paper's stand 0.92 m apart and their chairs reach under the next table;
// these stand 1.0 m apart, so a chair (shifted and turned, up to 0.08 m past its table's end)
// stays clear of its neighbour.
constexpr double kPitchM = 1.0;
// A chair reaches this far beyond the table edge it stands at (seat set back 0.15 m, backrest
// 0.26 m behind the seat centre): furniture.seat_setback_m's default and chair.gltf.
constexpr double kChairReachM = 0.42;
// Standing people are circles of this radius to the robot and walkers (Crowd::AddStandingPeople).
constexpr double kStandingRadiusM = 0.3;
// Half sizes of the shipped pieces (assets/README.md), m.
constexpr double kTableHalfLengthM = 0.45, kTableHalfDepthM = 0.375;  // table.gltf
constexpr double kDeskHalfLengthM = 0.60, kDeskHalfDepthM = 0.30;     // desk.gltf
constexpr double kRoundTableRadiusM = 0.45;
constexpr double kSofaFrontM = 0.30, kSofaBackM = 0.45;  // sofa.gltf: seat front and back, from its origin
constexpr double kLowTableHalfDepthM = 0.25;
constexpr double kPartitionHalfLengthM = 0.80;

// The room and the band the route leaves free along its walls.
struct Frame {
  double length_m, width_m;
  double wall_m, clearance_m;
  double inset_m() const { return wall_m + clearance_m; }  // furniture starts this far from a wall
};

// `count` positions `pitch_m` apart centred on `center_m`.
std::vector<double> Centred(int count, double pitch_m, double center_m) {
  std::vector<double> out;
  for (int i = 0; i < count; ++i) out.push_back(center_m + (i - 0.5 * (count - 1)) * pitch_m);
  return out;
}

// How many pieces `extent_m` long fit at `pitch_m` in `space_m`.
int FitCount(double space_m, double extent_m, double pitch_m) {
  return space_m < extent_m ? 0 : 1 + static_cast<int>(std::floor((space_m - extent_m) / pitch_m + 1e-9));
}

// A monitor on a desk for the seat `along_m` from its centre, on the far half of the top, facing
// the person who sits there (desks seat people on their -y side).
PlacedObject MonitorOn(const Piece& desk, double along_m) {
  const double yaw = desk.yaw_deg * M_PI / 180;
  const Eigen::Vector2d local(along_m, 0.12);
  const Eigen::Vector2d at = desk.center_m + Eigen::Vector2d(std::cos(yaw) * local.x() - std::sin(yaw) * local.y(),
                                                             std::sin(yaw) * local.x() + std::cos(yaw) * local.y());
  return {"monitor", Eigen::Vector3d(at.x(), at.y(), 0.74), desk.yaw_deg - 90};
}

Piece Desk(double x, double y, double yaw_deg, int seats) { return {"desk", {x, y}, yaw_deg, "one_side", seats}; }

// The paper's room grown and shrunk: tables in a row along x, people on both long sides.
Layout MeetingRow(const Frame& f, Rng* rng, Layout layout) {
  const int most = std::max(1, FitCount(f.length_m - 2 * f.inset_m() - 0.16, 2 * kTableHalfLengthM, kPitchM));
  const int fewest = (2 * most + 2) / 3;  // at least two thirds of the row that fits
  const int count = fewest + static_cast<int>(rng->UniformInt(static_cast<uint32_t>(most - fewest + 1)));
  for (double x : Centred(count, kPitchM, 0.5 * f.length_m))
    layout.pieces.push_back({"", {x, 0.5 * f.width_m}, 0, "both_sides", 0});
  layout.cup_fraction = 0.5;
  layout.laptop_fraction = 0.3;
  return layout;
}

// A lecturer standing behind a lectern by the west (front) wall, rows of two-person desks facing them.
Layout Classroom(const Frame& f, Rng* rng, Layout layout) {
  const double x_lecturer = f.inset_m() + kStandingRadiusM + 0.05;
  const double y_lecturer = 0.5 * f.width_m + rng->Uniform(-0.15, 0.15) * (f.width_m - 2 * f.inset_m());
  layout.standing.push_back({{x_lecturer, y_lecturer}, 0});
  const double x_lectern = x_lecturer + 0.6;
  layout.objects.push_back({"lectern", Eigen::Vector3d(x_lectern, y_lecturer, 0), 180});
  // Desks turned 90°: chairs on their +x side, everyone facing -x (the front).
  const double row_pitch = rng->Uniform(1.5, 1.7), column_pitch = rng->Uniform(1.3, 1.6);
  const double first_x = x_lectern + 0.25 + rng->Uniform(0.9, 1.3) + kDeskHalfDepthM;
  const double usable_y = f.width_m - 2 * f.inset_m();
  const int columns = FitCount(usable_y, 2 * kDeskHalfLengthM, column_pitch);
  for (double x = first_x; x + kDeskHalfDepthM + kChairReachM <= f.length_m - f.inset_m(); x += row_pitch) {
    for (double y : Centred(columns, column_pitch, 0.5 * f.width_m)) layout.pieces.push_back(Desk(x, y, 90, 2));
  }
  layout.cup_fraction = 0.2;
  layout.laptop_fraction = 0.35;
  return layout;
}

// Round tables (four to six around) and square ones (four) on a loose grid, a few people standing.
Layout Cafeteria(const Frame& f, Rng* rng, Layout layout) {
  const double space_x = f.length_m - 2 * f.inset_m(), space_y = f.width_m - 2 * f.inset_m();
  const double cell = std::min({rng->Uniform(2.2, 2.4), space_x, space_y});
  const int nx = std::max(1, static_cast<int>(std::floor(space_x / cell))),
            ny = std::max(1, static_cast<int>(std::floor(space_y / cell)));
  const double group_reach = kRoundTableRadiusM + kChairReachM;
  const double jitter = std::max(0.0, 0.5 * cell - group_reach - 0.02);
  for (double cx : Centred(nx, cell, 0.5 * f.length_m)) {
    for (double cy : Centred(ny, cell, 0.5 * f.width_m)) {
      const Eigen::Vector2d at(cx + rng->Uniform(-jitter, jitter), cy + rng->Uniform(-jitter, jitter));
      const double kind = rng->Uniform();
      if (kind < 0.12 && cell >= 2 * (0.45 + kStandingRadiusM)) {  // two people standing, talking
        const double a = rng->Uniform(0, M_PI);
        const Eigen::Vector2d d(std::cos(a), std::sin(a));
        layout.standing.push_back({at - 0.45 * d, a * 180 / M_PI});
        layout.standing.push_back({at + 0.45 * d, a * 180 / M_PI + 180});
      } else if (kind < 0.62) {
        const int seats = 4 + static_cast<int>(rng->UniformInt(3));
        layout.pieces.push_back({"round_table", at, rng->Uniform(0, 360.0 / seats), "around", seats});
      } else {
        layout.pieces.push_back({"square_table", at, rng->Uniform(-15, 15), "around", 4});
      }
    }
  }
  layout.cup_fraction = 0.75;
  layout.laptop_fraction = 0.1;
  return layout;
}

// Desks against the long walls (people facing the wall), islands of desks back to back with a
// partition between them in the middle, a monitor at every desk place. The route runs in the
// aisle between the wall desks and the islands.
Layout OpenOffice(const Frame& f, Rng* rng, Layout layout) {
  const double wall_desk_y = kDeskHalfDepthM + 0.02;
  const double chairs_end_y = wall_desk_y + kDeskHalfDepthM + kChairReachM;
  const double y0 = chairs_end_y + f.clearance_m, y1 = f.width_m - y0;
  layout.route_box_m = Eigen::Vector4d(f.wall_m, y0, f.length_m - f.wall_m, y1);
  auto add_desk = [&](double x, double y, double yaw) {
    const Piece desk = Desk(x, y, yaw, 2);
    layout.pieces.push_back(desk);
    for (double along : {-0.3, 0.3}) layout.objects.push_back(MonitorOn(desk, along));
  };
  const double space_x = f.length_m - 2 * f.inset_m();
  const double wall_pitch = rng->Uniform(1.25, 1.5);
  for (double x : Centred(FitCount(space_x, 2 * kDeskHalfLengthM, wall_pitch), wall_pitch, 0.5 * f.length_m)) {
    if (rng->Uniform() >= 0.15) add_desk(x, wall_desk_y, 180);            // south wall, facing it
    if (rng->Uniform() >= 0.15) add_desk(x, f.width_m - wall_desk_y, 0);  // north wall
  }
  // Islands: two rows of desks 0.44 m apart, far edges to the partition.
  const double half_island = 0.22 + 2 * kDeskHalfDepthM + kChairReachM;
  const double island_space = (y1 - y0) - 2 * f.clearance_m;
  const int islands = std::max(0, FitCount(island_space, 2 * half_island, 2 * half_island + f.clearance_m));
  const double island_pitch = rng->Uniform(1.65, 1.85);
  const int per_island = FitCount(space_x, 2 * kPartitionHalfLengthM, island_pitch);
  for (double yc : Centred(islands, 2 * half_island + f.clearance_m, 0.5 * f.width_m)) {
    for (double x : Centred(per_island, island_pitch, 0.5 * f.length_m)) {
      add_desk(x, yc - 0.22 - kDeskHalfDepthM, 0);
      add_desk(x, yc + 0.22 + kDeskHalfDepthM, 180);
      layout.objects.push_back({"partition", Eigen::Vector3d(x, yc, 0), 90});
    }
  }
  layout.cup_fraction = 0.4;
  layout.laptop_fraction = 0.15;
  return layout;
}

// Tables in a U open to the west, people on the outside facing in, sometimes a speaker standing
// in the opening.
Layout SeminarU(const Frame& f, Rng* rng, Layout layout) {
  const double y_south = f.inset_m() + kChairReachM + kTableHalfDepthM, y_north = f.width_m - y_south;
  const double x_east = f.length_m - f.inset_m() - kChairReachM - kTableHalfDepthM;
  // The east column (tables turned 90°, chairs on +x), clear of the rows' table ends.
  const double column_from = y_south + kTableHalfDepthM + 0.02, column_to = y_north - kTableHalfDepthM - 0.02;
  const int column = FitCount(column_to - column_from - 0.16, 2 * kTableHalfLengthM, kPitchM);
  for (double y : Centred(column, kPitchM, 0.5 * f.width_m))
    layout.pieces.push_back({"table", {x_east, y}, 90, "one_side", 2});
  // The rows, from the column westwards, leaving an opening at the front.
  const double row_end = x_east - kTableHalfDepthM - 0.1;
  const int most = FitCount(row_end - (f.inset_m() + 0.8), 2 * kTableHalfLengthM, kPitchM);
  const int count = most - static_cast<int>(rng->UniformInt(static_cast<uint32_t>(std::min(2, std::max(1, most - 1)))));
  for (int i = 0; i < count; ++i) {
    const double x = row_end - kTableHalfLengthM - kPitchM * i;
    layout.pieces.push_back({"table", {x, y_south}, 0, "one_side", 2});
    layout.pieces.push_back({"table", {x, y_north}, 180, "one_side", 2});
  }
  if (rng->Uniform() < 0.6) layout.standing.push_back({{f.inset_m() + kStandingRadiusM + 0.05, 0.5 * f.width_m}, 0});
  layout.cup_fraction = 0.5;
  layout.laptop_fraction = 0.3;
  return layout;
}

// Sofa groups round low tables (one sofa or two facing each other along x, so the robot's long
// legs see their people side on, as the paper's) and people standing in circles, in a row along x.
Layout Lounge(const Frame& f, Rng* rng, Layout layout) {
  const double space_x = f.length_m - 2 * f.inset_m();
  const double sofa_offset = kLowTableHalfDepthM + 0.45 + kSofaFrontM;  // table centre to sofa origin
  const double gap = 0.5;
  struct Group {
    int kind;  // 0: two sofas, 1: one sofa (on the west side), 2: people standing
    double extent_m;
    int people;
  };
  auto extent_of = [&](int kind, int people) {
    if (kind == 0) return 2 * (sofa_offset + kSofaBackM);
    if (kind == 1) return sofa_offset + kSofaBackM + kLowTableHalfDepthM;
    return 2 * ((people == 2 ? 0.45 : 0.55) + kStandingRadiusM);
  };
  // Groups from west to east while they fit; the first two are a sofa group and a standing one.
  std::vector<Group> groups;
  double used = -gap;
  for (int i = 0;; ++i) {
    const double u = rng->Uniform();
    const int kind = i == 0 ? (u < 0.5 ? 0 : 1) : i == 1 ? 2 : (u < 0.35 ? 0 : u < 0.6 ? 1 : 2);
    const int people = kind == 2 ? 2 + static_cast<int>(rng->UniformInt(3)) : 2 + static_cast<int>(rng->UniformInt(2));
    Group g{kind, extent_of(kind, people), people};
    if (used + gap + g.extent_m > space_x && kind == 0) g = Group{1, extent_of(1, people), people};
    if (used + gap + g.extent_m > space_x) break;
    used += gap + g.extent_m;
    groups.push_back(g);
  }
  double x = 0.5 * (f.length_m - used);
  const double y = 0.5 * f.width_m;
  for (const Group& g : groups) {
    if (g.kind == 2) {
      const double radius = g.people == 2 ? 0.45 : 0.55, turn = rng->Uniform(0, 2 * M_PI);
      const double cx = x + 0.5 * g.extent_m;
      for (int k = 0; k < g.people; ++k) {
        const double a = turn + 2 * M_PI * k / g.people;
        layout.standing.push_back({{cx + radius * std::cos(a), y + radius * std::sin(a)}, a * 180 / M_PI + 180});
      }
    } else {
      const double table_x = x + sofa_offset + kSofaBackM;
      layout.pieces.push_back({"low_table", {table_x, y}, 90, "none", 0});
      layout.pieces.push_back({"sofa", {table_x - sofa_offset, y}, 0, "sofa", g.people});
      if (g.kind == 0)
        layout.pieces.push_back(
            {"sofa", {table_x + sofa_offset, y}, 180, "sofa", 2 + static_cast<int>(rng->UniformInt(2))});
    }
    x += g.extent_m + gap;
  }
  layout.cup_fraction = 0;
  layout.laptop_fraction = 0;
  return layout;
}

}  // namespace

Layout DrawLayout(const std::string& family, const Eigen::Vector2d& size_m, const GeneratorOptions& options, Rng* rng) {
  static const std::map<std::string, std::function<Layout(const Frame&, Rng*, Layout)>> kRules = {
      {"meeting_row", MeetingRow}, {"classroom", Classroom}, {"cafeteria", Cafeteria},
      {"open_office", OpenOffice}, {"seminar_u", SeminarU},  {"lounge", Lounge}};
  const Frame frame{size_m.x(), size_m.y(), options.route_wall_m, options.route_clearance_m};
  Layout layout;
  layout.route_box_m =
      Eigen::Vector4d(frame.wall_m, frame.wall_m, size_m.x() - frame.wall_m, size_m.y() - frame.wall_m);
  const auto rule = kRules.find(family);
  HOILCD_CHECK_MSG(rule != kRules.end(), family);
  return rule->second(frame, rng, layout);
}

}  // namespace hoilcd
