#include "clutter.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "room_plan.h"

namespace hoilcd {
namespace {

constexpr double kDeg = M_PI / 180;
constexpr double kWallTouchM = 0.06;  // an object this close to a wall takes its stretch of it
constexpr double kCeilingGapM = 0.1;  // ceiling objects keep this far apart
// Heights (m) of the wall objects' bottom edges: pictures, posters and boards centred about eye
// level (1.5 m), a thermostat at 1.5 m (the usual installation height), trunking at dado height,
// the heating pipes' clips 0.10 m up, above the skirting.
constexpr double kPosterBottomM = 1.10, kPictureBottomM = 1.30, kBoardBottomM = 1.00, kClockBottomM = 1.95;
constexpr double kThermostatBottomM = 1.46, kTrunkingBottomM = 1.00, kPipeBottomM = 0.10;
constexpr double kGrilleBelowCeilingM = 0.15;
// The shelf boards' tops of bookcase.gltf and its top, m.
constexpr double kBookcaseShelvesM[] = {0.22, 0.62, 1.02, 1.42};
constexpr double kBookcaseTopM = 1.80, kCabinetTopM = 1.34;

// A person's place at a table: their props (a cup 0.17 m in and 0.21 m to the right, a laptop
// 0.22 m in, a charger 0.30 m to the left) and forearms, in the seat's frame (x towards the
// table from its edge, y to the person's left), m.
constexpr double kPlaceInM = 0.36, kPlaceRightM = 0.27, kPlaceLeftM = 0.36;

// An item drawn `mean` times on average: floor(mean) and one more with the fraction's chance.
int Count(double mean, Rng* rng) {
  const int whole = static_cast<int>(std::floor(mean));
  return whole + (rng->Uniform() < mean - whole ? 1 : 0);
}

Eigen::AlignedBox3d WorldBox(const PlacedObject& o, const Asset& asset) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(o.yaw_deg * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Eigen::AlignedBox3d box;
  for (int c = 0; c < 8; ++c)
    box.extend(o.position_m +
               r * asset.bounds_m.corner(static_cast<Eigen::AlignedBox3f::CornerType>(c)).cast<double>());
  return box;
}

Obstacle2D Footprint(const PlacedObject& o, const Asset& asset) {
  const Eigen::Vector3f lo = asset.bounds_m.min(), hi = asset.bounds_m.max();
  const double yaw = o.yaw_deg * kDeg;
  const Eigen::Vector2d center =
      o.position_m.head<2>() + Rotate(yaw, Eigen::Vector2d(0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y())));
  return Obstacle2D::Rectangle(o.asset, center, Eigen::Vector2d(hi.x() - lo.x(), hi.y() - lo.y()), yaw);
}

// The rectangles taken on the ceiling, seen from below.
class CeilingPlan {
 public:
  bool Free(const Eigen::AlignedBox2d& b) const {
    for (const Eigen::AlignedBox2d& t : taken_)
      if (b.min().x() < t.max().x() + kCeilingGapM && t.min().x() < b.max().x() + kCeilingGapM &&
          b.min().y() < t.max().y() + kCeilingGapM && t.min().y() < b.max().y() + kCeilingGapM) {
        return false;
      }
    return true;
  }
  void Take(const Eigen::AlignedBox2d& b) { taken_.push_back(b); }

 private:
  std::vector<Eigen::AlignedBox2d> taken_;
};

class ClutterPlanner {
 public:
  ClutterPlanner(const Eigen::Vector3d& size_m, const Layout& layout, const World& world, AssetLibrary* assets,
                 const std::vector<Eigen::Vector2d>& doors, const std::vector<Eigen::Vector2d>& route,
                 const GeneratorOptions& options, Rng* rng)
      : size_m_(size_m),
        layout_(layout),
        world_(world),
        assets_(assets),
        walls_(size_m),
        density_(options.objects.clutter_density),
        floor_(MakeFloorCheck(size_m.head<2>(), world, doors, route, options.route_clearance_m)),
        doors_(doors),
        rng_(rng) {}

