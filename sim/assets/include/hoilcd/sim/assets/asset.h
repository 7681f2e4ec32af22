// glTF 2.0 assets with thermal properties: loads a .gltf/.glb into one triangle mesh in the hoilcd
// asset frame (metres, z up, x forward, y left), with per-triangle thermal materials from the
// materials' `extras` and the asset's class, posture and contact points from the scene `extras`.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace hoilcd {

// Thermal properties of one glTF material (defaults apply when its extras omit a field).
struct ThermalMaterial {
  std::string name;           // glTF material name
  std::string region;         // e.g. "skin", "hair", "clothing_upper", "wood"; default: name
  double temperature_c = 22;  // surface temperature, °C, in [-50, 200]
  double emissivity = 0.9;    // 8–14 µm band emissivity, in (0, 1]
  bool specular = false;      // true: reflections are traced (metal, glass), else diffuse
  double roughness_um = 0;    // specular: rms roughness, µm (mirror-like share: MirrorShare)
  // Heat released in this part, W, in [0, 5000] (a datasheet's power turned to heat): with the
  // room's thermal solution its temperature comes from its balance; without, temperature_c.
  double power_w = 0;
};

// Where the asset touches its support: "seat", "table" or "floor" (HOI ground truth).
struct ContactPoint {
  std::string name;
  Eigen::Vector3f position_m;  // asset frame
};

// Indexed triangles; every triangle has a material.
struct TriangleMesh {
  std::vector<Eigen::Vector3f> positions_m;  // asset frame
  std::vector<uint32_t> indices;             // 3 per triangle
  std::vector<uint32_t> triangle_material;   // index into Asset::materials, one per triangle
  size_t TriangleCount() const { return triangle_material.size(); }
};

struct Asset {
  std::string path;
  std::string class_name;  // "person", "table", "chair", ...; empty when the file does not say
  std::string posture;     // people: "seated_upright", "standing", ...; else empty
  // How it is mounted: "floor" (stands on the floor, origin under it; the default), "wall" (its
  // back on a wall, origin at the bottom of its back face) or "hanging" (hangs from its origin: a
  // ceiling light, a coat over a backrest). Only floor objects are footprints on the floor.
  std::string mount = "floor";
  TriangleMesh mesh;
  // The glTF materials in file order; one extra default material ("default") at the end when a
  // primitive has none.
  std::vector<ThermalMaterial> materials;
  std::vector<ContactPoint> contacts;
  // Parts of the articulated person (person_part_*): the part's name, its parent part (empty for
  // the root), the joint it turns about and the COCO keypoints it carries, in the asset frame.
  std::string part;
  std::string parent;
  Eigen::Vector3f joint_m = Eigen::Vector3f::Zero();
  std::vector<ContactPoint> keypoints;
  Eigen::AlignedBox3f bounds_m;  // of mesh.positions_m

  // Index of the first material with this region, -1 if none.
  int MaterialIndex(std::string_view region) const;
};

// Loads a .gltf or .glb. The default scene's node hierarchy (TRS or matrix) is applied, then
// (x, y, z)_hoilcd = (Z, X, Y)_gltf. Asset extras come from the scene, else from the first root
// node that has a "class"; contact positions there are in glTF scene coordinates.
// Throws InputError naming the file (and the glTF JSON path, e.g. "/materials/2/extras/emissivity")
// on a missing file, a parse error, a non-triangle primitive, missing positions, a bad accessor, or
// a bad extras value (unknown key, wrong type, temperature outside [-50, 200] °C, emissivity
// outside (0, 1], a mount other than floor, wall or hanging). Materials without extras get the ThermalMaterial
// defaults, silently.
Asset LoadAsset(const std::string& path);

// The assets shipped with hoilcd: DataDir()/assets (data_dir.h).
std::string ShippedAssetDir();

// Caches assets by path so a scene that places 24 people loads each file once. Thread-safe;
// returned references stay valid for the library's lifetime.
class AssetLibrary {
 public:
  explicit AssetLibrary(std::string search_dir);

  // "person_seated_upright" -> search_dir/person_seated_upright.gltf (or .glb if only that exists);
  // a name ending in .gltf/.glb is a path used as is. Throws InputError like LoadAsset.
  const Asset& Get(const std::string& name_or_path);

  // The file Get(name_or_path) loads.
  std::string Resolve(const std::string& name_or_path) const;

 private:
  std::string search_dir_;
  std::mutex mutex_;
  std::map<std::string, std::unique_ptr<Asset>> assets_;  // by resolved path
};

}  // namespace hoilcd
