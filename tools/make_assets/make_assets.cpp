// make_assets: writes the hoilcd glTF 2.0 assets (people, furniture, hot objects) with their
// thermal extras. Usage: make_assets OUT_DIR. Output is deterministic: no randomness, no clock,
// and JSON objects are written with sorted keys, so regenerating shows no diff.
//
// Shapes are modelled in the hoilcd asset frame (metres, z up, x forward, y left) and converted
// to glTF (+Y up, front +Z) on output: (X, Y, Z)_gltf = (y, z, x)_hoilcd.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <tiny_gltf.h>

namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
constexpr double kPi = 3.14159265358979323846;

double Deg(double degrees) { return degrees * kPi / 180.0; }

// Rotation about the hoilcd y axis (left) that tips +z towards +x by `angle_rad`.
Mat3 PitchForward(double angle_rad) { return Eigen::AngleAxisd(angle_rad, Vec3::UnitY()).toRotationMatrix(); }

// ---------------------------------------------------------------------------------------------
// Shapes: closed triangle surfaces in the hoilcd frame.
// Hand-written: the libraries we build with (Eigen, tinygltf) make no capsule/loft meshes.

struct Shape {
  std::vector<Vec3> positions;
  std::vector<uint32_t> indices;  // 3 per triangle
};

