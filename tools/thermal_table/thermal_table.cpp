// thermal_table: the docs' table of what the room's thermal solution computes for a scene: each
// room surface's range over its patches, and each object's range over its instances, per
// material, both over the whole run (sampled every STEP seconds), as Markdown.
// Usage: thermal_table SCENE [STEP_S] [--set NAME=VALUE ...] (HOILCD_DATA_DIR as for hoilcd).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "hoilcd/sim/scene/scene.h"
#include "hoilcd/sim/scene/scene_options.h"
#include "hoilcd/sim/world/world.h"

namespace {

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  Eigen::Vector3f lo_at = Eigen::Vector3f::Zero(), hi_at = Eigen::Vector3f::Zero();  // where (room faces)
  void Add(double v, const Eigen::Vector3f& at = Eigen::Vector3f::Zero()) {
    if (!std::isfinite(v)) return;
    if (v < lo) lo = v, lo_at = at;
    if (v > hi) hi = v, hi_at = at;
  }
  bool empty() const { return lo > hi; }
};

// A face of the room's box, sampled at the centres of a grid of cells about 0.1 m wide (never on
// its edges, which lie on the next face too; RoomTemperatureC is bilinear between patch centres,
// so this reaches each patch's own value).
struct Face {
  std::string name;
  Eigen::Vector3f origin, u, v;  // points origin + a u + b v, a, b in [0, 1]
  std::string wall;              // north | south | east | west, or empty
};

