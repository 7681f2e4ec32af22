#include "room_objects.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "room_plan.h"

namespace hoilcd {
namespace {

// Sizes of the shipped room objects (assets/README.md), m: along the wall, out of it, height.
constexpr double kWhiteboardHalfM = 0.90, kWhiteboardBottomM = 0.90, kWhiteboardHeightM = 1.20;
constexpr double kDoorFrameHalfM = 0.52, kDoorFrameHeightM = 2.12;
constexpr double kPlateHalfM = 0.043, kPlateHeightM = 0.086;  // light_switch; wall_socket is two plates
constexpr double kAcHalfM = 0.40, kAcHeightM = 0.28, kAcBelowCeilingM = 0.15;
constexpr double kShelfHalfM = 0.45, kShelfHeightM = 0.50, kShelfBottomM = 1.45;
constexpr double kCabinetHalfM = 0.40, kCabinetDepthM = 0.42, kCabinetHeightM = 1.34;
constexpr double kBagLengthM = 0.32, kBagWidthM = 0.14;
constexpr double kChargerHalfM = 0.055, kChargerHalfWidthM = 0.025;
// Heights of the fittings' bottom edges: a switch centred 1.05 m up, a socket 0.30 m up (DIN
// 18015-3's installation zones, the usual European practice).
constexpr double kSwitchBottomM = 1.05 - kPlateHeightM / 2, kSocketBottomM = 0.30;
// chair.gltf: the seat is 0.42 m wide; the backrest's top edge is 0.253 m behind the seat centre,
// 0.86 m up. Table tops are at 0.74 m.
constexpr double kChairHalfWidthM = 0.21, kBackrestBackM = 0.253, kBackrestTopM = 0.86, kTableTopM = 0.74;
}  // namespace

bool HasFrontWall(const std::string& family) {
  return family == "classroom" || family == "seminar_u" || family == "meeting_row";
}

std::vector<Eigen::Vector2d> RoomDoors(const Eigen::Vector2d& size_m, bool whiteboard) {
  std::vector<Eigen::Vector2d> doors = {{size_m.x(), 0.5 * size_m.y()}};
  const double corner_y = kCornerM + kDoorFrameHalfM;
  if (!whiteboard) {
    doors.insert(doors.begin(), Eigen::Vector2d(0, 0.5 * size_m.y()));
  } else if (0.5 * size_m.y() - corner_y - kDoorFrameHalfM >= kWhiteboardHalfM + kGapM) {
    doors.insert(doors.begin(), Eigen::Vector2d(0, corner_y));  // by the south corner of the front wall
  }
  return doors;
}

std::vector<PlacedObject> RoomFittings(const Eigen::Vector3d& size_m, const nlohmann::ordered_json& windows,
                                       bool whiteboard, const RoomContext& context) {
  const RoomObjectOptions& o = context.options.objects;
  WallPlan plan(size_m);
  std::vector<PlacedObject> out;
  for (const auto& w : windows) {
    const std::string wall = w["wall"];
    const Wall at = wall == "south" ? kSouth : wall == "north" ? kNorth : wall == "west" ? kWest : kEast;
    const double center = w["center_m"], width = w["width_m"], bottom = w["bottom_m"], height = w["height_m"];
    plan.Take(at, center - 0.5 * width, center + 0.5 * width, bottom, bottom + height);
  }
  if (whiteboard)
    Mount(&plan, &out, "whiteboard", kWest, 0.5 * size_m.y(), kWhiteboardHalfM, kWhiteboardBottomM, kWhiteboardHeightM);
  // Each door in its frame, its switch on the handle's side (the frame's -y), else on the other.
  for (const Eigen::Vector2d& d : context.doors) {
    const Wall wall = d.x() < 0.5 * size_m.x() ? kWest : kEast;
    plan.Take(wall, d.y() - kDoorFrameHalfM, d.y() + kDoorFrameHalfM, 0, kDoorFrameHeightM);
    out.push_back(plan.On("door_frame", wall, d.y(), 0));
    const double handle_side = wall == kWest ? -1 : 1;  // the frame's -y along the wall
    const double offset = kDoorFrameHalfM + kGapM + kPlateHalfM + 0.001;
    if (!Mount(&plan, &out, "light_switch", wall, d.y() + handle_side * offset, kPlateHalfM, kSwitchBottomM,
               kPlateHeightM)) {
      Mount(&plan, &out, "light_switch", wall, d.y() - handle_side * offset, kPlateHalfM, kSwitchBottomM,
            kPlateHeightM);
    }
  }
  // The air conditioner high on the south or the east wall, its top kAcBelowCeilingM down.
  if (context.rng->Uniform() < o.ac_unit_probability) {
    const double bottom = size_m.z() - kAcBelowCeilingM - kAcHeightM;
    const Wall first = context.rng->Uniform() < 0.5 ? kSouth : kEast;
    bool placed = false;
    for (int attempt = 0; attempt < 8 && !placed; ++attempt) {
      const Wall wall = attempt % 2 == 0 ? first : (first == kSouth ? kEast : kSouth);
      const double along = context.rng->Uniform(kCornerM + kAcHalfM, plan.Length(wall) - kCornerM - kAcHalfM);
      placed = Mount(&plan, &out, "ac_unit", wall, along, kAcHalfM, bottom, kAcHeightM);
    }
  }
  // A socket on the nearer long wall for some of the tables and desks.
  for (const Piece& piece : context.layout.pieces) {
    if (context.rng->Uniform() >= o.socket_probability || piece.seats == "none" || piece.seats == "sofa") continue;
    const Wall wall = piece.center_m.y() < 0.5 * size_m.y() ? kSouth : kNorth;
    Mount(&plan, &out, "wall_socket", wall, piece.center_m.x(), 2 * kPlateHalfM, kSocketBottomM, kPlateHeightM);
  }
  // Shelves and cabinets on free stretches of the south, north and east walls.
  const Wall shelf_walls[] = {kSouth, kNorth, kEast};
  const int shelves = static_cast<int>(context.rng->UniformInt(static_cast<uint32_t>(o.shelf_count_max + 1)));
  for (int k = 0, tries = 0; k < shelves && tries < 12 * shelves; ++tries) {
    const Wall wall = shelf_walls[context.rng->UniformInt(3)];
    const double along = context.rng->Uniform(kCornerM + kShelfHalfM, plan.Length(wall) - kCornerM - kShelfHalfM);
    k += Mount(&plan, &out, "shelf", wall, along, kShelfHalfM, kShelfBottomM, kShelfHeightM);
  }
  FloorCheck floor =
      MakeFloorCheck(size_m.head<2>(), context.world, context.doors, context.route, context.options.route_clearance_m);
  const int cabinets = static_cast<int>(context.rng->UniformInt(static_cast<uint32_t>(o.cabinet_count_max + 1)));
  for (int k = 0, tries = 0; k < cabinets && tries < 12 * cabinets; ++tries) {
    const Wall wall = shelf_walls[context.rng->UniformInt(3)];
    const double along = context.rng->Uniform(kCornerM + kCabinetHalfM, plan.Length(wall) - kCornerM - kCabinetHalfM);
    if (!plan.Free(wall, along - kCabinetHalfM, along + kCabinetHalfM, 0, kCabinetHeightM)) continue;
    // The cabinet stands 1 cm off the wall: its origin is under its centre.
    PlacedObject cabinet = plan.On("cabinet", wall, along, 0);
    const double yaw = cabinet.yaw_deg * M_PI / 180;
    cabinet.position_m.head<2>() += Rotate(yaw, Eigen::Vector2d(0.5 * kCabinetDepthM + 0.01, 0));
    const Obstacle2D footprint = Obstacle2D::Rectangle("cabinet", cabinet.position_m.head<2>(),
                                                       Eigen::Vector2d(kCabinetDepthM, 2 * kCabinetHalfM), yaw);
    if (!floor.Clear(footprint)) continue;
    plan.Take(wall, along - kCabinetHalfM, along + kCabinetHalfM, 0, kCabinetHeightM);
    floor.footprints.push_back(footprint);
    out.push_back(cabinet);
    ++k;
  }
  // Ceiling lights in a grid of cells about ceiling_light_spacing_m across, one in each cell's middle.
  const int nx = std::max(1, static_cast<int>(std::lround(size_m.x() / o.ceiling_light_spacing_m)));
  const int ny = std::max(1, static_cast<int>(std::lround(size_m.y() / o.ceiling_light_spacing_m)));
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      out.push_back(
          {"ceiling_light", Eigen::Vector3d((i + 0.5) * size_m.x() / nx, (j + 0.5) * size_m.y() / ny, size_m.z()), 0});
  return out;
}

std::vector<PlacedObject> PeoplesThings(const std::vector<std::pair<int, int>>& occupied, const Eigen::Vector2d& size_m,
                                        const RoomContext& context) {
  const RoomObjectOptions& o = context.options.objects;
  FloorCheck floor =
      MakeFloorCheck(size_m, context.world, context.doors, context.route, context.options.route_clearance_m);
  std::vector<PlacedObject> out;
  const std::vector<Crowd::SeatPlace> seats = context.world.seat_places();
  for (const auto& [table, seat] : occupied) {
    const auto place = std::find_if(seats.begin(), seats.end(), [&, t = table, k = seat](const Crowd::SeatPlace& s) {
      return s.table == t && s.seat == k;
    });
    const double bag = context.rng->Uniform(), coat = context.rng->Uniform(), charger = context.rng->Uniform(),
                 side = context.rng->Uniform() < 0.5 ? 1.0 : -1.0;
    if (place == seats.end() || !place->chair) continue;  // a sofa's places hold nothing of this
    const Eigen::Vector2d at = place->world_from_seat.topRightCorner<2, 1>().cast<double>();
    const Eigen::Vector2d facing = place->world_from_seat.block<2, 1>(0, 0).cast<double>().normalized();
    const double yaw = std::atan2(facing.y(), facing.x());
    const double yaw_deg = yaw * 180 / M_PI;
    if (bag < o.bag_probability) {
      // On the floor beside the chair, its long side along the seat's facing; the other side if
      // this one is taken.
      for (double s : {side, -side}) {
        const Eigen::Vector2d center =
            at + Rotate(yaw, Eigen::Vector2d(-0.03, s * (kChairHalfWidthM + 0.02 + 0.5 * kBagWidthM)));
        const Obstacle2D footprint =
            Obstacle2D::Rectangle("bag", center, Eigen::Vector2d(kBagLengthM, kBagWidthM), yaw);
        if (!floor.Clear(footprint)) continue;
        floor.footprints.push_back(footprint);
        out.push_back({"bag", Eigen::Vector3d(center.x(), center.y(), 0), yaw_deg});
        break;
      }
    }
    if (coat < o.coat_probability) {
      const Eigen::Vector2d hook = at + Rotate(yaw, Eigen::Vector2d(-kBackrestBackM, 0));
      out.push_back({"coat", Eigen::Vector3d(hook.x(), hook.y(), kBackrestTopM), yaw_deg});
    }
    if (charger < o.charger_probability) {
      // On the table top 6 cm in from its near edge, 0.30 m to the person's left (clear of their
      // cup on the right, their laptop in front and the neighbours' props), along the edge.
      const Piece& piece = context.layout.pieces[static_cast<size_t>(table)];
      if (piece.asset == "low_table" || piece.asset == "sofa" || piece.asset == "lectern") continue;
      const std::string name = "table " + std::to_string(table);
      const auto top = std::find_if(context.world.obstacles().begin(), context.world.obstacles().end(),
                                    [&](const Obstacle2D& f) { return f.name == name; });
      if (top == context.world.obstacles().end()) continue;
      double edge = 0;
      while (edge < 1.0 && DistanceToObstacle(at + edge * facing, *top) > 0) edge += 0.005;
      const Eigen::Vector2d center = at + Rotate(yaw, Eigen::Vector2d(edge + 0.055, 0.30));
      bool on_top = edge < 1.0;
      for (int corner = 0; corner < 4 && on_top; ++corner) {
        const Eigen::Vector2d p = center + Rotate(yaw, Eigen::Vector2d((corner & 1 ? 1 : -1) * kChargerHalfWidthM,
                                                                       (corner & 2 ? 1 : -1) * kChargerHalfM));
        on_top = piece.asset == "round_table" ? (p - piece.center_m).norm() < 0.44 : DistanceToObstacle(p, *top) == 0;
      }
      if (on_top) out.push_back({"charger", Eigen::Vector3d(center.x(), center.y(), kTableTopM), yaw_deg + 90});
    }
  }
  return out;
}

}  // namespace hoilcd