// Signed volume (divergence theorem); positive when the closed surface's triangles face outwards.
double SignedVolume(const Shape& shape) {
  double volume = 0;
  for (size_t t = 0; t < shape.indices.size(); t += 3) {
    const Vec3& a = shape.positions[shape.indices[t]];
    const Vec3& b = shape.positions[shape.indices[t + 1]];
    const Vec3& c = shape.positions[shape.indices[t + 2]];
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

void OrientOutwards(Shape& shape) {
  if (SignedVolume(shape) >= 0) return;
  for (size_t t = 0; t < shape.indices.size(); t += 3) {
    std::swap(shape.indices[t + 1], shape.indices[t + 2]);
  }
}

// One cross-section of a loft: centre plus two half-axis vectors (length = half size).
struct Ring {
  Vec3 center;
  Vec3 u;
  Vec3 v;
};

// Superellipse coordinate: exponent 2 is an ellipse, larger values are boxier.
double SuperCoord(double c, double exponent) { return std::copysign(std::pow(std::abs(c), 2.0 / exponent), c); }

// Closed surface through `rings` (each sampled at `around` points), closed by a pole at each end.
Shape Loft(const std::vector<Ring>& rings, const Vec3& start_pole, const Vec3& end_pole, int around,
           double exponent = 2.0) {
  Shape shape;
  const auto n = static_cast<uint32_t>(around);
  shape.positions.push_back(start_pole);
  for (const Ring& ring : rings) {
    for (int j = 0; j < around; ++j) {
      const double theta = 2.0 * kPi * j / around;
      shape.positions.push_back(ring.center + ring.u * SuperCoord(std::cos(theta), exponent) +
                                ring.v * SuperCoord(std::sin(theta), exponent));
    }
  }
  shape.positions.push_back(end_pole);
  const auto ring_count = static_cast<uint32_t>(rings.size());
  const auto end_index = static_cast<uint32_t>(shape.positions.size() - 1);
  auto at = [n](uint32_t ring, uint32_t j) { return 1 + ring * n + (j % n); };
  for (uint32_t j = 0; j < n; ++j) {
    shape.indices.insert(shape.indices.end(), {0, at(0, j + 1), at(0, j)});
    shape.indices.insert(shape.indices.end(), {end_index, at(ring_count - 1, j), at(ring_count - 1, j + 1)});
  }
  for (uint32_t r = 0; r + 1 < ring_count; ++r) {
    for (uint32_t j = 0; j < n; ++j) {
      shape.indices.insert(shape.indices.end(), {at(r, j), at(r, j + 1), at(r + 1, j)});
      shape.indices.insert(shape.indices.end(), {at(r, j + 1), at(r + 1, j + 1), at(r + 1, j)});
    }
  }
  OrientOutwards(shape);
  return shape;
}

// Ellipsoid with half sizes `radii` along the columns of `axes`.
Shape Ellipsoid(const Vec3& center, const Mat3& axes, const Vec3& radii, int around, int rings) {
  std::vector<Ring> sections;
  for (int i = 1; i < rings; ++i) {
    const double phi = -kPi / 2 + kPi * i / rings;
    sections.push_back({center + axes.col(2) * radii.z() * std::sin(phi), axes.col(0) * radii.x() * std::cos(phi),
                        axes.col(1) * radii.y() * std::cos(phi)});
  }
  return Loft(sections, center - axes.col(2) * radii.z(), center + axes.col(2) * radii.z(), around);
}

// Any unit vector perpendicular to `w`.
Vec3 Perpendicular(const Vec3& w) {
  const Vec3 helper = std::abs(w.z()) < 0.9 ? Vec3::UnitZ() : Vec3::UnitX();
  return w.cross(helper).normalized();
}

// Tapered capsule: sphere of radius ra around joint a, rb around joint b, joined by a cone.
Shape Capsule(const Vec3& a, const Vec3& b, double ra, double rb, int around = 16, int cap_rings = 4) {
  const Vec3 w = (b - a).normalized();
  const Vec3 u = Perpendicular(w);
  const Vec3 v = w.cross(u);
  std::vector<Ring> sections;
  for (int i = 1; i <= cap_rings; ++i) {
    const double phi = -kPi / 2 + (kPi / 2) * i / cap_rings;
    const double r = ra * std::cos(phi);
    sections.push_back({a + w * ra * std::sin(phi), u * r, v * r});
  }
  for (int i = 0; i < cap_rings; ++i) {
    const double phi = (kPi / 2) * i / cap_rings;
    const double r = rb * std::cos(phi);
    sections.push_back({b + w * rb * std::sin(phi), u * r, v * r});
  }
  return Loft(sections, a - w * ra, b + w * rb, around);
}

// Round rod whose rounded ends touch `a` and `b`.
Shape Rod(const Vec3& a, const Vec3& b, double radius, int around = 12) {
  const Vec3 w = (b - a).normalized();
  return Capsule(a + w * radius, b - w * radius, radius, radius, around, 2);
}

// Solid of revolution about the z axis through `base`: profile (radius, height) from the bottom
// pole to the top pole (radius 0 at both ends is implied).
Shape Lathe(const Vec3& base, const std::vector<Eigen::Vector2d>& profile, double bottom_z, double top_z, int around) {
  std::vector<Ring> sections;
  for (const Eigen::Vector2d& p : profile) {
    sections.push_back({base + Vec3(0, 0, p.y()), Vec3(p.x(), 0, 0), Vec3(0, p.x(), 0)});
  }
  return Loft(sections, base + Vec3(0, 0, bottom_z), base + Vec3(0, 0, top_z), around);
}

// Box with half sizes `half` along the columns of `axes`; faces do not share vertices.
Shape Box(const Vec3& center, const Mat3& axes, const Vec3& half) {
  Shape shape;
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign = -1; sign <= 1; sign += 2) {
      const Vec3 n = axes.col(axis) * sign;
      const Vec3 s = axes.col((axis + 1) % 3) * half[(axis + 1) % 3];
      const Vec3 t = axes.col((axis + 2) % 3) * half[(axis + 2) % 3];
      const Vec3 c = center + n * half[axis];
      const auto first = static_cast<uint32_t>(shape.positions.size());
      shape.positions.insert(shape.positions.end(), {c - s - t, c + s - t, c + s + t, c - s + t});
      if (sign > 0) {
        shape.indices.insert(shape.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
      } else {
        shape.indices.insert(shape.indices.end(), {first, first + 2, first + 1, first, first + 3, first + 2});
      }
    }
  }
  OrientOutwards(shape);
  return shape;
}

// ---------------------------------------------------------------------------------------------
// Asset description: materials with thermal extras, triangles per material, scene extras.

struct ThermalSpec {
  std::string region;
  double temperature_c;
  double emissivity;
  bool specular;
  std::array<double, 4> base_color;  // for ordinary glTF viewers only
  double metallic;
  double power_w = 0;  // W released inside the part (written only when above 0)
};

struct Contact {
  std::string name;
  Vec3 position;  // hoilcd frame
};

struct AssetBuilder {
  std::string name;
  std::string class_name;
  std::string posture;  // people only
  std::string mount;    // "wall" or "hanging" for room objects that do not stand on the floor
  std::vector<ThermalSpec> materials;
  std::vector<Shape> parts;  // one per material
  std::vector<Contact> contacts;
  // Body parts of the articulated person only: part name, parent part ("" for the root), the
  // joint the part turns about and its COCO keypoints, all in the rest pose's body frame.
  std::string part;
  std::string parent;
  Vec3 joint = Vec3::Zero();
  std::vector<Contact> keypoints;

  int Material(const ThermalSpec& spec) {
    for (size_t i = 0; i < materials.size(); ++i) {
      if (materials[i].region == spec.region) return static_cast<int>(i);
    }
    materials.push_back(spec);
    parts.emplace_back();
    return static_cast<int>(materials.size() - 1);
  }

  // Adds the shape's triangles to the material `pick(centroid, normal)` returns for each.
  void Add(const Shape& shape, const std::function<int(const Vec3&, const Vec3&)>& pick) {
    std::vector<std::vector<int64_t>> remap(parts.size(), std::vector<int64_t>(shape.positions.size(), -1));
    for (size_t t = 0; t < shape.indices.size(); t += 3) {
      const Vec3& a = shape.positions[shape.indices[t]];
      const Vec3& b = shape.positions[shape.indices[t + 1]];
      const Vec3& c = shape.positions[shape.indices[t + 2]];
      const Vec3 normal = (b - a).cross(c - a).normalized();
      const int material = pick((a + b + c) / 3.0, normal);
      Shape& part = parts[static_cast<size_t>(material)];
      for (int k = 0; k < 3; ++k) {
        const uint32_t source = shape.indices[t + static_cast<size_t>(k)];
        int64_t& target = remap[static_cast<size_t>(material)][source];
        if (target < 0) {
          target = static_cast<int64_t>(part.positions.size());
          part.positions.push_back(shape.positions[source]);
        }
        part.indices.push_back(static_cast<uint32_t>(target));
      }
    }
  }

  void Add(const Shape& shape, int material) {
    Add(shape, [material](const Vec3&, const Vec3&) { return material; });
  }
};

// Thermal properties (SPEC.md "Radiometry"; assets/README.md lists sources and choices).
const ThermalSpec kSkin{"skin", 34.0, 0.98, false, {0.85, 0.62, 0.50, 1}, 0};
const ThermalSpec kHair{"hair", 30.0, 0.95, false, {0.20, 0.14, 0.10, 1}, 0};
const ThermalSpec kClothingUpper{"clothing_upper", 28.5, 0.90, false, {0.25, 0.40, 0.65, 1}, 0};
const ThermalSpec kClothingLower{"clothing_lower", 27.5, 0.90, false, {0.20, 0.20, 0.25, 1}, 0};
const ThermalSpec kShoes{"shoes", 25.0, 0.90, false, {0.10, 0.08, 0.06, 1}, 0};
const ThermalSpec kWood{"wood", 22.0, 0.90, false, {0.60, 0.45, 0.30, 1}, 0};
const ThermalSpec kMetal{"metal", 22.0, 0.10, true, {0.75, 0.75, 0.78, 1}, 1};
const ThermalSpec kPlastic{"plastic", 22.0, 0.94, false, {0.30, 0.30, 0.32, 1}, 0};
const ThermalSpec kCeramic{"ceramic", 45.0, 0.92, false, {0.95, 0.95, 0.92, 1}, 0};
const ThermalSpec kCoffee{"coffee", 55.0, 0.95, false, {0.30, 0.18, 0.08, 1}, 0};
const ThermalSpec kLaptopBase{"laptop_base", 32.0, 0.90, false, {0.55, 0.55, 0.58, 1}, 0};
const ThermalSpec kLaptopLid{"laptop_lid", 30.0, 0.90, false, {0.55, 0.55, 0.58, 1}, 0};
const ThermalSpec kLaptopScreen{"laptop_screen", 30.0, 0.94, true, {0.05, 0.05, 0.08, 1}, 0};
const ThermalSpec kMonitorBack{"monitor_back", 30.0, 0.94, false, {0.12, 0.12, 0.12, 1}, 0, 13.0};
const ThermalSpec kMonitorScreen{"monitor_screen", 27.0, 0.94, true, {0.03, 0.03, 0.05, 1}, 0, 4.0};
const ThermalSpec kRadiator{"radiator", 42.0, 0.93, false, {0.95, 0.95, 0.95, 1}, 0};
const ThermalSpec kUpholstery{"upholstery", 22.0, 0.95, false, {0.35, 0.30, 0.45, 1}, 0};
const ThermalSpec kFelt{"felt", 22.0, 0.92, false, {0.45, 0.50, 0.45, 1}, 0};
const ThermalSpec kLaminate{"laminate", 22.0, 0.90, false, {0.85, 0.85, 0.80, 1}, 0};
// Room objects: docs/models/room_objects.md gives each figure's source.
const ThermalSpec kWhiteboard{"whiteboard", 22.0, 0.88, true, {0.97, 0.97, 0.97, 1}, 0};
const ThermalSpec kAnodized{"anodized_aluminium", 22.0, 0.55, true, {0.80, 0.80, 0.82, 1}, 1};
const ThermalSpec kPaintedWood{"painted_wood", 22.0, 0.93, false, {0.93, 0.93, 0.90, 1}, 0};
const ThermalSpec kDoorLeaf{"door_leaf", 22.0, 0.90, false, {0.70, 0.55, 0.40, 1}, 0};
const ThermalSpec kAcLouvre{"ac_louvre", 15.0, 0.94, false, {0.90, 0.90, 0.90, 1}, 0};
const ThermalSpec kBooks{"books", 22.0, 0.93, false, {0.60, 0.25, 0.20, 1}, 0};
const ThermalSpec kPaintedSteel{"painted_steel", 22.0, 0.93, false, {0.55, 0.58, 0.60, 1}, 0};
const ThermalSpec kLightDiffuser{"light_diffuser", 26.0, 0.94, false, {1.00, 1.00, 0.98, 1}, 0};
const ThermalSpec kLightFrame{"light_frame", 30.0, 0.93, false, {0.95, 0.95, 0.95, 1}, 0};
const ThermalSpec kBagFabric{"bag_fabric", 22.0, 0.90, false, {0.15, 0.20, 0.30, 1}, 0};
const ThermalSpec kCoat{"coat", 25.0, 0.90, false, {0.30, 0.25, 0.20, 1}, 0};
const ThermalSpec kCharger{"charger", 40.0, 0.94, false, {0.10, 0.10, 0.10, 1}, 0};
// The clutter of lived-in rooms (docs/models/room_objects.md gives each figure's source). Powered
// parts carry power_w for the room's thermal solution and temperature_c for renders without it.
const ThermalSpec kPcCase{"pc_case", 24.0, 0.93, false, {0.15, 0.15, 0.16, 1}, 0, 10.0};
const ThermalSpec kPcExhaust{"pc_exhaust", 34.0, 0.93, false, {0.05, 0.05, 0.05, 1}, 0};
const ThermalSpec kPhone{"phone", 26.0, 0.94, false, {0.10, 0.10, 0.11, 1}, 0, 6.0};
const ThermalSpec kRouter{"router", 33.0, 0.94, false, {0.90, 0.90, 0.90, 1}, 0, 8.0};
const ThermalSpec kMug{"mug", 22.0, 0.92, false, {0.85, 0.30, 0.25, 1}, 0};
const ThermalSpec kBottle{"bottle", 22.0, 0.94, false, {0.70, 0.85, 0.95, 1}, 0};
const ThermalSpec kPaper{"paper", 22.0, 0.93, false, {0.98, 0.98, 0.98, 1}, 0};
const ThermalSpec kBinder{"binder", 22.0, 0.94, false, {0.20, 0.30, 0.60, 1}, 0};
const ThermalSpec kPoster{"poster", 22.0, 0.89, false, {0.40, 0.60, 0.80, 1}, 0};
const ThermalSpec kGlass{"glass", 22.0, 0.94, true, {0.85, 0.90, 0.90, 1}, 0};
const ThermalSpec kPinboard{"pinboard", 22.0, 0.90, false, {0.35, 0.45, 0.55, 1}, 0};
const ThermalSpec kSupplyAir{"supply_air", 30.0, 0.93, false, {0.90, 0.90, 0.90, 1}, 0};
const ThermalSpec kHeatingFlow{"heating_flow", 45.0, 0.93, false, {0.95, 0.95, 0.95, 1}, 0};
const ThermalSpec kHeatingReturn{"heating_return", 37.0, 0.93, false, {0.95, 0.95, 0.95, 1}, 0};
const ThermalSpec kBlindFabric{"blind_fabric", 22.0, 0.90, false, {0.85, 0.83, 0.78, 1}, 0};
const ThermalSpec kCardboard{"cardboard", 22.0, 0.93, false, {0.65, 0.50, 0.32, 1}, 0};
const ThermalSpec kRug{"rug", 22.0, 0.90, false, {0.50, 0.20, 0.20, 1}, 0};
const ThermalSpec kPaintedPlaster{"painted_plaster", 22.0, 0.93, false, {0.95, 0.95, 0.93, 1}, 0};

// ---------------------------------------------------------------------------------------------
// People.

// Joint positions of one posture (hoilcd frame; index 0 = left (+y), 1 = right (-y)).
struct Pose {
  std::string posture;
  Vec3 pelvis;  // spine base, at hip-joint height
  Mat3 torso;   // columns: forward, left, up of the torso
  Mat3 head;    // columns: forward, left, up of the head
  Vec3 elbow[2];
  Vec3 wrist[2];
  Vec3 hand_tip[2];  // fingertips
  Vec3 hand_up[2];   // back-of-hand direction
  Vec3 hip[2];
  Vec3 knee[2];
  Vec3 ankle[2];
  std::vector<Contact> contacts;
};

// Torso cross-sections: height above the pelvis, half width (left), half depth (forward),
// forward offset of the centre.
struct TorsoSection {
  double height;
  double half_width;
  double half_depth;
  double forward;
};

constexpr double kShoulderHeight = 0.44;  // shoulder joints above the pelvis along the spine
// Shoulder joints 0.33 m apart and shoulder caps 5 cm thick: 0.43 m across the shoulders
// (bideltoid breadth), between the adult means of women (~0.40 m) and men (~0.46 m).
constexpr double kShoulderHalfWidth = 0.165;

Vec3 Shoulder(const Pose& pose, int side) {
  const double sign = side == 0 ? 1.0 : -1.0;
  return pose.pelvis + pose.torso * Vec3(-0.01, sign * kShoulderHalfWidth, kShoulderHeight);
}

void AddPerson(AssetBuilder& asset, const Pose& pose) {
  const int skin = asset.Material(kSkin);
  const int hair = asset.Material(kHair);
  const int upper = asset.Material(kClothingUpper);
  const int lower = asset.Material(kClothingLower);
  const int shoes = asset.Material(kShoes);
  const Mat3& t = pose.torso;
  auto torso_point = [&](double forward, double left, double up) -> Vec3 {
    return pose.pelvis + t * Vec3(forward, left, up);
  };

  // Torso: a superelliptic loft from the hips to the shoulders.
  const TorsoSection sections[] = {
      {-0.03, 0.145, 0.100, -0.01}, {0.05, 0.155, 0.105, 0.00},   {0.15, 0.145, 0.100, 0.00},
      {0.26, 0.150, 0.110, 0.01},   {0.36, 0.162, 0.112, 0.01},   {0.42, 0.163, 0.100, 0.00},
      {0.46, 0.155, 0.088, -0.005}, {0.485, 0.125, 0.075, -0.01}, {0.505, 0.075, 0.062, -0.01}};
  std::vector<Ring> rings;
  for (const TorsoSection& s : sections) {
    rings.push_back({torso_point(s.forward, 0, s.height), t.col(1) * s.half_width, t.col(0) * s.half_depth});
  }
  asset.Add(Loft(rings, torso_point(-0.01, 0, -0.06), torso_point(-0.01, 0, 0.515), 32, 2.6), upper);

  // Pelvis and buttocks.
  asset.Add(Ellipsoid(torso_point(-0.01, 0, 0.0), t, Vec3(0.115, 0.15, 0.10), 24, 12), lower);

  // Neck and head (face and ears skin; top, back and sides of the skull hair).
  const Mat3& h = pose.head;
  const Vec3 neck_base = torso_point(-0.015, 0, 0.45);
  const Vec3 head_center = neck_base + h * Vec3(0.02, 0, 0.225);
  asset.Add(Capsule(neck_base, neck_base + h * Vec3(0.01, 0, 0.12), 0.062, 0.056, 20, 4), skin);
  const Vec3 head_radii(0.10, 0.083, 0.12);
  asset.Add(Ellipsoid(head_center, h, head_radii, 32, 20), [&](const Vec3& c, const Vec3&) {
    const Vec3 local = h.transpose() * (c - head_center);
    const double f = local.x() / head_radii.x();
    const double u = local.z() / head_radii.z();
    const bool is_hair = u > 0.45 || (f < 0.35 && u > 0.15) || (f < -0.15 && u > -0.55);
    return is_hair ? hair : skin;
  });
  asset.Add(Ellipsoid(head_center + h * Vec3(0.095, 0, -0.015), h, Vec3(0.025, 0.014, 0.032), 12, 8), skin);
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    asset.Add(Ellipsoid(head_center + h * Vec3(-0.005, sign * 0.081, -0.005), h, Vec3(0.02, 0.012, 0.032), 10, 6),
              skin);
  }

  for (int side = 0; side < 2; ++side) {
    const Vec3 shoulder = Shoulder(pose, side);
    // Shoulder cap, upper arm, forearm (long sleeves), hand.
    asset.Add(Ellipsoid(shoulder + t * Vec3(0, 0, -0.01), t, Vec3(0.06, 0.05, 0.055), 16, 10), upper);
    asset.Add(Capsule(shoulder, pose.elbow[side], 0.052, 0.042), upper);
    asset.Add(Capsule(pose.elbow[side], pose.wrist[side], 0.041, 0.031), upper);
    const Vec3 along = (pose.hand_tip[side] - pose.wrist[side]).normalized();
    const Vec3 back = (pose.hand_up[side] - pose.hand_up[side].dot(along) * along).normalized();
    Mat3 hand_axes;
    hand_axes.col(2) = along;
    hand_axes.col(0) = back;
    hand_axes.col(1) = along.cross(back);
    const double hand_half_length = (pose.hand_tip[side] - pose.wrist[side]).norm() / 2;
    asset.Add(Ellipsoid((pose.wrist[side] + pose.hand_tip[side]) / 2, hand_axes, Vec3(0.017, 0.043, hand_half_length),
                        16, 10),
              skin);
    // Thigh, shin (trousers), shoe.
    asset.Add(Capsule(pose.hip[side], pose.knee[side], 0.08, 0.055), lower);
    asset.Add(Capsule(pose.knee[side], pose.ankle[side], 0.05, 0.038), lower);
    const Vec3 shoe_center(pose.ankle[side].x() + 0.06, pose.ankle[side].y(), 0.045);
    asset.Add(Ellipsoid(shoe_center, Mat3::Identity(), Vec3(0.135, 0.05, 0.045), 16, 10), shoes);
  }
  asset.contacts = pose.contacts;
  asset.posture = pose.posture;
  asset.class_name = "person";
}