// Whether p lies on a window of `wall` (the wall's own patches behind the glass are hidden).
bool BehindWindow(const hoilcd::Scene& scene, const std::string& wall, const Eigen::Vector3f& p) {
  for (const hoilcd::WindowSpec& w : scene.room.windows) {
    if (w.wall != wall) continue;
    const double along = wall == "north" || wall == "south" ? p.x() : p.y();
    if (std::abs(along - w.center_m) < 0.5 * w.width_m && p.z() > w.bottom_m && p.z() < w.bottom_m + w.height_m)
      return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: thermal_table SCENE [STEP_S] [--set NAME=VALUE ...]\n";
    return 2;
  }
  try {
    double step_s = 10;
    std::vector<std::string> overrides = {"room.thermal.enabled=true"};
    for (int i = 2; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--set" && i + 1 < argc) {
        overrides.push_back(argv[++i]);
      } else {
        char* end = nullptr;
        step_s = std::strtod(arg.c_str(), &end);
        if (end == arg.c_str() || *end != '\0' || !(step_s > 0) || !std::isfinite(step_s)) {
          throw std::invalid_argument("STEP_S '" + arg + "': expected seconds, a number above 0");
        }
      }
    }
    const hoilcd::Scene scene = hoilcd::LoadScene(argv[1], overrides);
    const hoilcd::BandRadianceTable table;
    hoilcd::World world(scene, table);
    world.PlanCrowd(hoilcd::SimulateSceneRobot(scene, world.obstacles()).samples);
    const Eigen::Vector3f size = scene.room.size_m.cast<float>();
    const float X = size.x(), Y = size.y(), Z = size.z();
    const std::vector<Face> faces = {{"floor", {0, 0, 0}, {X, 0, 0}, {0, Y, 0}, ""},
                                     {"ceiling", {0, 0, Z}, {X, 0, 0}, {0, Y, 0}, ""},
                                     {"south wall (y = 0)", {0, 0, 0}, {X, 0, 0}, {0, 0, Z}, "south"},
                                     {"north wall", {0, Y, 0}, {X, 0, 0}, {0, 0, Z}, "north"},
                                     {"west wall (x = 0)", {0, 0, 0}, {0, Y, 0}, {0, 0, Z}, "west"},
                                     {"east wall", {X, 0, 0}, {0, Y, 0}, {0, 0, Z}, "east"}};
    const hoilcd::InstanceInfo& room = world.instance(world.room_instance());
    const char* kRoomMaterial[] = {"floor", "ceiling", "wall"};
    auto room_material_name = [&](int m) {
      return m < 3                                                 ? std::string(kRoomMaterial[m])
             : m < 3 + static_cast<int>(scene.room.windows.size()) ? "window"
                                                                   : "interior wall";
    };
    std::map<std::pair<std::string, std::string>, Range> room_ranges;    // (face, material)
    std::map<std::pair<std::string, std::string>, Range> object_ranges;  // (asset, material)
    std::map<std::pair<std::string, std::string>, double> held;          // declared °C
    std::map<std::string, int> instances_of;
    Range air;
    const double duration_s = scene.frames / scene.frame_rate_hz;
    for (double t = 0;; t = std::min(duration_s, t + step_s)) {
      world.SetTime(t);
      const hoilcd::RoomNetwork& network = *world.room_network();
      air.Add(world.AirTemperatureC(t));
      for (const Face& face : faces) {
        const int nu = std::max(2, static_cast<int>(face.u.norm() / 0.1f)),
                  nv = std::max(2, static_cast<int>(face.v.norm() / 0.1f));
        for (int m = 0; m < static_cast<int>(room.materials.size()); ++m) {
          Range& range = room_ranges[{face.name, room_material_name(m)}];
          for (int a = 0; a < nu; ++a) {
            for (int b = 0; b < nv; ++b) {
              const Eigen::Vector3f p = face.origin + face.u * ((a + 0.5f) / nu) + face.v * ((b + 0.5f) / nv);
              if (BehindWindow(scene, face.wall, p)) continue;
              range.Add(network.RoomTemperatureC(m, p), p);
            }
          }
        }
      }
      for (int m = 0; m < static_cast<int>(room.materials.size()); ++m) {
        room_ranges[{"mean over the material", room_material_name(m)}].Add(network.RoomMeanTemperatureC(m));
      }
      for (int i = 0; i < world.num_instances(); ++i) {
        const hoilcd::InstanceInfo& info = world.instance(i);
        if (!info.fixture || info.asset == nullptr) continue;
        const std::string asset = std::filesystem::path(info.asset->path).stem().string();
        if (t == 0) ++instances_of[asset];
        for (int m = 0; m < static_cast<int>(info.asset->materials.size()); ++m) {
          const hoilcd::ThermalMaterial& material = info.asset->materials[static_cast<size_t>(m)];
          const float c = network.InstanceTemperatureC(i, m);
          if (std::isfinite(c)) {
            object_ranges[{asset, material.name}].Add(c);
          } else {
            held[{asset, material.name}] = material.temperature_c;
          }
        }
      }
      if (t >= duration_s) break;
    }
    std::printf("Air, over the run: %.2f to %.2f °C. Sampled every %g s over %g s.\n\n", air.lo, air.hi, step_s,
                duration_s);
    std::printf(
        "| room surface | material | °C, over its patches and the run | coldest at (x, y, z), m | warmest at "
        "|\n|---|---|---|---|---|\n");
    for (const auto& [key, r] : room_ranges) {
      if (r.empty()) continue;
      if (key.first == "mean over the material") {
        std::printf("| %s | %s | %.1f – %.1f | | |\n", key.first.c_str(), key.second.c_str(), r.lo, r.hi);
        continue;
      }
      std::printf("| %s | %s | %.1f – %.1f | (%.2f, %.2f, %.2f) | (%.2f, %.2f, %.2f) |\n", key.first.c_str(),
                  key.second.c_str(), r.lo, r.hi, r.lo_at.x(), r.lo_at.y(), r.lo_at.z(), r.hi_at.x(), r.hi_at.y(),
                  r.hi_at.z());
    }
    std::printf("\n| object (instances) | material | °C, over its instances and the run |\n|---|---|---|\n");
    for (const auto& [key, range] : object_ranges) {
      std::printf("| %s (%d) | %s | %.1f – %.1f |\n", key.first.c_str(), instances_of[key.first], key.second.c_str(),
                  range.lo, range.hi);
    }
    for (const auto& [key, value] : held) {
      if (object_ranges.count(key) == 0) {
        std::printf("| %s (%d) | %s | held at %.1f |\n", key.first.c_str(), instances_of[key.first], key.second.c_str(),
                    value);
      }
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "thermal_table: " << e.what() << "\n";
    return 1;
  }
}
