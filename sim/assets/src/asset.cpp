#include "hoilcd/sim/assets/asset.h"

#include <optional>

// The one translation unit of hoilcd::sim that holds tinygltf's implementation. Assets carry no
// textures, so tinygltf's stb image reading and writing are left out.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string_view>

#include <fcntl.h>
#include <sys/stat.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/json_reader.h"
#include "hoilcd/sim/assets/data_dir.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

constexpr double kMinTemperatureC = -50;
constexpr double kMaxTemperatureC = 200;
constexpr int kMaxNodeDepth = 256;                   // deeper than any real file; stops cyclic node graphs
constexpr size_t kMaxBufferBytes = size_t{1} << 30;  // 1 GiB: far above any room asset

// tinygltf's file callbacks, confined to the glTF file's own folder: a buffer uri may name only a
// regular file inside it (no "../" or absolute path out of it, no FIFO or device that blocks).
struct BufferFolder {
  fs::path root;  // canonical folder of the glTF file
};

bool BufferFileExists(const std::string& path, void*) {
  std::error_code error;
  return fs::exists(path, error);
}

// No expansion: tinygltf's default runs wordexp() on uris ("~", "$VAR").
std::string KeepPath(const std::string& path, void*) { return path; }

bool RefuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "writing is not supported";
  return false;
}

bool ReadBufferFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user_data) {
  const fs::path& root = static_cast<const BufferFolder*>(user_data)->root;
  std::error_code error;
  const fs::path real = fs::weakly_canonical(path, error);
  if (error || std::mismatch(root.begin(), root.end(), real.begin(), real.end()).first != root.end()) {
    *err = "a buffer file inside the glTF file's folder " + root.string();
    return false;
  }
  // O_NONBLOCK: opening a FIFO must not wait for a writer; fstat then refuses it.
  const int fd = ::open(real.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    *err = std::string("cannot open: ") + std::strerror(errno);
    return false;
  }
  struct stat info {};
  bool ok = ::fstat(fd, &info) == 0 && S_ISREG(info.st_mode);
  if (!ok) *err = "not a regular file";
  if (ok && static_cast<uint64_t>(info.st_size) > kMaxBufferBytes) {
    ok = false;
    *err = "larger than " + std::to_string(kMaxBufferBytes >> 20) + " MiB";
  }
  if (ok) {
    out->resize(static_cast<size_t>(info.st_size));
    size_t done = 0;
    while (ok && done < out->size()) {
      const ssize_t n = ::read(fd, out->data() + done, out->size() - done);
      if (n < 0 && errno == EINTR) continue;
      ok = n > 0;
      if (ok)
        done += static_cast<size_t>(n);
      else
        *err = n == 0 ? "file shrank while reading" : std::string("read error: ") + std::strerror(errno);
    }
  }
  ::close(fd);
  return ok;
}

// glTF (+Y up, front +Z) to hoilcd asset frame (z up, x forward): a cyclic axis permutation.
Eigen::Vector3f ToAssetFrame(const Eigen::Vector3d& p_gltf) {
  return Eigen::Vector3d(p_gltf.z(), p_gltf.x(), p_gltf.y()).cast<float>();
}