// Hips, legs and feet of every seated posture: seat top at 0.45 m, origin under the seat centre.
Pose SeatedLegs() {
  Pose pose;
  pose.pelvis = Vec3(-0.08, 0, 0.53);
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    pose.hip[side] = Vec3(-0.07, sign * 0.09, 0.53);
    pose.knee[side] = Vec3(0.35, sign * 0.10, 0.51);
    pose.ankle[side] = Vec3(0.39, sign * 0.11, 0.09);
    pose.contacts.push_back({"floor", Vec3(0.45, sign * 0.11, 0.0)});
  }
  pose.contacts.insert(pose.contacts.begin(), {"seat", Vec3(-0.05, 0, 0.45)});
  return pose;
}

Pose SeatedUpright() {
  Pose pose = SeatedLegs();
  pose.posture = "seated_upright";
  pose.torso = Mat3::Identity();
  pose.head = Mat3::Identity();
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    // Hands resting on the thighs.
    pose.elbow[side] = Vec3(-0.06, sign * 0.22, 0.72);
    pose.wrist[side] = Vec3(0.15, sign * 0.15, 0.655);
    pose.hand_tip[side] = Vec3(0.32, sign * 0.12, 0.635);
    pose.hand_up[side] = Vec3(0, 0, 1);
  }
  return pose;
}

Pose SeatedArmsOnTable() {
  Pose pose = SeatedLegs();
  pose.posture = "seated_arms_on_table";
  pose.torso = PitchForward(Deg(4));
  pose.head = PitchForward(Deg(8));
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    // Forearms on the table top (0.74 m, near edge at x = 0.30 m), hands flat near the middle.
    pose.elbow[side] = Vec3(0.19, sign * 0.22, 0.79);
    pose.wrist[side] = Vec3(0.45, sign * 0.13, 0.772);
    pose.hand_tip[side] = Vec3(0.62, sign * 0.10, 0.760);
    pose.hand_up[side] = Vec3(0, sign * 0.3, 1);
    pose.contacts.push_back({"table", Vec3(0.33, sign * 0.175, 0.74)});
  }
  return pose;
}

Pose SeatedLeaning() {
  Pose pose = SeatedLegs();
  pose.posture = "seated_leaning";
  pose.torso = PitchForward(Deg(20));
  pose.head = PitchForward(Deg(12));
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    // Elbows and forearms on the table top, hands meeting in front.
    pose.elbow[side] = Vec3(0.34, sign * 0.23, 0.785);
    pose.wrist[side] = Vec3(0.56, sign * 0.10, 0.772);
    pose.hand_tip[side] = Vec3(0.70, sign * 0.04, 0.760);
    pose.hand_up[side] = Vec3(0, sign * 0.3, 1);
    pose.contacts.push_back({"table", Vec3(0.40, sign * 0.195, 0.74)});
  }
  return pose;
}

Pose Standing() {
  Pose pose;
  pose.posture = "standing";
  pose.pelvis = Vec3(0, 0, 0.925);
  pose.torso = Mat3::Identity();
  pose.head = Mat3::Identity();
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    pose.hip[side] = Vec3(0, sign * 0.09, 0.92);
    pose.knee[side] = Vec3(0.015, sign * 0.10, 0.50);
    pose.ankle[side] = Vec3(-0.01, sign * 0.105, 0.09);
    pose.elbow[side] = Vec3(-0.03, sign * 0.225, 1.07);
    pose.wrist[side] = Vec3(0.0, sign * 0.225, 0.82);
    pose.hand_tip[side] = Vec3(0.01, sign * 0.215, 0.64);
    pose.hand_up[side] = Vec3(0, sign, 0);
    pose.contacts.push_back({"floor", Vec3(0.05, sign * 0.105, 0.0)});
  }
  return pose;
}

AssetBuilder Person(const std::string& name, const Pose& pose) {
  AssetBuilder asset;
  asset.name = name;
  AddPerson(asset, pose);
  return asset;
}

// The articulated person: one asset per rigid part, all modelled in the rest pose (standing,
// arms hanging straight, the body frame of person_standing) so that the files stacked together
// show the whole person. Each part carries the joint it turns about, its parent part and the
// COCO keypoints it holds (inside the part's surface, so they project onto the person).
struct RestSkeleton {
  Vec3 pelvis{0, 0, 0.925};
  Vec3 neck_base{-0.015, 0, 1.375};
  Vec3 neck_top{-0.005, 0, 1.495};
  Vec3 head_center{0.005, 0, 1.60};
  Vec3 shoulder[2], elbow[2], wrist[2], hand_tip[2], hip[2], knee[2], ankle[2];
  RestSkeleton() {
    for (int side = 0; side < 2; ++side) {
      const double sign = side == 0 ? 1.0 : -1.0;
      shoulder[side] = pelvis + Vec3(-0.01, sign * kShoulderHalfWidth, kShoulderHeight);
      elbow[side] = shoulder[side] + Vec3(0, sign * 0.015, -0.28);
      wrist[side] = elbow[side] + Vec3(0, 0, -0.25);
      hand_tip[side] = wrist[side] + Vec3(0, 0, -0.17);
      hip[side] = Vec3(0, sign * 0.09, 0.92);
      knee[side] = Vec3(0, sign * 0.09, 0.50);
      ankle[side] = Vec3(0, sign * 0.09, 0.09);
    }
  }
};

AssetBuilder Part(const std::string& part, const std::string& parent, const Vec3& joint) {
  AssetBuilder asset;
  asset.name = "person_part_" + part;
  asset.class_name = "person";
  asset.part = part;
  asset.parent = parent;
  asset.joint = joint;
  return asset;
}

// A limb part: one capsule from its joint to the next joint, in one material; `keypoint` (when
// not empty) names the COCO keypoint at the joint.
AssetBuilder LimbPart(const std::string& part, const std::string& parent, const Vec3& joint, const Vec3& end,
                      double joint_radius_m, double end_radius_m, const ThermalSpec& material,
                      const std::string& keypoint) {
  AssetBuilder limb = Part(part, parent, joint);
  limb.Add(Capsule(joint, end, joint_radius_m, end_radius_m), limb.Material(material));
  if (!keypoint.empty()) limb.keypoints.push_back({keypoint, joint});
  return limb;
}

// The head: skin with hair over the crown and back, nose and ears, the face's COCO keypoints.
AssetBuilder HeadPart(const RestSkeleton& rest) {
  const Mat3 I = Mat3::Identity();
  AssetBuilder head = Part("head", "neck", rest.neck_top);
  const int skin = head.Material(kSkin);
  const int hair = head.Material(kHair);
  const Vec3 head_radii(0.10, 0.083, 0.12);
  const Vec3 c = rest.head_center;
  head.Add(Ellipsoid(c, I, head_radii, 32, 20), [&](const Vec3& p, const Vec3&) {
    const Vec3 local = p - c;
    const double f = local.x() / head_radii.x();
    const double u = local.z() / head_radii.z();
    const bool is_hair = u > 0.45 || (f < 0.35 && u > 0.15) || (f < -0.15 && u > -0.55);
    return is_hair ? hair : skin;
  });
  head.Add(Ellipsoid(c + Vec3(0.095, 0, -0.015), I, Vec3(0.025, 0.014, 0.032), 12, 8), skin);
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    head.Add(Ellipsoid(c + Vec3(-0.005, sign * 0.081, -0.005), I, Vec3(0.02, 0.012, 0.032), 10, 6), skin);
  }
  head.keypoints = {{"nose", c + Vec3(0.09, 0, -0.015)},
                    {"left_eye", c + Vec3(0.075, 0.035, 0.025)},
                    {"right_eye", c + Vec3(0.075, -0.035, 0.025)},
                    {"left_ear", c + Vec3(-0.005, 0.075, -0.005)},
                    {"right_ear", c + Vec3(-0.005, -0.075, -0.005)}};
  return head;
}