  // What the room holds already: the windows' and every object's stretches of wall, the floor
  // objects' footprints, the hanging objects' rectangles on the ceiling, the objects on table tops.
  void Hold(const nlohmann::ordered_json& windows, const std::vector<PlacedObject>& placed) {
    for (const auto& w : windows) {
      const std::string wall = w["wall"];
      const Wall at = wall == "south" ? kSouth : wall == "north" ? kNorth : wall == "west" ? kWest : kEast;
      const double center = w["center_m"], width = w["width_m"], bottom = w["bottom_m"], height = w["height_m"];
      walls_.Take(at, center - 0.5 * width, center + 0.5 * width, bottom, bottom + height);
      windows_.push_back({at, center - 0.5 * width, center + 0.5 * width, bottom, bottom + height});
    }
    for (const PlacedObject& o : placed) Note(o);
  }

  void Floor() {
    const int bookcases = Count(0.7 * density_, rng_);
    for (int k = 0, tries = 0; k < bookcases && tries < 12 * bookcases; ++tries) k += Bookcase();
    const int boxes = Count(0.5 * density_, rng_);
    for (int k = 0, tries = 0; k < boxes && tries < 12 * boxes; ++tries) k += AgainstWall("cardboard_box", 0.02);
    for (const Piece& piece : layout_.pieces) {
      if (piece.asset != "desk" || rng_->Uniform() >= std::min(1.0, 0.7 * density_)) continue;
      for (int tries = 0; tries < 4; ++tries) {
        // Beside one end of the desk, its depth along the desk's, on the far (+y) half.
        const double yaw = piece.yaw_deg * kDeg, side = tries % 2 == 0 ? 1 : -1;
        const Eigen::Vector2d at = piece.center_m + Rotate(yaw, Eigen::Vector2d(side * 0.73, tries < 2 ? 0.05 : -0.05));
        if (Place({"pc_tower", Eigen::Vector3d(at.x(), at.y(), 0), piece.yaw_deg + 90})) break;
      }
    }
    const int seats = static_cast<int>(world_.seat_places().size());
    const int bins = Count(density_ * std::max(1.0, seats / 6.0), rng_);
    for (int k = 0, tries = 0; k < bins && tries < 16 * bins; ++tries) {
      if (rng_->Uniform() < 0.5 || layout_.pieces.empty()) {
        k += AgainstWall("bin", 0.02);
      } else {
        const Piece& piece = layout_.pieces[rng_->UniformInt(static_cast<uint32_t>(layout_.pieces.size()))];
        const double yaw = piece.yaw_deg * kDeg;
        const Eigen::Vector2d at = piece.center_m + Rotate(yaw, Eigen::Vector2d(rng_->Uniform() < 0.5 ? 0.78 : -0.78,
                                                                                rng_->Uniform(-0.3, 0.3)));
        k += Place({"bin", Eigen::Vector3d(at.x(), at.y(), 0), 0});
      }
    }
    // Rugs, driven over: under a lounge's low tables, else now and then in the room's middle.
    bool low_tables = false;
    for (const Piece& piece : layout_.pieces) {
      if (piece.asset != "low_table") continue;
      low_tables = true;
      if (rng_->Uniform() < std::min(1.0, 0.7 * density_)) Rug(piece.center_m, piece.yaw_deg);
    }
    if (!low_tables && rng_->Uniform() < std::min(1.0, 0.25 * density_)) {
      const Eigen::Vector4d& box = layout_.route_box_m;
      Rug(Eigen::Vector2d(rng_->Uniform(box[0], box[2]), rng_->Uniform(box[1], box[3])),
          rng_->Uniform() < 0.5 ? 0 : 90);
    }
    // A router on a cabinet or bookcase.
    if (rng_->Uniform() < std::min(1.0, 0.5 * density_) && !tops_.empty()) {
      const PlacedObject& top = tops_[rng_->UniformInt(static_cast<uint32_t>(tops_.size()))];
      const bool cabinet = top.asset == "cabinet";
      const Eigen::Vector2d at =
          top.position_m.head<2>() + Rotate(top.yaw_deg * kDeg, Eigen::Vector2d(0, cabinet ? 0.2 : 0.0));
      Add({"router", Eigen::Vector3d(at.x(), at.y(), cabinet ? kCabinetTopM : kBookcaseTopM), top.yaw_deg});
    }
  }