std::string FormatNumber(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

std::string Pointer(const std::string& collection, size_t index, const std::string& rest = "") {
  return "/" + collection + "/" + std::to_string(index) + rest;
}

// Reads one glTF file into hoilcd structures; every problem goes to the collector.
class GltfReader {
 public:
  GltfReader(const std::string& path, const tinygltf::Model& model, ProblemCollector& problems)
      : path_(path), model_(model), problems_(problems) {}

  void Read(Asset& asset) {
    ReadMaterials(asset);
    if (model_.scenes.empty()) {
      Fail("/scenes", "the file has no scene");
      return;
    }
    const size_t scene_index = model_.defaultScene >= 0 ? static_cast<size_t>(model_.defaultScene) : 0;
    if (scene_index >= model_.scenes.size()) {
      Fail("/scene", "names scene " + std::to_string(scene_index) + " which does not exist");
      return;
    }
    const tinygltf::Scene& scene = model_.scenes[scene_index];
    const std::string scene_pointer = Pointer("scenes", scene_index);
    ReadAssetExtras(asset, scene.extras, scene_pointer + "/extras");
    for (size_t i = 0; i < scene.nodes.size(); ++i) {
      const int node = scene.nodes[i];
      if (!ValidIndex(node, model_.nodes.size(), scene_pointer + "/nodes/" + std::to_string(i))) {
        continue;
      }
      if (asset.class_name.empty() && model_.nodes[static_cast<size_t>(node)].extras.Has("class")) {
        ReadAssetExtras(asset, model_.nodes[static_cast<size_t>(node)].extras,
                        Pointer("nodes", static_cast<size_t>(node), "/extras"));
      }
      AddNode(asset, static_cast<size_t>(node), Eigen::Matrix4d::Identity(), 0);
    }
    if (needs_default_material_) {
      const auto default_material = static_cast<uint32_t>(asset.materials.size());
      asset.materials.push_back({"default", "default"});
      for (uint32_t& m : asset.mesh.triangle_material) {
        if (m == kNoMaterial) m = default_material;
      }
    }
    if (asset.mesh.positions_m.empty() && problems_.empty()) {
      Fail(scene_pointer, "the default scene has no triangles");
    }
    asset.bounds_m.setEmpty();
    for (const Eigen::Vector3f& p : asset.mesh.positions_m) asset.bounds_m.extend(p);
  }

 private:
  static constexpr uint32_t kNoMaterial = UINT32_MAX;

  void Fail(const std::string& pointer, const std::string& message) { problems_.Add(path_ + ": " + pointer, message); }

  bool ValidIndex(int index, size_t size, const std::string& pointer) {
    if (index >= 0 && static_cast<size_t>(index) < size) return true;
    Fail(pointer, "index " + std::to_string(index) + " is out of range (" + std::to_string(size) + " entries)");
    return false;
  }

  void ReadMaterials(Asset& asset) {
    for (size_t i = 0; i < model_.materials.size(); ++i) {
      const tinygltf::Material& source = model_.materials[i];
      ThermalMaterial material;
      material.name = source.name.empty() ? "material_" + std::to_string(i) : source.name;
      material.region = material.name;
      const std::string pointer = Pointer("materials", i, "/extras");
      const tinygltf::Value& extras = source.extras;
      if (extras.Type() != tinygltf::NULL_TYPE && !extras.IsObject()) {
        Fail(pointer, "must be an object");
      } else if (extras.IsObject()) {
        for (const std::string& key : extras.Keys()) {
          const tinygltf::Value& value = extras.Get(key);
          const std::string where = pointer + "/" + key;
          if (key == "temperature_c") {
            if (!value.IsNumber()) {
              Fail(where, "must be a number (°C)");
            } else if (value.GetNumberAsDouble() < kMinTemperatureC || value.GetNumberAsDouble() > kMaxTemperatureC) {
              Fail(where, "temperature " + FormatNumber(value.GetNumberAsDouble()) + " °C is outside [-50, 200]");
            } else {
              material.temperature_c = value.GetNumberAsDouble();
            }
          } else if (key == "emissivity") {
            if (!value.IsNumber()) {
              Fail(where, "must be a number in (0, 1]");
            } else if (!(value.GetNumberAsDouble() > 0 && value.GetNumberAsDouble() <= 1)) {
              Fail(where, "emissivity " + FormatNumber(value.GetNumberAsDouble()) + " is outside (0, 1]");
            } else {
              material.emissivity = value.GetNumberAsDouble();
            }
          } else if (key == "specular") {
            if (!value.IsBool()) {
              Fail(where, "must be true or false");
            } else {
              material.specular = value.Get<bool>();
            }
          } else if (key == "roughness_um") {
            if (!value.IsNumber() || !(value.GetNumberAsDouble() >= 0 && value.GetNumberAsDouble() <= 100)) {
              Fail(where, "must be a number in [0, 100] (rms surface roughness, µm)");
            } else {
              material.roughness_um = value.GetNumberAsDouble();
            }
          } else if (key == "power_w") {
            if (!value.IsNumber() || !(value.GetNumberAsDouble() >= 0 && value.GetNumberAsDouble() <= 5000)) {
              Fail(where, "must be a number in [0, 5000] (heat released in this part, W)");
            } else {
              material.power_w = value.GetNumberAsDouble();
            }
          } else if (key == "region") {
            if (!value.IsString() || value.Get<std::string>().empty()) {
              Fail(where, "must be a non-empty string");
            } else {
              material.region = value.Get<std::string>();
            }
          } else {
            Fail(where, "unknown key (expected temperature_c, emissivity, specular, roughness_um, power_w, region)");
          }
        }
      }
      asset.materials.push_back(material);
    }
  }

  void ReadAssetExtras(Asset& asset, const tinygltf::Value& extras, const std::string& pointer) {
    if (extras.Type() == tinygltf::NULL_TYPE) return;
    if (!extras.IsObject()) {
      Fail(pointer, "must be an object");
      return;
    }
    for (const std::string& key : extras.Keys()) {
      const tinygltf::Value& value = extras.Get(key);
      const std::string where = pointer + "/" + key;
      if (key == "class" || key == "posture" || key == "part" || key == "parent") {
        if (!value.IsString() || value.Get<std::string>().empty()) {
          Fail(where, "must be a non-empty string");
        } else {
          std::string& field = key == "class"     ? asset.class_name
                               : key == "posture" ? asset.posture
                               : key == "part"    ? asset.part
                                                  : asset.parent;
          field = value.Get<std::string>();
        }
      } else if (key == "mount") {
        const std::string mount = value.IsString() ? value.Get<std::string>() : "";
        if (mount != "floor" && mount != "wall" && mount != "hanging") {
          Fail(where, "must be \"floor\", \"wall\" or \"hanging\"");
        } else {
          asset.mount = mount;
        }
      } else if (key == "contacts") {
        ReadContacts(asset.contacts, value, where);
      } else if (key == "keypoints") {
        ReadContacts(asset.keypoints, value, where);
      } else if (key == "joint") {
        if (const std::optional<Eigen::Vector3f> p = ReadPosition(value, where)) asset.joint_m = *p;
      } else {
        Fail(where, "unknown key (expected class, posture, mount, contacts, part, parent, joint, keypoints)");
      }
    }
  }

  std::optional<Eigen::Vector3f> ReadPosition(const tinygltf::Value& value, const std::string& where) {
    bool numbers = value.IsArray() && value.ArrayLen() == 3;
    for (size_t k = 0; numbers && k < 3; ++k) numbers = value.Get(static_cast<int>(k)).IsNumber();
    if (!numbers) {
      Fail(where, "must be an array of 3 numbers (glTF metres)");
      return std::nullopt;
    }
    return ToAssetFrame(
        {value.Get(0).GetNumberAsDouble(), value.Get(1).GetNumberAsDouble(), value.Get(2).GetNumberAsDouble()});
  }

  void ReadContacts(std::vector<ContactPoint>& out, const tinygltf::Value& contacts, const std::string& pointer) {
    if (!contacts.IsArray()) {
      Fail(pointer, "must be an array of {name, position}");
      return;
    }
    for (size_t i = 0; i < contacts.ArrayLen(); ++i) {
      const tinygltf::Value& contact = contacts.Get(static_cast<int>(i));
      const std::string where = pointer + "/" + std::to_string(i);
      if (!contact.IsObject()) {
        Fail(where, "must be an object {name, position}");
        continue;
      }
      ContactPoint point;
      bool ok = true;
      for (const std::string& key : contact.Keys()) {
        const tinygltf::Value& value = contact.Get(key);
        if (key == "name") {
          if (!value.IsString() || value.Get<std::string>().empty()) {
            ok = false;
            Fail(where + "/name", "must be a non-empty string");
          } else {
            point.name = value.Get<std::string>();
          }
        } else if (key == "position") {
          const std::optional<Eigen::Vector3f> p = ReadPosition(value, where + "/position");
          if (p) point.position_m = *p;
          ok = ok && p.has_value();
        } else {
          ok = false;
          Fail(where + "/" + key, "unknown key (expected name, position)");
        }
      }
      if (!contact.Has("name") || !contact.Has("position")) {
        ok = false;
        Fail(where, "needs both name and position");
      }
      if (ok) out.push_back(point);
    }
  }

  static Eigen::Matrix4d LocalTransform(const tinygltf::Node& node) {
    Eigen::Matrix4d local = Eigen::Matrix4d::Identity();
    if (node.matrix.size() == 16) {
      for (int k = 0; k < 16; ++k) local(k % 4, k / 4) = node.matrix[static_cast<size_t>(k)];
      return local;
    }
    Eigen::Affine3d trs = Eigen::Affine3d::Identity();
    if (node.translation.size() == 3) {
      trs.translate(Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]));
    }
    if (node.rotation.size() == 4) {
      trs.rotate(
          Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]).normalized());
    }
    if (node.scale.size() == 3) {
      trs.scale(Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]));
    }
    return trs.matrix();
  }

  void AddNode(Asset& asset, size_t node_index, const Eigen::Matrix4d& parent, int depth) {
    const std::string pointer = Pointer("nodes", node_index);
    if (depth > kMaxNodeDepth) {
      Fail(pointer, "node hierarchy is deeper than " + std::to_string(kMaxNodeDepth) + " levels (a cycle?)");
      return;
    }
    const tinygltf::Node& node = model_.nodes[node_index];
    const Eigen::Matrix4d world = parent * LocalTransform(node);
    if (node.mesh >= 0 && ValidIndex(node.mesh, model_.meshes.size(), pointer + "/mesh")) {
      AddMesh(asset, static_cast<size_t>(node.mesh), world);
    }
    for (size_t i = 0; i < node.children.size(); ++i) {
      const int child = node.children[i];
      if (ValidIndex(child, model_.nodes.size(), pointer + "/children/" + std::to_string(i))) {
        AddNode(asset, static_cast<size_t>(child), world, depth + 1);
      }
    }
  }

  // Locates an accessor's elements in its buffer; false (with a problem) if it cannot be read.
  // Hand-written: tinygltf parses accessors but offers no bounds-checked element reader.
  struct View {
    const unsigned char* first = nullptr;
    size_t stride = 0;
    size_t count = 0;
  };
  bool Locate(int accessor_index, const std::string& pointer, View& view) {
    if (!ValidIndex(accessor_index, model_.accessors.size(), pointer)) return false;
    const std::string where = Pointer("accessors", static_cast<size_t>(accessor_index));
    const tinygltf::Accessor& accessor = model_.accessors[static_cast<size_t>(accessor_index)];
    if (accessor.sparse.isSparse) {
      Fail(where + "/sparse", "sparse accessors are not supported");
      return false;
    }
    if (!ValidIndex(accessor.bufferView, model_.bufferViews.size(), where + "/bufferView")) {
      return false;
    }
    const tinygltf::BufferView& buffer_view = model_.bufferViews[static_cast<size_t>(accessor.bufferView)];
    const std::string view_pointer = Pointer("bufferViews", static_cast<size_t>(accessor.bufferView));
    if (!ValidIndex(buffer_view.buffer, model_.buffers.size(), view_pointer + "/buffer")) {
      return false;
    }
    const std::vector<unsigned char>& data = model_.buffers[static_cast<size_t>(buffer_view.buffer)].data;
    const int stride = accessor.ByteStride(buffer_view);
    const int component = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(accessor.componentType));
    const int components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(accessor.type));
    if (stride <= 0 || component <= 0 || components <= 0) {
      Fail(where, "has an invalid type, component type or byte stride");
      return false;
    }
    // Every size below comes from the file: compare by subtraction so nothing can wrap.
    const size_t element = static_cast<size_t>(component) * static_cast<size_t>(components);
    const size_t view_offset = buffer_view.byteOffset;
    const size_t view_length = buffer_view.byteLength;
    bool inside =
        view_offset <= data.size() && view_length <= data.size() - view_offset && accessor.byteOffset <= view_length;
    if (inside && accessor.count > 0) {
      const size_t available = view_length - accessor.byteOffset;
      inside = element <= available && accessor.count - 1 <= (available - element) / static_cast<size_t>(stride);
    }
    if (!inside) {
      Fail(where, "reads past the end of its buffer view or buffer");
      return false;
    }
    const size_t begin = view_offset + accessor.byteOffset;
    view.first = data.data() + begin;
    view.stride = static_cast<size_t>(stride);
    view.count = accessor.count;
    return true;
  }

  void AddMesh(Asset& asset, size_t mesh_index, const Eigen::Matrix4d& world) {
    const tinygltf::Mesh& mesh = model_.meshes[mesh_index];
    const bool mirrored = world.topLeftCorner<3, 3>().determinant() < 0;
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& primitive = mesh.primitives[p];
      const std::string pointer = Pointer("meshes", mesh_index, "/primitives/" + std::to_string(p));
      if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1) {
        Fail(pointer + "/mode",
             "is " + std::to_string(primitive.mode) + "; only triangle lists (mode 4) are supported");
        continue;
      }
      const auto position_it = primitive.attributes.find("POSITION");
      if (position_it == primitive.attributes.end()) {
        Fail(pointer + "/attributes", "has no POSITION");
        continue;
      }
      View positions;
      if (!Locate(position_it->second, pointer + "/attributes/POSITION", positions)) continue;
      const tinygltf::Accessor& position_accessor = model_.accessors[static_cast<size_t>(position_it->second)];
      if (position_accessor.type != TINYGLTF_TYPE_VEC3 ||
          position_accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
        Fail(Pointer("accessors", static_cast<size_t>(position_it->second)), "POSITION must be a VEC3 of FLOAT");
        continue;
      }
      std::vector<uint32_t> indices;
      if (primitive.indices >= 0) {
        if (!ReadIndices(primitive.indices, pointer + "/indices", indices)) continue;
      } else {
        indices.resize(positions.count);
        for (size_t i = 0; i < positions.count; ++i) indices[i] = static_cast<uint32_t>(i);
      }
      if (indices.size() % 3 != 0) {
        Fail(pointer, "has " + std::to_string(indices.size()) + " indices, not a multiple of 3");
        continue;
      }
      bool in_range = true;
      for (uint32_t index : indices) in_range = in_range && index < positions.count;
      if (!in_range) {
        Fail(pointer + "/indices", "refers to a vertex past the " + std::to_string(positions.count) + " positions");
        continue;
      }
      uint32_t material = kNoMaterial;
      if (primitive.material >= 0) {
        if (!ValidIndex(primitive.material, model_.materials.size(), pointer + "/material")) continue;
        material = static_cast<uint32_t>(primitive.material);
      } else {
        needs_default_material_ = true;
      }

      const auto base = static_cast<uint32_t>(asset.mesh.positions_m.size());
      for (size_t i = 0; i < positions.count; ++i) {
        float xyz[3];
        std::memcpy(xyz, positions.first + i * positions.stride, sizeof(xyz));
        const Eigen::Vector4d p = world * Eigen::Vector4d(xyz[0], xyz[1], xyz[2], 1.0);
        asset.mesh.positions_m.push_back(ToAssetFrame(p.head<3>()));
      }
      for (size_t t = 0; t < indices.size(); t += 3) {
        // A mirroring transform flips the winding; swap two corners to keep front faces.
        asset.mesh.indices.push_back(base + indices[t]);
        asset.mesh.indices.push_back(base + indices[mirrored ? t + 2 : t + 1]);
        asset.mesh.indices.push_back(base + indices[mirrored ? t + 1 : t + 2]);
        asset.mesh.triangle_material.push_back(material);
      }
    }
  }

  bool ReadIndices(int accessor_index, const std::string& pointer, std::vector<uint32_t>& indices) {
    View view;
    if (!Locate(accessor_index, pointer, view)) return false;
    const tinygltf::Accessor& accessor = model_.accessors[static_cast<size_t>(accessor_index)];
    if (accessor.type != TINYGLTF_TYPE_SCALAR) {
      Fail(Pointer("accessors", static_cast<size_t>(accessor_index)), "indices must be SCALAR");
      return false;
    }
    indices.resize(view.count);
    for (size_t i = 0; i < view.count; ++i) {
      const unsigned char* at = view.first + i * view.stride;
      switch (accessor.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
          indices[i] = *at;
          break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          uint16_t value;
          std::memcpy(&value, at, sizeof(value));
          indices[i] = value;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
          std::memcpy(&indices[i], at, sizeof(uint32_t));
          break;
        default:
          Fail(Pointer("accessors", static_cast<size_t>(accessor_index), "/componentType"),
               "indices must be unsigned byte, short or int");
          return false;
      }
    }
    return true;
  }

  const std::string& path_;
  const tinygltf::Model& model_;
  ProblemCollector& problems_;
  bool needs_default_material_ = false;
};