// Arms, hands, legs and feet of both sides, appended to *parts.
void AddLimbParts(const RestSkeleton& rest, std::vector<AssetBuilder>* parts_out) {
  std::vector<AssetBuilder>& parts = *parts_out;
  const Mat3 I = Mat3::Identity();
  for (int side = 0; side < 2; ++side) {
    const std::string s = side == 0 ? "left" : "right";
    const double sign = side == 0 ? 1.0 : -1.0;
    parts.push_back(
        LimbPart("upper_arm_" + s, "torso", rest.shoulder[side], rest.elbow[side], 0.052, 0.042, kClothingUpper, ""));
    parts.push_back(LimbPart("lower_arm_" + s, "upper_arm_" + s, rest.elbow[side], rest.wrist[side], 0.041, 0.031,
                             kClothingUpper, s + "_elbow"));

    // The hand hangs with its back outwards (palm towards the thigh).
    AssetBuilder hand = Part("hand_" + s, "lower_arm_" + s, rest.wrist[side]);
    Mat3 hand_axes;
    hand_axes.col(2) = Vec3(0, 0, -1);
    hand_axes.col(0) = Vec3(0, sign, 0);
    hand_axes.col(1) = hand_axes.col(2).cross(hand_axes.col(0));
    hand.Add(Ellipsoid((rest.wrist[side] + rest.hand_tip[side]) / 2, hand_axes,
                       Vec3(0.017, 0.043, (rest.hand_tip[side] - rest.wrist[side]).norm() / 2), 16, 10),
             hand.Material(kSkin));
    hand.keypoints.push_back({s + "_wrist", rest.wrist[side] + Vec3(0, 0, -0.01)});
    parts.push_back(hand);

    parts.push_back(
        LimbPart("thigh_" + s, "pelvis", rest.hip[side], rest.knee[side], 0.08, 0.055, kClothingLower, s + "_hip"));
    parts.push_back(LimbPart("shin_" + s, "thigh_" + s, rest.knee[side], rest.ankle[side], 0.05, 0.038, kClothingLower,
                             s + "_knee"));

    AssetBuilder foot = Part("foot_" + s, "shin_" + s, rest.ankle[side]);
    foot.Add(
        Ellipsoid(Vec3(rest.ankle[side].x() + 0.06, rest.ankle[side].y(), 0.045), I, Vec3(0.135, 0.05, 0.045), 16, 10),
        foot.Material(kShoes));
    foot.keypoints.push_back({s + "_ankle", rest.ankle[side] + Vec3(0, 0, -0.03)});
    foot.contacts.push_back({"floor", Vec3(rest.ankle[side].x() + 0.06, rest.ankle[side].y(), 0.0)});
    parts.push_back(foot);
  }
}

std::vector<AssetBuilder> PersonParts() {
  const RestSkeleton rest;
  const Mat3 I = Mat3::Identity();
  std::vector<AssetBuilder> parts;

  AssetBuilder pelvis = Part("pelvis", "", rest.pelvis);
  pelvis.Add(Ellipsoid(rest.pelvis + Vec3(-0.01, 0, 0), I, Vec3(0.115, 0.15, 0.10), 24, 12),
             pelvis.Material(kClothingLower));
  parts.push_back(pelvis);

  AssetBuilder torso = Part("torso", "pelvis", rest.pelvis);
  const TorsoSection sections[] = {
      {0.02, 0.145, 0.100, -0.01},  {0.08, 0.155, 0.105, 0.00},   {0.15, 0.145, 0.100, 0.00},
      {0.26, 0.150, 0.110, 0.01},   {0.36, 0.162, 0.112, 0.01},   {0.42, 0.163, 0.100, 0.00},
      {0.46, 0.155, 0.088, -0.005}, {0.485, 0.125, 0.075, -0.01}, {0.505, 0.075, 0.062, -0.01}};
  std::vector<Ring> rings;
  for (const TorsoSection& s : sections) {
    rings.push_back({rest.pelvis + Vec3(s.forward, 0, s.height), Vec3(0, s.half_width, 0), Vec3(s.half_depth, 0, 0)});
  }
  const int upper = torso.Material(kClothingUpper);
  torso.Add(Loft(rings, rest.pelvis + Vec3(-0.01, 0, -0.01), rest.pelvis + Vec3(-0.01, 0, 0.515), 32, 2.6), upper);
  for (int side = 0; side < 2; ++side) {
    torso.Add(Ellipsoid(rest.shoulder[side] + Vec3(0, 0, -0.01), I, Vec3(0.06, 0.05, 0.055), 16, 10), upper);
    torso.keypoints.push_back({side == 0 ? "left_shoulder" : "right_shoulder", rest.shoulder[side]});
  }
  parts.push_back(torso);

  AssetBuilder neck = Part("neck", "torso", rest.neck_base);
  neck.Add(Capsule(rest.neck_base, rest.neck_top, 0.062, 0.056, 20, 4), neck.Material(kSkin));
  parts.push_back(neck);

  parts.push_back(HeadPart(rest));

  AddLimbParts(rest, &parts);
  return parts;
}

// ---------------------------------------------------------------------------------------------
// Furniture and hot objects.

// A wooden top 3 cm thick with its surface at 0.74 m (half sizes along x and y) on four metal legs
// at (±leg_x, ±leg_y).
AssetBuilder TableOnLegs(const std::string& name, double half_x, double half_y, double leg_x, double leg_y) {
  AssetBuilder asset;
  asset.name = name;
  asset.class_name = "table";
  const int wood = asset.Material(kWood);
  const int metal = asset.Material(kMetal);
  asset.Add(Box(Vec3(0, 0, 0.725), Mat3::Identity(), Vec3(half_x, half_y, 0.015)), wood);
  for (int i = 0; i < 4; ++i) {
    const double x = (i & 1) ? leg_x : -leg_x;
    const double y = (i & 2) ? leg_y : -leg_y;
    asset.Add(Rod(Vec3(x, y, 0), Vec3(x, y, 0.712), 0.02), metal);
  }
  return asset;
}

AssetBuilder Table() { return TableOnLegs("table", 0.45, 0.375, 0.40, 0.325); }

AssetBuilder Chair() {
  AssetBuilder asset;
  asset.name = "chair";
  asset.class_name = "chair";
  const int plastic = asset.Material(kPlastic);
  const int metal = asset.Material(kMetal);
  asset.Add(Box(Vec3(0, 0, 0.435), Mat3::Identity(), Vec3(0.21, 0.21, 0.015)), plastic);
  const Mat3 back_axes = PitchForward(Deg(-8));
  asset.Add(Box(Vec3(-0.235, 0, 0.72), back_axes, Vec3(0.015, 0.20, 0.13)), plastic);
  for (int i = 0; i < 4; ++i) {
    const double x = (i & 1) ? 0.18 : -0.18;
    const double y = (i & 2) ? 0.18 : -0.18;
    asset.Add(Rod(Vec3(x, y, 0), Vec3(x, y, 0.425), 0.012), metal);
  }
  for (int side = 0; side < 2; ++side) {
    const double y = side == 0 ? 0.17 : -0.17;
    asset.Add(Rod(Vec3(-0.18, y, 0.42), Vec3(-0.25, y, 0.84), 0.011), metal);
  }
  return asset;
}

// A round café table on one pedestal (knees fit all around): top Ø 0.90 m at 0.74 m.
AssetBuilder RoundTable() {
  AssetBuilder asset;
  asset.name = "round_table";
  asset.class_name = "table";
  const int wood = asset.Material(kWood);
  const int metal = asset.Material(kMetal);
  asset.Add(Lathe(Vec3::Zero(), {{0.45, 0.71}, {0.45, 0.74}}, 0.71, 0.74, 48), wood);
  asset.Add(Rod(Vec3(0, 0, 0.02), Vec3(0, 0, 0.71), 0.04), metal);
  asset.Add(Lathe(Vec3::Zero(), {{0.25, 0.0}, {0.25, 0.02}}, 0.0, 0.02, 32), metal);
  return asset;
}

// A square café table, 0.80 × 0.80 m, top at 0.74 m, four legs.
AssetBuilder SquareTable() { return TableOnLegs("square_table", 0.40, 0.40, 0.35, 0.35); }

// A desk for one or two people sitting on its -y side: 1.20 m along x × 0.60 m, top at 0.74 m,
// a modesty panel along the +y edge and two side panels.
AssetBuilder Desk() {
  AssetBuilder asset;
  asset.name = "desk";
  asset.class_name = "table";
  const int laminate = asset.Material(kLaminate);
  const int metal = asset.Material(kMetal);
  asset.Add(Box(Vec3(0, 0, 0.725), Mat3::Identity(), Vec3(0.60, 0.30, 0.015)), laminate);
  asset.Add(Box(Vec3(0, 0.27, 0.45), Mat3::Identity(), Vec3(0.56, 0.01, 0.25)), laminate);
  for (int side = 0; side < 2; ++side) {
    const double x = side == 0 ? -0.57 : 0.57;
    asset.Add(Box(Vec3(x, 0, 0.355), Mat3::Identity(), Vec3(0.015, 0.28, 0.355)), metal);
  }
  return asset;
}

// A three-seat sofa, faces +x (backrest at -x), 1.80 m along y × 0.85 m: seat cushions 0.55 m
// deep with their top at 0.45 m (a chair's), backrest to 0.85 m, arms to 0.62 m.
AssetBuilder Sofa() {
  AssetBuilder asset;
  asset.name = "sofa";
  asset.class_name = "sofa";
  const int cloth = asset.Material(kUpholstery);
  asset.Add(Box(Vec3(0.025, 0, 0.225), Mat3::Identity(), Vec3(0.275, 0.75, 0.225)), cloth);
  asset.Add(Box(Vec3(-0.35, 0, 0.425), Mat3::Identity(), Vec3(0.10, 0.90, 0.425)), cloth);
  for (int side = 0; side < 2; ++side) {
    const double y = side == 0 ? -0.825 : 0.825;
    asset.Add(Box(Vec3(0.025, y, 0.31), Mat3::Identity(), Vec3(0.275, 0.075, 0.31)), cloth);
  }
  return asset;
}

// A low coffee table, 1.00 m along x × 0.50 m, top at 0.42 m, four legs.
AssetBuilder LowTable() {
  AssetBuilder asset;
  asset.name = "low_table";
  asset.class_name = "table";
  const int wood = asset.Material(kWood);
  asset.Add(Box(Vec3(0, 0, 0.40), Mat3::Identity(), Vec3(0.50, 0.25, 0.02)), wood);
  for (int i = 0; i < 4; ++i) {
    const double x = (i & 1) ? 0.46 : -0.46;
    const double y = (i & 2) ? 0.21 : -0.21;
    asset.Add(Box(Vec3(x, y, 0.19), Mat3::Identity(), Vec3(0.025, 0.025, 0.19)), wood);
  }
  return asset;
}

// A freestanding office partition (a felt screen on two feet): 1.60 m along y × 0.05 m, 1.30 m tall.
AssetBuilder Partition() {
  AssetBuilder asset;
  asset.name = "partition";
  asset.class_name = "partition";
  const int felt = asset.Material(kFelt);
  const int metal = asset.Material(kMetal);
  asset.Add(Box(Vec3(0, 0, 0.70), Mat3::Identity(), Vec3(0.025, 0.80, 0.60)), felt);
  for (int side = 0; side < 2; ++side) {
    const double y = side == 0 ? -0.70 : 0.70;
    asset.Add(Box(Vec3(0, y, 0.05), Mat3::Identity(), Vec3(0.20, 0.03, 0.05)), metal);
  }
  return asset;
}

// A lectern: the speaker stands at +x; 0.60 m along y × 0.50 m, its sloped top 1.05-1.15 m high.
AssetBuilder Lectern() {
  AssetBuilder asset;
  asset.name = "lectern";
  asset.class_name = "lectern";
  const int wood = asset.Material(kWood);
  asset.Add(Box(Vec3(-0.05, 0, 0.50), Mat3::Identity(), Vec3(0.20, 0.28, 0.50)), wood);
  asset.Add(Box(Vec3(0, 0, 1.10), PitchForward(Deg(12)), Vec3(0.25, 0.30, 0.02)), wood);
  return asset;
}