  void Walls() {
    if (rng_->Uniform() < std::min(1.0, density_)) {
      for (Wall wall : {kSouth, kNorth, kWest, kEast})
        Run(wall, 0.0, 0.08, {{"skirting_board", 1.0}, {"skirting_board_short", 0.2}}, 0.0, 0.016, false);
    }
    const bool sills = rng_->Uniform() < std::min(1.0, density_);
    for (const Span& w : windows_) {
      const double center = 0.5 * (w.a + w.b), width = w.b - w.a;
      if (sills) {
        const int n = static_cast<int>(std::floor((width + 0.10) / 0.2));
        if (walls_.Free(w.wall, center - 0.1 * n, center + 0.1 * n, w.z0 - 0.03, w.z0, 0.0, 0.016)) {
          for (int i = 0; i < n; ++i)
            Add(walls_.On("window_sill", w.wall, center + 0.2 * (i - 0.5 * (n - 1)), w.z0 - 0.03));
          walls_.Take(w.wall, center - 0.1 * n, center + 0.1 * n, w.z0 - 0.03, w.z0);
        }
      }
      if (rng_->Uniform() < std::min(1.0, 0.5 * density_) && w.z1 + 0.07 <= size_m_.z()) {
        const int n = static_cast<int>(std::ceil(width / 0.2 - 1e-9));
        for (int i = 0; i < n; ++i) Add(walls_.On("blind", w.wall, center + 0.2 * (i - 0.5 * (n - 1)), w.z1 - 0.60));
        walls_.Take(w.wall, center - 0.1 * n, center + 0.1 * n, w.z1, w.z1 + 0.07);
      }
    }
    if (rng_->Uniform() < std::min(1.0, 0.5 * density_))
      Run(kNorth, kPipeBottomM, kPipeBottomM + 0.13, {{"heating_pipe", 1.0}}, 0.05, kCornerM, true);
    if (rng_->Uniform() < std::min(1.0, 0.4 * density_))
      Run(kSouth, kTrunkingBottomM, kTrunkingBottomM + 0.06, {{"cable_trunking", 1.0}}, 0.05, kCornerM, true);
    if (!doors_.empty() && rng_->Uniform() < std::min(1.0, density_)) {
      const Eigen::Vector2d& d = doors_.front();
      const Wall wall = d.x() < 0.5 * size_m_.x() ? kWest : kEast;
      for (double side : {1.0, -1.0}) {
        if (Mount(&walls_, &out_, "thermostat", wall, d.y() + side * 0.70, 0.04, kThermostatBottomM, 0.08)) break;
      }
    }
    if (rng_->Uniform() < std::min(1.0, density_)) High("return_grille", 0.20, 0.30);
    if (rng_->Uniform() < std::min(1.0, 0.3 * density_)) High("supply_grille", 0.20, 0.15);
    const double perimeter = 2 * (size_m_.x() + size_m_.y());
    const int decorations = Count(density_ * perimeter / 4.0, rng_);
    for (int k = 0; k < decorations; ++k) {
      const double pick = rng_->Uniform();
      if (pick < 0.35) {
        Decorate("poster", 0.297, kPosterBottomM, 0.841);
      } else if (pick < 0.7) {
        Decorate("framed_picture", 0.25, kPictureBottomM, 0.40);
      } else {
        Decorate("notice_board", 0.45, kBoardBottomM, 0.60);
      }
    }
    if (rng_->Uniform() < std::min(1.0, 0.6 * density_))
      Decorate("wall_clock", 0.15, std::min(kClockBottomM, size_m_.z() - 0.45), 0.30);
  }