bool HasGltfExtension(const std::string& path) {
  const std::string extension = fs::path(path).extension().string();
  return extension == ".gltf" || extension == ".glb";
}

// tinygltf turns "extras" into its own values recursively, and keeps the last of a repeated key:
// the glTF's JSON (a .glb's JSON chunk) goes through ParseJson first, which bounds the nesting and
// refuses repeated keys. Text that is not JSON, and a .glb too short for its chunk, are left for
// tinygltf to refuse ("cannot parse glTF").
void CheckGltfJson(const std::string& path, bool binary) {
  const std::string bytes = ReadFileBytes(path);
  std::string_view text = bytes;
  if (binary) {
    // 12-byte header, then the JSON chunk: its length (uint32, little-endian), "JSON", the text.
    if (bytes.size() < 20 || bytes.compare(16, 4, "JSON") != 0) return;
    uint64_t length = 0;
    for (int k = 3; k >= 0; --k) length = length << 8 | static_cast<unsigned char>(bytes[static_cast<size_t>(12 + k)]);
    if (length > bytes.size() - 20) return;
    text = text.substr(20, static_cast<size_t>(length));
  }
  try {
    ParseJson(text, path);
  } catch (const JsonSyntaxError&) {
  }
}

}  // namespace

int Asset::MaterialIndex(std::string_view region) const {
  for (size_t i = 0; i < materials.size(); ++i) {
    if (materials[i].region == region) return static_cast<int>(i);
  }
  return -1;
}