AssetBuilder Cup() {
  AssetBuilder asset;
  asset.name = "cup";
  asset.class_name = "cup";
  const int ceramic = asset.Material(kCeramic);
  const int coffee = asset.Material(kCoffee);
  constexpr double kOuterRadius = 0.041;
  constexpr double kInnerRadius = 0.036;
  constexpr double kHeight = 0.085;
  constexpr double kCoffeeLevel = 0.068;
  const std::vector<Eigen::Vector2d> profile = {
      {kOuterRadius, 0.0}, {kOuterRadius, kHeight}, {kInnerRadius, kHeight}, {kInnerRadius, kCoffeeLevel}};
  asset.Add(Lathe(Vec3::Zero(), profile, 0.0, kCoffeeLevel, 40),
            [&](const Vec3& c, const Vec3&) { return std::abs(c.z() - kCoffeeLevel) < 1e-6 ? coffee : ceramic; });
  // Handle: a half torus on the -y side, ends sunk into the wall.
  std::vector<Ring> rings;
  constexpr int kSteps = 14;
  for (int i = 0; i <= kSteps; ++i) {
    const double a = -kPi / 2 + kPi * i / kSteps;
    const Vec3 center(0, -(0.036 + 0.022 * std::cos(a)), 0.043 + 0.025 * std::sin(a));
    const Vec3 radial = Vec3(0, -std::cos(a), std::sin(a));
    rings.push_back({center, Vec3(0.007, 0, 0), radial * 0.0055});
  }
  asset.Add(Loft(rings, rings.front().center, rings.back().center, 12), ceramic);
  return asset;
}

AssetBuilder Laptop() {
  AssetBuilder asset;
  asset.name = "laptop";
  asset.class_name = "laptop";
  const int base = asset.Material(kLaptopBase);
  const int lid = asset.Material(kLaptopLid);
  const int screen = asset.Material(kLaptopScreen);
  // Front (+x) is where the user sits; hinge at the back edge (x = -0.11 m).
  asset.Add(Box(Vec3(0, 0, 0.009), Mat3::Identity(), Vec3(0.11, 0.16, 0.009)), base);
  const Mat3 lid_axes = PitchForward(Deg(-20));  // opened to 110 degrees
  const Vec3 hinge(-0.11, 0, 0.018);
  const Vec3 lid_center = hinge + lid_axes * Vec3(0.0035, 0, 0.11);
  const Vec3 screen_normal = lid_axes.col(0);
  asset.Add(Box(lid_center, lid_axes, Vec3(0.0035, 0.16, 0.11)),
            [&](const Vec3&, const Vec3& n) { return n.dot(screen_normal) > 0.99 ? screen : lid; });
  return asset;
}

AssetBuilder Monitor() {
  AssetBuilder asset;
  asset.name = "monitor";
  asset.class_name = "monitor";
  const int back = asset.Material(kMonitorBack);
  const int screen = asset.Material(kMonitorScreen);
  const int plastic = asset.Material(kPlastic);
  // 24-inch panel facing +x (the viewer), on a neck and foot plate.
  asset.Add(Box(Vec3(0, 0, 0.29), Mat3::Identity(), Vec3(0.025, 0.27, 0.165)),
            [&](const Vec3&, const Vec3& n) { return n.x() > 0.99 ? screen : back; });
  asset.Add(Box(Vec3(-0.05, 0, 0.17), Mat3::Identity(), Vec3(0.02, 0.04, 0.16)), plastic);
  asset.Add(Box(Vec3(-0.03, 0, 0.0075), Mat3::Identity(), Vec3(0.09, 0.11, 0.0075)), plastic);
  return asset;
}

AssetBuilder Radiator() {
  AssetBuilder asset;
  asset.name = "radiator";
  asset.class_name = "radiator";
  const int hot = asset.Material(kRadiator);
  // Panel 1.0 m wide (y), 0.6 m high, 0.1 m deep, 0.15 m above the floor, front facing +x.
  asset.Add(Box(Vec3(0, 0, 0.45), Mat3::Identity(), Vec3(0.05, 0.50, 0.30)), hot);
  for (int side = 0; side < 2; ++side) {
    const double y = side == 0 ? 0.45 : -0.45;
    asset.Add(Rod(Vec3(0, y, 0), Vec3(0, y, 0.16), 0.011), hot);
  }
  return asset;
}

// ---------------------------------------------------------------------------------------------
// Room objects. Wall-mounted ones ("mount": "wall") have their origin on the wall at the bottom
// of their back face, centred along the wall, and face +x; hanging ones ("mount": "hanging")
// hang from their origin (a ceiling light's top face, a coat's fold over a chair's backrest).

AssetBuilder RoomObject(const std::string& name, const std::string& class_name, const std::string& mount) {
  AssetBuilder asset;
  asset.name = name;
  asset.class_name = class_name;
  asset.mount = mount;
  return asset;
}

// A box from `lo` to `hi` (axis-aligned corners).
Shape Slab(const Vec3& lo, const Vec3& hi) { return Box(0.5 * (lo + hi), Mat3::Identity(), 0.5 * (hi - lo)); }

// A whiteboard 1.80 m along the wall × 1.20 m: glossy board in a 25 mm anodized aluminium frame
// 20 mm deep, a pen tray along the bottom.
AssetBuilder Whiteboard() {
  AssetBuilder asset = RoomObject("whiteboard", "whiteboard", "wall");
  const int board = asset.Material(kWhiteboard);
  const int frame = asset.Material(kAnodized);
  asset.Add(Slab(Vec3(0, -0.875, 0.025), Vec3(0.015, 0.875, 1.175)), board);
  asset.Add(Slab(Vec3(0, -0.90, 1.175), Vec3(0.02, 0.90, 1.20)), frame);
  asset.Add(Slab(Vec3(0, -0.90, 0.0), Vec3(0.02, 0.90, 0.025)), frame);
  for (double y : {-0.8875, 0.8875}) asset.Add(Slab(Vec3(0, y - 0.0125, 0.025), Vec3(0.02, y + 0.0125, 1.175)), frame);
  asset.Add(Slab(Vec3(0.02, -0.35, 0.0), Vec3(0.08, 0.35, 0.02)), frame);
  return asset;
}

// A closed door in its frame: a 0.90 × 2.05 m clear opening (a scene's default doorway) with a
// painted architrave 70 mm wide round it and a lever handle at 1.05 m on the -y side.
AssetBuilder DoorFrame() {
  AssetBuilder asset = RoomObject("door_frame", "door", "wall");
  const int paint = asset.Material(kPaintedWood);
  const int leaf = asset.Material(kDoorLeaf);
  const int metal = asset.Material(kMetal);
  for (double y : {-0.485, 0.485}) asset.Add(Slab(Vec3(0, y - 0.035, 0), Vec3(0.015, y + 0.035, 2.05)), paint);
  asset.Add(Slab(Vec3(0, -0.52, 2.05), Vec3(0.015, 0.52, 2.12)), paint);
  asset.Add(Slab(Vec3(0, -0.45, 0), Vec3(0.006, 0.45, 2.05)), leaf);
  asset.Add(Rod(Vec3(0.006, -0.38, 1.05), Vec3(0.06, -0.38, 1.05), 0.008), metal);
  asset.Add(Rod(Vec3(0.055, -0.38, 1.05), Vec3(0.055, -0.26, 1.05), 0.008), metal);
  return asset;
}

// The indoor unit of a split air conditioner, 0.80 m along the wall × 0.28 m × 0.20 m deep, in
// cooling mode: the outlet louvre along the bottom front is cold.
AssetBuilder AcUnit() {
  AssetBuilder asset = RoomObject("ac_unit", "ac_unit", "wall");
  const int casing = asset.Material(kPlastic);
  const int louvre = asset.Material(kAcLouvre);
  asset.Add(Slab(Vec3(0, -0.40, 0.02), Vec3(0.20, 0.40, 0.28)), casing);
  asset.Add(Slab(Vec3(0.09, -0.34, 0.0), Vec3(0.19, 0.34, 0.03)), louvre);
  return asset;
}

// A light switch: an 86 × 86 mm plate with a rocker (ABS).
AssetBuilder LightSwitch() {
  AssetBuilder asset = RoomObject("light_switch", "switch", "wall");
  const int plastic = asset.Material(kPlastic);
  asset.Add(Slab(Vec3(0, -0.043, 0), Vec3(0.009, 0.043, 0.086)), plastic);
  asset.Add(Slab(Vec3(0.009, -0.025, 0.018), Vec3(0.016, 0.025, 0.068)), plastic);
  return asset;
}

// A double wall socket: two 86 × 86 mm plates side by side, each with its raised insert (ABS).
AssetBuilder WallSocket() {
  AssetBuilder asset = RoomObject("wall_socket", "socket", "wall");
  const int plastic = asset.Material(kPlastic);
  for (double y : {-0.043, 0.043}) {
    asset.Add(Slab(Vec3(0, y - 0.042, 0), Vec3(0.009, y + 0.042, 0.086)), plastic);
    asset.Add(Slab(Vec3(0.009, y - 0.022, 0.021), Vec3(0.014, y + 0.022, 0.065)), plastic);
  }
  return asset;
}

// A wall shelf: a wooden board 0.90 m × 0.25 m on two steel brackets 0.20 m high, with books
// standing at one end and a stack lying at the other.
AssetBuilder Shelf() {
  AssetBuilder asset = RoomObject("shelf", "shelf", "wall");
  const int wood = asset.Material(kWood);
  const int books = asset.Material(kBooks);
  const int metal = asset.Material(kMetal);
  asset.Add(Slab(Vec3(0, -0.45, 0.18), Vec3(0.25, 0.45, 0.20)), wood);
  for (double y : {-0.33, 0.33}) {
    asset.Add(Slab(Vec3(0, y - 0.006, 0), Vec3(0.01, y + 0.006, 0.18)), metal);
    asset.Add(Slab(Vec3(0.01, y - 0.006, 0.165), Vec3(0.20, y + 0.006, 0.18)), metal);
  }
  const double widths[] = {0.035, 0.05, 0.03, 0.045, 0.04, 0.06};
  const double heights[] = {0.24, 0.28, 0.22, 0.26, 0.24, 0.30};
  double y = -0.43;
  for (int i = 0; i < 6; ++i) {
    asset.Add(Slab(Vec3(0.02, y, 0.20), Vec3(0.21, y + widths[i] - 0.002, 0.20 + heights[i])), books);
    y += widths[i];
  }
  asset.Add(Slab(Vec3(0.03, 0.15, 0.20), Vec3(0.23, 0.41, 0.27)), books);
  return asset;
}