  void Ceiling() {
    const double x = size_m_.x(), y = size_m_.y(), h = size_m_.z();
    if (rng_->Uniform() < std::min(1.0, 0.25 * density_)) {
      // A bulkhead boxing in a duct along the south or north wall, end to end, where it is free.
      const Wall wall = rng_->Uniform() < 0.5 ? kSouth : kNorth;
      const double cy = wall == kSouth ? 0.20 : y - 0.20;
      const int n = static_cast<int>(std::floor(x));
      const double x0 = 0.5 * (x - n);
      const Eigen::AlignedBox2d strip(Eigen::Vector2d(x0, cy - 0.20), Eigen::Vector2d(x - x0, cy + 0.20));
      const Eigen::AlignedBox3d volume(Eigen::Vector3d(x0, cy - 0.20, h - 0.25), Eigen::Vector3d(x - x0, cy + 0.20, h));
      if (n > 0 && ceiling_.Free(strip) && walls_.Free(wall, x0, x - x0, h - 0.25, h, 0.0, 0.0) && Clear(volume)) {
        for (int i = 0; i < n; ++i) Add({"bulkhead", Eigen::Vector3d(x0 + i + 0.5, cy, h), 90});
      }
    }
    const double area = x * y;
    const int diffusers = Count(density_ * area / 15.0, rng_);
    for (int k = 0, tries = 0; k < diffusers && tries < 20 * diffusers; ++tries)
      k += OnCeiling("ceiling_diffuser", 0.30, 0.6);
    const int detectors = Count(density_ * std::ceil(area / 60.0), rng_);
    for (int k = 0, tries = 0; k < detectors && tries < 20 * detectors; ++tries)
      k += OnCeiling("smoke_detector", 0.055, 0.5);
    if (rng_->Uniform() < std::min(1.0, 0.5 * density_)) {
      // Sprinklers on a grid of at most 4.6 m and 20.9 m² a head (NFPA 13, light hazard).
      int nx = static_cast<int>(std::ceil(x / 4.6)), ny = static_cast<int>(std::ceil(y / 4.6));
      while ((x / nx) * (y / ny) > 20.9) (x / nx > y / ny ? nx : ny) += 1;
      for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
          for (const Eigen::Vector2d& nudge :
               {Eigen::Vector2d(0, 0), Eigen::Vector2d(0.45, 0), Eigen::Vector2d(-0.45, 0), Eigen::Vector2d(0, 0.45),
                Eigen::Vector2d(0, -0.45)}) {
            const Eigen::Vector2d at = Eigen::Vector2d((i + 0.5) * x / nx, (j + 0.5) * y / ny) + nudge;
            if (CeilingAt("sprinkler", at, 0.035)) break;
          }
        }
      }
    }
  }

  // Papers, mugs, bottles, phones and power strips on every table top, off the seats' places.
  void TableTops() {
    const std::vector<Crowd::SeatPlace> seats = world_.seat_places();
    for (size_t t = 0; t < layout_.pieces.size(); ++t) {
      const Piece& piece = layout_.pieces[t];
      const std::string& a = piece.asset;
      if (!(a.empty() || a == "table" || a == "square_table" || a == "round_table" || a == "desk" || a == "low_table"))
        continue;
      const std::string name = "table " + std::to_string(t);
      const auto top = std::find_if(world_.obstacles().begin(), world_.obstacles().end(),
                                    [&](const Obstacle2D& f) { return f.name == name; });
      if (top == world_.obstacles().end()) continue;
      const double top_z = a == "low_table" ? 0.42 : 0.74;
      std::vector<Obstacle2D> reserved;
      for (const Crowd::SeatPlace& s : seats) {
        if (s.table != static_cast<int>(t)) continue;
        const Eigen::Vector2d at = s.world_from_seat.topRightCorner<2, 1>().cast<double>();
        const Eigen::Vector2d facing = s.world_from_seat.block<2, 1>(0, 0).cast<double>().normalized();
        double edge = 0;
        while (edge < 1.0 && DistanceToObstacle(at + edge * facing, *top) > 0) edge += 0.005;
        const double yaw = std::atan2(facing.y(), facing.x());
        const Eigen::Vector2d center =
            at + Rotate(yaw, Eigen::Vector2d(edge + 0.5 * kPlaceInM - 0.02, 0.5 * (kPlaceLeftM - kPlaceRightM)));
        reserved.push_back(
            Obstacle2D::Rectangle("place", center, Eigen::Vector2d(kPlaceInM + 0.04, kPlaceLeftM + kPlaceRightM), yaw));
      }
      for (const auto& [center, footprint] : on_tops_)
        if (std::abs(center.z() - top_z) < 0.01 && DistanceToObstacle(center.head<2>(), *top) == 0)
          reserved.push_back(footprint);
      const bool desk = a == "desk";
      const std::pair<const char*, double> items[] = {
          {"papers", 0.6}, {"mug", 0.5}, {"bottle", 0.4}, {"desk_phone", desk ? 0.5 : 0.15}, {"power_strip", 0.25}};
      for (const auto& [asset, mean] : items) {
        const int n = Count(mean * density_, rng_);
        for (int k = 0; k < n; ++k) OnTop(asset, piece, *top, top_z, &reserved);
      }
    }
  }

  std::vector<PlacedObject> Out() const { return out_; }

 private:
  // Records an object already in the room (or just placed): its stretch of any wall it touches,
  // its footprint on the floor, its rectangle on the ceiling, what stands on a table top.
  void Note(const PlacedObject& o) {
    const Asset& asset = assets_->Get(o.asset);
    const Eigen::AlignedBox3d box = WorldBox(o, asset);
    boxes_.push_back(box);
    const double x = size_m_.x(), y = size_m_.y();
    if (box.min().y() < kWallTouchM) walls_.Take(kSouth, box.min().x(), box.max().x(), box.min().z(), box.max().z());
    if (y - box.max().y() < kWallTouchM)
      walls_.Take(kNorth, box.min().x(), box.max().x(), box.min().z(), box.max().z());
    if (box.min().x() < kWallTouchM) walls_.Take(kWest, box.min().y(), box.max().y(), box.min().z(), box.max().z());
    if (x - box.max().x() < kWallTouchM) walls_.Take(kEast, box.min().y(), box.max().y(), box.min().z(), box.max().z());
    if (asset.mount == "floor" && o.position_m.z() < 0.2 && asset.bounds_m.max().z() > 0.02)
      floor_.footprints.push_back(Footprint(o, asset));
    if (asset.mount == "hanging" && box.max().z() > size_m_.z() - 1e-3)
      ceiling_.Take(Eigen::AlignedBox2d(box.min().head<2>(), box.max().head<2>()));
    if (asset.mount == "floor" && o.position_m.z() > 0.3) on_tops_.emplace_back(o.position_m, Footprint(o, asset));
    if (o.asset == "cabinet" || o.asset == "bookcase") tops_.push_back(o);
  }

  // Whether `box` meets no object's box.
  bool Clear(const Eigen::AlignedBox3d& box) const {
    return std::none_of(boxes_.begin(), boxes_.end(), [&](const Eigen::AlignedBox3d& b) { return b.intersects(box); });
  }

  void Add(const PlacedObject& o) {
    out_.push_back(o);
    Note(o);
  }

  // A floor object at `o` when its footprint is clear (it then takes its stretch of a near wall).
  bool Place(const PlacedObject& o) {
    const Obstacle2D footprint = Footprint(o, assets_->Get(o.asset));
    if (!floor_.Clear(footprint)) return false;
    const Eigen::AlignedBox3d box = WorldBox(o, assets_->Get(o.asset));
    const double x = size_m_.x(), y = size_m_.y();
    const std::pair<Wall, bool> near[] = {{kSouth, box.min().y() < kWallTouchM},
                                          {kNorth, y - box.max().y() < kWallTouchM},
                                          {kWest, box.min().x() < kWallTouchM},
                                          {kEast, x - box.max().x() < kWallTouchM}};
    for (const auto& [wall, touches] : near) {
      const bool along_x = wall == kSouth || wall == kNorth;
      const double a = along_x ? box.min().x() : box.min().y(), b = along_x ? box.max().x() : box.max().y();
      if (touches && !walls_.Free(wall, a, b, 0, box.max().z(), 0.0, 0.0)) return false;
    }
    Add(o);
    return true;
  }

  // A floor object with its back `off_m` from a random wall, facing into the room.
  bool AgainstWall(const std::string& name, double off_m) {
    const Asset& asset = assets_->Get(name);
    const Wall wall = static_cast<Wall>(rng_->UniformInt(4));
    const double half = 0.5 * asset.bounds_m.sizes().y(), depth = asset.bounds_m.sizes().x();
    const double along = rng_->Uniform(half + 0.05, walls_.Length(wall) - half - 0.05);
    PlacedObject o = walls_.On(name, wall, along, 0);
    o.position_m.head<2>() +=
        Rotate(o.yaw_deg * kDeg,
               Eigen::Vector2d(off_m + 0.5 * depth - 0.5 * (asset.bounds_m.min().x() + asset.bounds_m.max().x()), 0));
    return Place(o);
  }

  // A bookcase against a wall, its shelves holding rows of books and binders.
  bool Bookcase() {
    const size_t before = out_.size();
    if (!AgainstWall("bookcase", 0.01)) return false;
    const PlacedObject bookcase = out_[before];
    const double yaw = bookcase.yaw_deg * kDeg;
    for (double shelf : kBookcaseShelvesM) {
      for (double along : {-0.195, 0.185}) {
        if (rng_->Uniform() >= 0.85) continue;
        const bool binders = rng_->Uniform() < 0.4;
        const Eigen::Vector2d at = bookcase.position_m.head<2>() +
                                   Rotate(yaw, Eigen::Vector2d(binders ? 0.005 : 0.0, binders ? along + 0.005 : along));
        Add({binders ? "binder_row" : "book_row", Eigen::Vector3d(at.x(), at.y(), shelf), bookcase.yaw_deg});
      }
    }
    return true;
  }

  void Rug(const Eigen::Vector2d& at, double yaw_deg) {
    const PlacedObject rug{"rug", Eigen::Vector3d(at.x(), at.y(), 0), yaw_deg};
    const Eigen::AlignedBox3d box = WorldBox(rug, assets_->Get("rug"));
    if (box.min().x() < 0.3 || box.min().y() < 0.3 || box.max().x() > size_m_.x() - 0.3 ||
        box.max().y() > size_m_.y() - 0.3)
      return;
    for (const Eigen::Vector2d& d : doors_)
      if (DistanceToObstacle(d, Footprint(rug, assets_->Get("rug"))) < kDoorwayM) return;
    Add(rug);
  }

  // Pieces `lengths` long (longest first) end to end along every free stretch of `wall` over
  // [z0, z1]; `whole` runs only where at least one longest piece fits.
  void Run(Wall wall, double z0, double z1, const std::vector<std::pair<std::string, double>>& pieces, double gap_m,
           double corner_m, bool whole) {
    for (const auto& [a, b] : walls_.FreeStretches(wall, z0, z1, gap_m, corner_m)) {
      double left = b - a;
      std::vector<std::pair<std::string, double>> run;
      for (const auto& [name, length] : pieces) {
        while (left >= length - 1e-9) {
          run.emplace_back(name, length);
          left -= length;
        }
      }
      if (run.empty() || (whole && run.front().second < pieces.front().second)) continue;
      double at = a + 0.5 * left;
      for (const auto& [name, length] : run) {
        Add(walls_.On(name, wall, at + 0.5 * length, z0));
        at += length;
      }
      walls_.Take(wall, a + 0.5 * left, b - 0.5 * left, z0, z1);
    }
  }

  // A wall object high on a random wall, its top kGrilleBelowCeilingM under the ceiling.
  void High(const std::string& name, double half_m, double height_m) {
    for (int tries = 0; tries < 12; ++tries) {
      const Wall wall = static_cast<Wall>(rng_->UniformInt(4));
      const double along = rng_->Uniform(kCornerM + half_m, walls_.Length(wall) - kCornerM - half_m);
      if (Mount(&walls_, &out_, name, wall, along, half_m, size_m_.z() - kGrilleBelowCeilingM - height_m, height_m))
        return;
    }
  }

  void Decorate(const std::string& name, double half_m, double bottom_m, double height_m) {
    for (int tries = 0; tries < 12; ++tries) {
      const Wall wall = static_cast<Wall>(rng_->UniformInt(4));
      if (walls_.Length(wall) < 2 * (kCornerM + half_m)) continue;
      const double along = rng_->Uniform(kCornerM + half_m, walls_.Length(wall) - kCornerM - half_m);
      if (Mount(&walls_, &out_, name, wall, along, half_m, bottom_m, height_m)) return;
    }
  }

  bool CeilingAt(const std::string& name, const Eigen::Vector2d& at, double half_m) {
    const Eigen::AlignedBox2d box(at - Eigen::Vector2d(half_m, half_m), at + Eigen::Vector2d(half_m, half_m));
    if (box.min().minCoeff() < 0.3 || box.max().x() > size_m_.x() - 0.3 || box.max().y() > size_m_.y() - 0.3 ||
        !ceiling_.Free(box))
      return false;
    Add({name, Eigen::Vector3d(at.x(), at.y(), size_m_.z()), 0});
    return true;
  }

  // A ceiling object at a random point at least wall_m from the walls.
  bool OnCeiling(const std::string& name, double half_m, double wall_m) {
    const double x = size_m_.x(), y = size_m_.y();
    if (x < 2 * (wall_m + half_m) || y < 2 * (wall_m + half_m)) return false;
    return CeilingAt(name,
                     Eigen::Vector2d(rng_->Uniform(wall_m + half_m, x - wall_m - half_m),
                                     rng_->Uniform(wall_m + half_m, y - wall_m - half_m)),
                     half_m);
  }

  // A table-top object at a random point of `top`, 1.5 cm in from its edges, clear of `reserved`.
  void OnTop(const std::string& name, const Piece& piece, const Obstacle2D& top, double top_z,
             std::vector<Obstacle2D>* reserved) {
    const Asset& asset = assets_->Get(name);
    const bool round = piece.asset == "round_table";
    const Eigen::Vector2d half = round ? Eigen::Vector2d(0.45, 0.45) : top.half_size_m;
    for (int tries = 0; tries < 80; ++tries) {
      const Eigen::Vector2d local(rng_->Uniform(-half.x(), half.x()), rng_->Uniform(-half.y(), half.y()));
      const Eigen::Vector2d at = top.center_m + Rotate(round ? 0 : top.yaw_rad, local);
      const double yaw_deg = piece.yaw_deg + 90 * static_cast<double>(rng_->UniformInt(4)) + rng_->Uniform(-12, 12);
      const PlacedObject o{name, Eigen::Vector3d(at.x(), at.y(), top_z), yaw_deg};
      const Obstacle2D footprint = Footprint(o, asset);
      bool fits = true;
      for (int c = 0; c < 4 && fits; ++c) {
        const Eigen::Vector2d corner =
            footprint.center_m +
            Rotate(footprint.yaw_rad, Eigen::Vector2d((c & 1 ? 1 : -1) * footprint.half_size_m.x(),
                                                      (c & 2 ? 1 : -1) * footprint.half_size_m.y()));
        const Eigen::Vector2d in_top = Rotate(-top.yaw_rad, corner - top.center_m);
        fits = round ? (corner - top.center_m).norm() < 0.45 - 0.015
                     : std::abs(in_top.x()) < top.half_size_m.x() - 0.015 &&
                           std::abs(in_top.y()) < top.half_size_m.y() - 0.015;
      }
      Obstacle2D grown = footprint;
      grown.half_size_m += Eigen::Vector2d(0.01, 0.01);
      for (const Obstacle2D& r : *reserved) fits = fits && !FootprintsOverlap(grown, r);
      if (!fits) continue;
      reserved->push_back(footprint);
      out_.push_back(o);
      return;
    }
  }

  Eigen::Vector3d size_m_;
  const Layout& layout_;
  const World& world_;
  AssetLibrary* assets_;
  WallPlan walls_;
  double density_;
  FloorCheck floor_;
  std::vector<Eigen::Vector2d> doors_;
  Rng* rng_;
  CeilingPlan ceiling_;
  std::vector<Span> windows_;
  std::vector<std::pair<Eigen::Vector3d, Obstacle2D>> on_tops_;
  std::vector<PlacedObject> tops_;          // cabinets and bookcases
  std::vector<Eigen::AlignedBox3d> boxes_;  // every object's
  std::vector<PlacedObject> out_;
};

}  // namespace

bool StandsOnTheFloor(const std::string& asset) {
  for (const char* name :
       {"cabinet", "bag", "bookcase", "book_row", "binder_row", "router", "pc_tower", "bin", "cardboard_box"})
    if (asset == name) return true;
  return false;
}

std::vector<PlacedObject> Clutter(const Eigen::Vector3d& size_m, const Layout& layout,
                                  const nlohmann::ordered_json& windows, const std::vector<Eigen::Vector2d>& doors,
                                  const std::vector<PlacedObject>& placed, const World& world, AssetLibrary* assets,
                                  const std::vector<Eigen::Vector2d>& route, const GeneratorOptions& options,
                                  Rng* rng) {
  if (options.objects.clutter_density <= 0) return {};
  ClutterPlanner planner(size_m, layout, world, assets, doors, route, options, rng);
  planner.Hold(windows, placed);
  planner.Floor();
  planner.Walls();
  planner.Ceiling();
  planner.TableTops();
  return planner.Out();
}

}  // namespace hoilcd