Asset LoadAsset(const std::string& path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) {
    throw InputError(path, "glTF file not found");
  }
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::error_code error_code;
  BufferFolder folder{fs::weakly_canonical(fs::absolute(path), error_code).parent_path()};
  loader.SetFsCallbacks({BufferFileExists, KeepPath, ReadBufferFile, RefuseWrite, &folder});
  std::string errors;
  std::string warnings;
  const bool binary = fs::path(path).extension() == ".glb";
  CheckGltfJson(path, binary);
  const bool loaded = binary ? loader.LoadBinaryFromFile(&model, &errors, &warnings, path)
                             : loader.LoadASCIIFromFile(&model, &errors, &warnings, path);
  if (!loaded) {
    while (!errors.empty() && errors.back() == '\n') errors.pop_back();
    throw InputError(path, "cannot parse glTF: " + (errors.empty() ? "unknown error" : errors));
  }
  Asset asset;
  asset.path = path;
  ProblemCollector problems;
  GltfReader(path, model, problems).Read(asset);
  problems.ThrowIfAny();
  return asset;
}

std::string ShippedAssetDir() { return DataDir() + "/assets"; }

AssetLibrary::AssetLibrary(std::string search_dir) : search_dir_(std::move(search_dir)) {}

std::string AssetLibrary::Resolve(const std::string& name_or_path) const {
  if (HasGltfExtension(name_or_path)) return name_or_path;
  const fs::path gltf = fs::path(search_dir_) / (name_or_path + ".gltf");
  const fs::path glb = fs::path(search_dir_) / (name_or_path + ".glb");
  std::error_code error;
  if (!fs::exists(gltf, error) && fs::exists(glb, error)) return glb.string();
  return gltf.string();
}

const Asset& AssetLibrary::Get(const std::string& name_or_path) {
  const std::string path = Resolve(name_or_path);
  std::error_code error;
  fs::path key = fs::absolute(path, error).lexically_normal();
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = assets_.find(key.string());
  if (it == assets_.end()) {
    it = assets_.emplace(key.string(), std::make_unique<Asset>(LoadAsset(path))).first;
  }
  return *it->second;
}

}  // namespace hoilcd