// A painted steel storage cabinet, 0.80 m along the wall × 0.42 m deep × 1.02 m, origin under its
// centre, doors facing +x with two handles, three box files on top.
AssetBuilder Cabinet() {
  AssetBuilder asset = RoomObject("cabinet", "cabinet", "");
  const int steel = asset.Material(kPaintedSteel);
  const int metal = asset.Material(kMetal);
  const int books = asset.Material(kBooks);
  asset.Add(Slab(Vec3(-0.21, -0.40, 0), Vec3(0.21, 0.40, 1.02)), steel);
  for (double y : {-0.04, 0.04}) asset.Add(Rod(Vec3(0.225, y, 0.55), Vec3(0.225, y, 0.75), 0.008), metal);
  for (int i = 0; i < 3; ++i) {
    const double y = -0.30 + 0.085 * i;
    asset.Add(Slab(Vec3(-0.15, y, 1.02), Vec3(0.17, y + 0.08, 1.34)), books);
  }
  return asset;
}

// A surface-mounted LED panel, 0.60 × 0.60 m and 41 mm deep, hanging from its top face: a warm
// painted aluminium frame round the diffuser.
AssetBuilder CeilingLight() {
  AssetBuilder asset = RoomObject("ceiling_light", "ceiling_light", "hanging");
  const int frame = asset.Material(kLightFrame);
  const int diffuser = asset.Material(kLightDiffuser);
  asset.Add(Slab(Vec3(-0.30, -0.30, -0.040), Vec3(0.30, 0.30, 0.0)), frame);
  asset.Add(Slab(Vec3(-0.285, -0.285, -0.041), Vec3(0.285, 0.285, -0.02)), diffuser);
  return asset;
}

// A soft shoulder bag standing on the floor, 0.32 m long (x) × 0.14 m × 0.36 m with a strap.
AssetBuilder Bag() {
  AssetBuilder asset = RoomObject("bag", "bag", "");
  const int fabric = asset.Material(kBagFabric);
  std::vector<Ring> rings;
  for (const auto& [z, scale] :
       std::vector<std::pair<double, double>>{{0.0, 0.92}, {0.04, 1.0}, {0.30, 1.0}, {0.36, 0.85}}) {
    rings.push_back({Vec3(0, 0, z), Vec3(0.16 * scale, 0, 0), Vec3(0, 0.07 * scale, 0)});
  }
  asset.Add(Loft(rings, Vec3(0, 0, 0), Vec3(0, 0, 0.36), 16, 4.0), fabric);
  asset.Add(Rod(Vec3(-0.12, 0, 0.34), Vec3(-0.10, 0, 0.48), 0.008, 8), fabric);
  asset.Add(Rod(Vec3(-0.11, 0, 0.48), Vec3(0.11, 0, 0.48), 0.008, 8), fabric);
  asset.Add(Rod(Vec3(0.10, 0, 0.48), Vec3(0.12, 0, 0.34), 0.008, 8), fabric);
  return asset;
}

// A coat folded over a chair's backrest: its origin is on the backrest's top edge (chair.gltf:
// 0.253 m behind the seat centre, 0.86 m up); most of it hangs 0.45 m down behind the backrest.
AssetBuilder Coat() {
  AssetBuilder asset = RoomObject("coat", "coat", "hanging");
  const int cloth = asset.Material(kCoat);
  asset.Add(Capsule(Vec3(-0.01, -0.20, 0.02), Vec3(-0.01, 0.20, 0.02), 0.022, 0.022, 10, 2), cloth);
  asset.Add(Slab(Vec3(-0.06, -0.21, -0.45), Vec3(-0.022, 0.21, 0.0)), cloth);
  asset.Add(Slab(Vec3(0.03, -0.19, -0.07), Vec3(0.042, 0.19, 0.01)), cloth);
  return asset;
}

// A laptop power brick lying on a table, 0.11 × 0.05 × 0.03 m, warm under load.
AssetBuilder Charger() {
  AssetBuilder asset = RoomObject("charger", "charger", "");
  const int brick = asset.Material(kCharger);
  asset.Add(Slab(Vec3(-0.055, -0.025, 0), Vec3(0.055, 0.025, 0.03)), brick);
  return asset;
}

// ---------------------------------------------------------------------------------------------
// The clutter of lived-in rooms: things on desks, on walls, on floors, on ceilings and on shelves.

// A closed cylinder with flat ends from `a` to `b`.
Shape Cylinder(const Vec3& a, const Vec3& b, double radius, int around) {
  const Vec3 w = (b - a).normalized();
  const Vec3 u = Perpendicular(w) * radius;
  const Vec3 v = w.cross(u.normalized()) * radius;
  return Loft({{a, u, v}, {b, u, v}}, a, b, around);
}

// The shape without its downward-facing triangles (a rug's underside lies on the floor).
Shape WithoutUnderside(const Shape& shape) {
  Shape out;
  out.positions = shape.positions;
  for (size_t t = 0; t < shape.indices.size(); t += 3) {
    const Vec3& a = shape.positions[shape.indices[t]];
    const Vec3& b = shape.positions[shape.indices[t + 1]];
    const Vec3& c = shape.positions[shape.indices[t + 2]];
    if ((b - a).cross(c - a).normalized().z() < -0.99) continue;
    out.indices.insert(out.indices.end(), {shape.indices[t], shape.indices[t + 1], shape.indices[t + 2]});
  }
  return out;
}

// A desktop PC tower standing on the floor, 0.45 m deep (x, front at +x) × 0.20 m × 0.45 m, its
// exhaust grille high on the back.
AssetBuilder PcTower() {
  AssetBuilder asset = RoomObject("pc_tower", "pc", "");
  const int body = asset.Material(kPcCase);
  const int exhaust = asset.Material(kPcExhaust);
  asset.Add(Slab(Vec3(-0.225, -0.10, 0), Vec3(0.225, 0.10, 0.45)), body);
  asset.Add(Slab(Vec3(-0.232, -0.06, 0.29), Vec3(-0.225, 0.06, 0.41)), exhaust);
  return asset;
}

// A desk phone, 0.20 m deep × 0.22 m, its keypad sloping up towards the back, the handset on
// its left (-y).
AssetBuilder DeskPhone() {
  AssetBuilder asset = RoomObject("desk_phone", "phone", "");
  const int phone = asset.Material(kPhone);
  asset.Add(Slab(Vec3(-0.10, -0.11, 0), Vec3(0.10, 0.11, 0.03)), phone);
  asset.Add(Box(Vec3(-0.01, 0.02, 0.045), PitchForward(Deg(-15)), Vec3(0.085, 0.075, 0.018)), phone);
  asset.Add(Capsule(Vec3(-0.075, -0.075, 0.055), Vec3(0.075, -0.075, 0.055), 0.022, 0.022, 10, 2), phone);
  return asset;
}

// A six-way power strip, 0.30 × 0.056 × 0.04 m, with its switch at one end.
AssetBuilder PowerStrip() {
  AssetBuilder asset = RoomObject("power_strip", "power_strip", "");
  const int plastic = asset.Material(kPlastic);
  asset.Add(Slab(Vec3(-0.028, -0.15, 0), Vec3(0.028, 0.15, 0.04)), plastic);
  asset.Add(Slab(Vec3(-0.012, 0.115, 0.04), Vec3(0.012, 0.14, 0.048)), plastic);
  return asset;
}

// An empty mug left on a desk: Ø 8.2 cm, 9.5 cm tall, handle at -y.
AssetBuilder Mug() {
  AssetBuilder asset = RoomObject("mug", "mug", "");
  const int mug = asset.Material(kMug);
  asset.Add(Lathe(Vec3::Zero(), {{0.041, 0.0}, {0.041, 0.095}, {0.037, 0.095}, {0.037, 0.008}}, 0.0, 0.008, 20), mug);
  std::vector<Ring> rings;
  constexpr int kSteps = 8;
  for (int i = 0; i <= kSteps; ++i) {
    const double a = -kPi / 2 + kPi * i / kSteps;
    const Vec3 center(0, -(0.037 + 0.024 * std::cos(a)), 0.048 + 0.027 * std::sin(a));
    rings.push_back({center, Vec3(0.007, 0, 0), Vec3(0, -std::cos(a), std::sin(a)) * 0.0055});
  }
  asset.Add(Loft(rings, rings.front().center, rings.back().center, 8), mug);
  return asset;
}

// A half-litre water bottle, Ø 6.6 cm, 0.225 m tall with its cap.
AssetBuilder Bottle() {
  AssetBuilder asset = RoomObject("bottle", "bottle", "");
  const int bottle = asset.Material(kBottle);
  asset.Add(
      Lathe(Vec3::Zero(),
            {{0.031, 0.0}, {0.033, 0.01}, {0.033, 0.15}, {0.022, 0.185}, {0.014, 0.20}, {0.015, 0.20}, {0.015, 0.225}},
            0.0, 0.225, 16),
      bottle);
  return asset;
}

// A stack of A4 paper, 2 cm high, its top sheet askew.
AssetBuilder Papers() {
  AssetBuilder asset = RoomObject("papers", "papers", "");
  const int paper = asset.Material(kPaper);
  asset.Add(Slab(Vec3(-0.105, -0.1485, 0), Vec3(0.105, 0.1485, 0.02)), paper);
  asset.Add(
      Box(Vec3(0.0, 0.0, 0.0205), Eigen::AngleAxisd(Deg(8), Vec3::UnitZ()).toRotationMatrix(), Vec3(0.1, 0.14, 0.0005)),
      paper);
  return asset;
}

// Five lever-arch binders standing side by side, spines at +x: 0.29 m deep × 0.39 m × 0.32 m.
AssetBuilder BinderRow() {
  AssetBuilder asset = RoomObject("binder_row", "binders", "");
  const int binder = asset.Material(kBinder);
  for (int i = 0; i < 5; ++i) {
    const double y = -0.195 + 0.078 * i;
    asset.Add(Slab(Vec3(-0.145, y + 0.001, 0), Vec3(0.145, y + 0.077, 0.32)), binder);
  }
  return asset;
}

// Nine books standing side by side, spines at +x, 0.34 m along y, 0.20 to 0.28 m tall.
AssetBuilder BookRow() {
  AssetBuilder asset = RoomObject("book_row", "books", "");
  const int books = asset.Material(kBooks);
  const double widths[] = {0.03, 0.045, 0.025, 0.04, 0.035, 0.05, 0.03, 0.04, 0.045};
  const double heights[] = {0.24, 0.28, 0.21, 0.26, 0.23, 0.27, 0.20, 0.25, 0.24};
  const double depths[] = {0.17, 0.20, 0.15, 0.19, 0.16, 0.20, 0.15, 0.18, 0.17};
  double y = -0.17;
  for (int i = 0; i < 9; ++i) {
    asset.Add(Slab(Vec3(0.10 - depths[i], y + 0.001, 0), Vec3(0.10, y + widths[i] - 0.001, heights[i])), books);
    y += widths[i];
  }
  return asset;
}

// An open wooden bookcase against a wall, 0.32 m deep (x, open at +x) × 0.80 m × 1.80 m, with a
// back panel and shelf boards whose tops are at 0.22, 0.62, 1.02, 1.42 and 1.80 m (the top).
AssetBuilder Bookcase() {
  AssetBuilder asset = RoomObject("bookcase", "bookcase", "");
  const int wood = asset.Material(kWood);
  for (double y : {-0.391, 0.391}) asset.Add(Slab(Vec3(-0.16, y - 0.009, 0), Vec3(0.16, y + 0.009, 1.78)), wood);
  asset.Add(Slab(Vec3(-0.16, -0.382, 0), Vec3(-0.152, 0.382, 1.78)), wood);
  asset.Add(Slab(Vec3(0.14, -0.382, 0), Vec3(0.16, 0.382, 0.202)), wood);  // the plinth
  for (double top : {0.22, 0.62, 1.02, 1.42})
    asset.Add(Slab(Vec3(-0.152, -0.382, top - 0.018), Vec3(0.16, 0.382, top)), wood);
  asset.Add(Slab(Vec3(-0.16, -0.40, 1.78), Vec3(0.16, 0.40, 1.80)), wood);
  return asset;
}

// An A1 poster (0.594 × 0.841 m) on the wall.
AssetBuilder Poster() {
  AssetBuilder asset = RoomObject("poster", "poster", "wall");
  asset.Add(Slab(Vec3(0, -0.297, 0), Vec3(0.002, 0.297, 0.841)), asset.Material(kPoster));
  return asset;
}

// A framed picture 0.50 × 0.40 m behind glass, 27 mm deep.
AssetBuilder FramedPicture() {
  AssetBuilder asset = RoomObject("framed_picture", "picture", "wall");
  const int frame = asset.Material(kPaintedWood);
  const int glass = asset.Material(kGlass);
  asset.Add(Slab(Vec3(0, -0.25, 0), Vec3(0.025, 0.25, 0.40)), frame);
  asset.Add(Slab(Vec3(0.025, -0.22, 0.03), Vec3(0.027, 0.22, 0.37)), glass);
  return asset;
}

// A wall clock, Ø 0.30 m and 4 cm deep: a plastic rim round a glass face.
AssetBuilder WallClock() {
  AssetBuilder asset = RoomObject("wall_clock", "clock", "wall");
  const int rim = asset.Material(kPlastic);
  const int glass = asset.Material(kGlass);
  asset.Add(Cylinder(Vec3(0, 0, 0.15), Vec3(0.04, 0, 0.15), 0.15, 24),
            [&](const Vec3&, const Vec3& n) { return n.x() > 0.99 ? glass : rim; });
  return asset;
}

// A notice board 0.90 × 0.60 m: a fabric pin board in a wooden frame with four A4 sheets pinned on.
AssetBuilder NoticeBoard() {
  AssetBuilder asset = RoomObject("notice_board", "notice_board", "wall");
  const int wood = asset.Material(kWood);
  const int board = asset.Material(kPinboard);
  const int paper = asset.Material(kPaper);
  asset.Add(Slab(Vec3(0, -0.45, 0), Vec3(0.02, 0.45, 0.60)), wood);
  asset.Add(Slab(Vec3(0.02, -0.43, 0.02), Vec3(0.022, 0.43, 0.58)), board);
  const double sheets[][2] = {{-0.40, 0.26}, {-0.15, 0.22}, {0.12, 0.27}, {0.20, 0.04}};
  for (const auto& s : sheets) asset.Add(Slab(Vec3(0.022, s[0], s[1]), Vec3(0.0235, s[0] + 0.21, s[1] + 0.297)), paper);
  return asset;
}

// A room thermostat, 80 × 80 × 25 mm.
AssetBuilder Thermostat() {
  AssetBuilder asset = RoomObject("thermostat", "thermostat", "wall");
  asset.Add(Slab(Vec3(0, -0.04, 0), Vec3(0.025, 0.04, 0.08)), asset.Material(kPlastic));
  return asset;
}

// A 600 × 600 mm square ceiling diffuser hanging from its top face: a painted frame, the vanes
// the supply air leaves through, a painted centre plate.
AssetBuilder CeilingDiffuser() {
  AssetBuilder asset = RoomObject("ceiling_diffuser", "diffuser", "hanging");
  const int steel = asset.Material(kPaintedSteel);
  const int vanes = asset.Material(kSupplyAir);
  asset.Add(Slab(Vec3(-0.30, -0.30, -0.02), Vec3(0.30, 0.30, 0)), steel);
  asset.Add(Slab(Vec3(-0.24, -0.24, -0.045), Vec3(0.24, 0.24, -0.02)), vanes);
  asset.Add(Slab(Vec3(-0.10, -0.10, -0.06), Vec3(0.10, 0.10, -0.045)), steel);
  return asset;
}

// A supply-air wall grille 0.40 × 0.15 m, its louvres in the supply air.
AssetBuilder SupplyGrille() {
  AssetBuilder asset = RoomObject("supply_grille", "grille", "wall");
  const int steel = asset.Material(kPaintedSteel);
  const int vanes = asset.Material(kSupplyAir);
  asset.Add(Slab(Vec3(0, -0.20, 0), Vec3(0.02, 0.20, 0.15)), steel);
  asset.Add(Slab(Vec3(0.02, -0.18, 0.015), Vec3(0.025, 0.18, 0.135)), vanes);
  return asset;
}

// A return-air wall grille 0.40 × 0.30 m with six horizontal slats, all at the room's air.
AssetBuilder ReturnGrille() {
  AssetBuilder asset = RoomObject("return_grille", "grille", "wall");
  const int steel = asset.Material(kPaintedSteel);
  asset.Add(Slab(Vec3(0, -0.20, 0), Vec3(0.015, 0.20, 0.30)), steel);
  for (int i = 0; i < 6; ++i) {
    const double z = 0.035 + 0.045 * i;
    asset.Add(Slab(Vec3(0.015, -0.18, z), Vec3(0.03, 0.18, z + 0.012)), steel);
  }
  return asset;
}

// One metre of a heating pipe run along a wall: the flow pipe over the return, both Ø 22 mm,
// 45 mm off the wall on two clips. Runs are placed end to end.
AssetBuilder HeatingPipe() {
  AssetBuilder asset = RoomObject("heating_pipe", "pipe", "wall");
  const int flow = asset.Material(kHeatingFlow);
  const int ret = asset.Material(kHeatingReturn);
  const int clip = asset.Material(kPlastic);
  asset.Add(Cylinder(Vec3(0.045, -0.5, 0.105), Vec3(0.045, 0.5, 0.105), 0.011, 10), flow);
  asset.Add(Cylinder(Vec3(0.045, -0.5, 0.035), Vec3(0.045, 0.5, 0.035), 0.011, 10), ret);
  for (double y : {-0.25, 0.25}) asset.Add(Slab(Vec3(0, y - 0.01, 0), Vec3(0.035, y + 0.01, 0.13)), clip);
  return asset;
}

// One metre of PVC cable trunking, 60 mm high and 40 mm deep. Runs are placed end to end.
AssetBuilder CableTrunking() {
  AssetBuilder asset = RoomObject("cable_trunking", "trunking", "wall");
  asset.Add(Slab(Vec3(0, -0.5, 0), Vec3(0.04, 0.5, 0.06)), asset.Material(kPlastic));
  return asset;
}

// A painted skirting board 80 mm high and 15 mm deep, `length_m` long.
AssetBuilder SkirtingBoard(const std::string& name, double length_m) {
  AssetBuilder asset = RoomObject(name, "skirting", "wall");
  asset.Add(Slab(Vec3(0, -0.5 * length_m, 0), Vec3(0.015, 0.5 * length_m, 0.08)), asset.Material(kPaintedWood));
  return asset;
}

// 0.20 m of a painted window sill, 0.16 m deep and 30 mm thick. Sills are placed end to end under
// a window, their tops at its bottom edge.
AssetBuilder WindowSill() {
  AssetBuilder asset = RoomObject("window_sill", "sill", "wall");
  asset.Add(Slab(Vec3(0, -0.10, 0), Vec3(0.16, 0.10, 0.03)), asset.Material(kPaintedWood));
  return asset;
}

// 0.20 m of a roller blind: the cassette 70 mm square over the window and the fabric hanging
// 0.60 m down 5 cm in front of the glass, with its bottom rail. Placed end to end across a window.
AssetBuilder Blind() {
  AssetBuilder asset = RoomObject("blind", "blind", "wall");
  const int steel = asset.Material(kPaintedSteel);
  const int fabric = asset.Material(kBlindFabric);
  asset.Add(Slab(Vec3(0, -0.10, 0.60), Vec3(0.07, 0.10, 0.67)), steel);
  asset.Add(Slab(Vec3(0.05, -0.10, 0.02), Vec3(0.052, 0.10, 0.60)), fabric);
  asset.Add(Slab(Vec3(0.045, -0.10, 0), Vec3(0.058, 0.10, 0.02)), steel);
  return asset;
}

// A round waste bin, Ø 0.30 m at the rim and 0.35 m tall, open at the top.
AssetBuilder Bin() {
  AssetBuilder asset = RoomObject("bin", "bin", "");
  asset.Add(Lathe(Vec3::Zero(), {{0.13, 0.0}, {0.15, 0.35}, {0.142, 0.35}, {0.122, 0.01}}, 0.0, 0.01, 20),
            asset.Material(kPlastic));
  return asset;
}

// A closed cardboard box, 0.40 × 0.30 × 0.30 m.
AssetBuilder CardboardBox() {
  AssetBuilder asset = RoomObject("cardboard_box", "box", "");
  const int board = asset.Material(kCardboard);
  asset.Add(Slab(Vec3(-0.20, -0.15, 0), Vec3(0.20, 0.15, 0.30)), board);
  asset.Add(Slab(Vec3(-0.20, -0.025, 0.30), Vec3(0.20, 0.025, 0.301)), board);
  return asset;
}

// A rug 1.60 × 1.20 m and 10 mm thick lying on the floor (the robot drives over it).
AssetBuilder Rug() {
  AssetBuilder asset = RoomObject("rug", "rug", "");
  asset.Add(WithoutUnderside(Slab(Vec3(-0.80, -0.60, 0), Vec3(0.80, 0.60, 0.01))), asset.Material(kRug));
  return asset;
}

// A smoke detector on the ceiling, Ø 0.11 m and 50 mm deep, hanging from its top face.
AssetBuilder SmokeDetector() {
  AssetBuilder asset = RoomObject("smoke_detector", "detector", "hanging");
  asset.Add(Lathe(Vec3(0, 0, -0.05), {{0.045, 0.0}, {0.055, 0.015}, {0.055, 0.05}}, 0.0, 0.05, 16),
            asset.Material(kPlastic));
  return asset;
}

// A pendent sprinkler head: a Ø 70 mm escutcheon on the ceiling, the body and its deflector
// 60 mm below.
AssetBuilder Sprinkler() {
  AssetBuilder asset = RoomObject("sprinkler", "sprinkler", "hanging");
  const int metal = asset.Material(kMetal);
  asset.Add(Cylinder(Vec3(0, 0, -0.008), Vec3(0, 0, 0), 0.035, 16), metal);
  asset.Add(Cylinder(Vec3(0, 0, -0.05), Vec3(0, 0, -0.008), 0.008, 8), metal);
  asset.Add(Cylinder(Vec3(0, 0, -0.06), Vec3(0, 0, -0.055), 0.016, 12), metal);
  asset.Add(Slab(Vec3(-0.012, -0.003, -0.058), Vec3(0.012, 0.003, -0.05)), metal);
  return asset;
}

// One metre of a painted plasterboard bulkhead boxing in a duct along a wall: 0.40 m wide (x)
// and 0.25 m deep, hanging from its top face. Runs are placed end to end.
AssetBuilder Bulkhead() {
  AssetBuilder asset = RoomObject("bulkhead", "bulkhead", "hanging");
  asset.Add(Slab(Vec3(-0.20, -0.5, -0.25), Vec3(0.20, 0.5, 0)), asset.Material(kPaintedPlaster));
  return asset;
}

// A Wi-Fi router, 0.14 m deep × 0.20 m × 35 mm, two antennas up at its back.
AssetBuilder Router() {
  AssetBuilder asset = RoomObject("router", "router", "");
  const int router = asset.Material(kRouter);
  asset.Add(Slab(Vec3(-0.07, -0.10, 0), Vec3(0.07, 0.10, 0.035)), router);
  for (double y : {-0.08, 0.08}) asset.Add(Cylinder(Vec3(-0.06, y, 0.035), Vec3(-0.06, y, 0.18), 0.006, 8), router);
  return asset;
}

// ---------------------------------------------------------------------------------------------
// glTF output.

tinygltf::Value Vec3Value(const Vec3& p_hoilcd) {
  const Vec3 p(p_hoilcd.y(), p_hoilcd.z(), p_hoilcd.x());
  return tinygltf::Value(
      tinygltf::Value::Array{tinygltf::Value(p.x()), tinygltf::Value(p.y()), tinygltf::Value(p.z())});
}

// Rounds to 0.1 mm so the JSON stays readable.
double Round(double value) { return std::round(value * 1e4) / 1e4; }
Vec3 Rounded(const Vec3& p) { return Vec3(Round(p.x()), Round(p.y()), Round(p.z())); }

int AddBufferView(tinygltf::Model& model, const void* data, size_t size, int target) {
  std::vector<unsigned char>& bytes = model.buffers[0].data;
  const size_t offset = bytes.size();
  bytes.resize(offset + size);
  std::memcpy(bytes.data() + offset, data, size);
  bytes.resize((bytes.size() + 3) / 4 * 4, 0);  // keep every view 4-byte aligned
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = size;
  view.target = target;
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size() - 1);
}

// A material with its thermal properties in extras.
tinygltf::Material GltfMaterial(const ThermalSpec& spec) {
  tinygltf::Material material;
  material.name = spec.region;
  material.pbrMetallicRoughness.baseColorFactor.assign(spec.base_color.begin(), spec.base_color.end());
  material.pbrMetallicRoughness.metallicFactor = spec.metallic;
  material.pbrMetallicRoughness.roughnessFactor = spec.specular ? 0.2 : 0.8;
  tinygltf::Value::Object extras{{"temperature_c", tinygltf::Value(spec.temperature_c)},
                                 {"emissivity", tinygltf::Value(spec.emissivity)},
                                 {"specular", tinygltf::Value(spec.specular)},
                                 {"region", tinygltf::Value(spec.region)}};
  if (spec.power_w > 0) extras["power_w"] = tinygltf::Value(spec.power_w);
  material.extras = tinygltf::Value(extras);
  return material;
}

// One part's triangles as a primitive of material `material`: positions (hoilcd x, y, z to
// glTF's z, x, y) and indices (16-bit when they fit) appended to the model's buffer.
tinygltf::Primitive GltfPrimitive(const Shape& part, int material, tinygltf::Model* model) {
  std::vector<float> positions;
  std::vector<double> lo(3, 1e9);
  std::vector<double> hi(3, -1e9);
  for (const Vec3& p_hoilcd : part.positions) {
    const float gltf[3] = {static_cast<float>(p_hoilcd.y()), static_cast<float>(p_hoilcd.z()),
                           static_cast<float>(p_hoilcd.x())};
    for (int k = 0; k < 3; ++k) {
      positions.push_back(gltf[k]);
      lo[static_cast<size_t>(k)] = std::min(lo[static_cast<size_t>(k)], double{gltf[k]});
      hi[static_cast<size_t>(k)] = std::max(hi[static_cast<size_t>(k)], double{gltf[k]});
    }
  }
  tinygltf::Accessor position_accessor;
  position_accessor.bufferView =
      AddBufferView(*model, positions.data(), positions.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
  position_accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  position_accessor.type = TINYGLTF_TYPE_VEC3;
  position_accessor.count = part.positions.size();
  position_accessor.minValues = lo;
  position_accessor.maxValues = hi;
  model->accessors.push_back(position_accessor);
  const int position_index = static_cast<int>(model->accessors.size() - 1);

  tinygltf::Accessor index_accessor;
  if (part.positions.size() < 65536) {
    const std::vector<uint16_t> indices(part.indices.begin(), part.indices.end());
    index_accessor.bufferView =
        AddBufferView(*model, indices.data(), indices.size() * 2, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    index_accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  } else {
    index_accessor.bufferView =
        AddBufferView(*model, part.indices.data(), part.indices.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    index_accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  }
  index_accessor.type = TINYGLTF_TYPE_SCALAR;
  index_accessor.count = part.indices.size();
  model->accessors.push_back(index_accessor);

  tinygltf::Primitive primitive;
  primitive.attributes["POSITION"] = position_index;
  primitive.indices = static_cast<int>(model->accessors.size() - 1);
  primitive.material = material;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  return primitive;
}

// The scene's extras: class, posture, contact points, and for a body part its name, parent,
// joint and keypoints.
tinygltf::Value SceneExtras(const AssetBuilder& asset) {
  tinygltf::Value::Object extras{{"class", tinygltf::Value(asset.class_name)}};
  if (!asset.posture.empty()) extras["posture"] = tinygltf::Value(asset.posture);
  if (!asset.mount.empty()) extras["mount"] = tinygltf::Value(asset.mount);
  auto points = [](const std::vector<Contact>& list) {
    tinygltf::Value::Array out;
    for (const Contact& contact : list) {
      out.push_back(tinygltf::Value(tinygltf::Value::Object{{"name", tinygltf::Value(contact.name)},
                                                            {"position", Vec3Value(Rounded(contact.position))}}));
    }
    return tinygltf::Value(out);
  };
  if (!asset.contacts.empty()) extras["contacts"] = points(asset.contacts);
  if (!asset.part.empty()) {
    extras["part"] = tinygltf::Value(asset.part);
    if (!asset.parent.empty()) extras["parent"] = tinygltf::Value(asset.parent);
    extras["joint"] = Vec3Value(Rounded(asset.joint));
    if (!asset.keypoints.empty()) extras["keypoints"] = points(asset.keypoints);
  }
  return tinygltf::Value(extras);
}

tinygltf::Model ToGltf(const AssetBuilder& asset) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "hoilcd make_assets";
  model.buffers.emplace_back();
  tinygltf::Mesh mesh;
  mesh.name = asset.name;
  for (size_t m = 0; m < asset.materials.size(); ++m) {
    model.materials.push_back(GltfMaterial(asset.materials[m]));
    if (asset.parts[m].indices.empty()) continue;
    mesh.primitives.push_back(GltfPrimitive(asset.parts[m], static_cast<int>(m), &model));
  }
  model.buffers[0].name = asset.name;
  model.meshes.push_back(mesh);

  tinygltf::Node node;
  node.name = asset.name;
  node.mesh = 0;
  model.nodes.push_back(node);

  tinygltf::Scene scene;
  scene.name = asset.name;
  scene.nodes.push_back(0);
  scene.extras = SceneExtras(asset);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  return model;
}

size_t TriangleCount(const AssetBuilder& asset) {
  size_t count = 0;
  for (const Shape& part : asset.parts) count += part.indices.size() / 3;
  return count;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_assets OUT_DIR\n";
    return 2;
  }
  const std::string out_dir = argv[1];
  std::vector<AssetBuilder> assets = {Person("person_seated_upright", SeatedUpright()),
                                      Person("person_seated_leaning", SeatedLeaning()),
                                      Person("person_seated_arms_on_table", SeatedArmsOnTable()),
                                      Person("person_standing", Standing()),
                                      Table(),
                                      Chair(),
                                      Cup(),
                                      Laptop(),
                                      Monitor(),
                                      Radiator(),
                                      RoundTable(),
                                      SquareTable(),
                                      Desk(),
                                      Sofa(),
                                      LowTable(),
                                      Partition(),
                                      Lectern(),
                                      Whiteboard(),
                                      DoorFrame(),
                                      AcUnit(),
                                      LightSwitch(),
                                      WallSocket(),
                                      Shelf(),
                                      Cabinet(),
                                      CeilingLight(),
                                      Bag(),
                                      Coat(),
                                      Charger(),
                                      PcTower(),
                                      DeskPhone(),
                                      PowerStrip(),
                                      Mug(),
                                      Bottle(),
                                      Papers(),
                                      BinderRow(),
                                      BookRow(),
                                      Bookcase(),
                                      Poster(),
                                      FramedPicture(),
                                      WallClock(),
                                      NoticeBoard(),
                                      Thermostat(),
                                      CeilingDiffuser(),
                                      SupplyGrille(),
                                      ReturnGrille(),
                                      HeatingPipe(),
                                      CableTrunking(),
                                      SkirtingBoard("skirting_board", 1.0),
                                      SkirtingBoard("skirting_board_short", 0.2),
                                      WindowSill(),
                                      Blind(),
                                      Bin(),
                                      CardboardBox(),
                                      Rug(),
                                      SmokeDetector(),
                                      Sprinkler(),
                                      Bulkhead(),
                                      Router()};
  for (AssetBuilder& part : PersonParts()) assets.push_back(std::move(part));
  tinygltf::TinyGLTF writer;
  for (const AssetBuilder& asset : assets) {
    const tinygltf::Model model = ToGltf(asset);
    const std::string path = out_dir + "/" + asset.name + ".gltf";
    if (!writer.WriteGltfSceneToFile(&model, path, true, true, true, false)) {
      std::cerr << "make_assets: cannot write " << path << "\n";
      return 1;
    }
    std::cout << path << ": " << TriangleCount(asset) << " triangles\n";
  }
  return 0;
}
