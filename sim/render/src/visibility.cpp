#include "hoilcd/sim/render/visibility.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "hoilcd/core/util/parallel.h"

namespace hoilcd {
namespace {

// A frame as the camera saw it: the rendered buffers and the camera's place in the world.
struct FrameView {
  FrameView(const World& world, const CameraIntrinsics& intrinsics, const CameraPose& pose, const cv::Mat& instance_ids,
            const cv::Mat& depth_m)
      : world(world),
        intrinsics(intrinsics),
        instance_ids(instance_ids),
        depth_m(depth_m),
        world_from_cam(pose.WorldFromCam()),
        cam_from_world(world_from_cam.Inverse()),
        R(world_from_cam.rotation.toRotationMatrix().cast<float>()),
        origin(world_from_cam.translation.cast<float>()),
        W(intrinsics.width),
        H(intrinsics.height) {}

  bool Inside(const Eigen::Vector2d& uv) const {
    return uv.x() >= -0.5 && uv.y() >= -0.5 && uv.x() < W - 0.5 && uv.y() < H - 0.5;
  }

  const World& world;
  const CameraIntrinsics& intrinsics;
  const cv::Mat& instance_ids;
  const cv::Mat& depth_m;
  const Rigid3 world_from_cam;
  const Rigid3 cam_from_world;
  const Eigen::Matrix3f R;
  const Eigen::Vector3f origin;
  const int W, H;
};

// Pixels of one instance and their bounding box (x1 < 0: none).
struct PixelBox {
  int pixels = 0, x0, y0, x1 = -1, y1 = -1;
};

// Every person's visible pixels and their box, in one pass over the instance ids (indexed by
// instance label).
std::vector<PixelBox> SeenPixels(const FrameView& view) {
  int max_label = -1;
  for (const Person& person : view.world.people()) max_label = std::max(max_label, person.instance);
  std::vector<PixelBox> seen(max_label + 1, PixelBox{0, view.W, view.H, -1, -1});
  for (int y = 0; y < view.H; ++y) {
    const int* row = view.instance_ids.ptr<int>(y);
    for (int x = 0; x < view.W; ++x) {
      const int label = row[x];
      if (label < 0 || label > max_label) continue;
      PixelBox& s = seen[label];
      ++s.pixels;
      s.x0 = std::min(s.x0, x), s.x1 = std::max(s.x1, x), s.y0 = std::min(s.y0, y), s.y1 = std::max(s.y1, y);
    }
  }
  return seen;
}

// The image window of one body part: the projection of its bounding box, clipped to the image.
struct PartWindow {
  int instance, ua, ub, va, vb;
};

// The windows of a person's body parts in front of the camera; *in_front: any part is.
std::vector<PartWindow> PartWindows(const FrameView& view, const Person& person, bool* in_front) {
  const int W = view.W, H = view.H;
  std::vector<PartWindow> windows;
  *in_front = false;
  for (int part : person.parts) {
    const Eigen::Matrix4f& world_from_object = view.world.caster().transform_of(part);
    const Eigen::AlignedBox3f& b = view.world.instance(part).asset->bounds_m;
    double u_min = W, u_max = -1, v_min = H, v_max = -1;
    bool part_in_front = false;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3f c = b.corner(static_cast<Eigen::AlignedBox3f::CornerType>(corner));
      const Eigen::Vector3d w = (world_from_object * c.homogeneous()).head<3>().cast<double>();
      Eigen::Vector3d p = view.cam_from_world * w;
      part_in_front |= p.z() > 0.05;
      p.z() = std::max(p.z(), 0.05);
      const Eigen::Vector2d uv = view.intrinsics.Project(p);
      u_min = std::min(u_min, uv.x()), u_max = std::max(u_max, uv.x());
      v_min = std::min(v_min, uv.y()), v_max = std::max(v_max, uv.y());
    }
    *in_front |= part_in_front;
    if (!part_in_front) continue;
    PartWindow w{part, std::max(0, static_cast<int>(std::floor(u_min))),
                 std::min(W - 1, static_cast<int>(std::ceil(u_max))), std::max(0, static_cast<int>(std::floor(v_min))),
                 std::min(H - 1, static_cast<int>(std::ceil(v_max)))};
    if (w.ua > w.ub || w.va > w.vb) continue;
    windows.push_back(w);
  }
  return windows;
}

// Pixels the person would cover alone: their visible pixels (`seen`), and those of the rest of
// each body part's window that a ray against the part alone hits, cast as packets of 4×4 pixels.
// Returns the count; the box holds only the pixels found by the rays.
PixelBox AlonePixels(const FrameView& view, int instance, const PixelBox& seen,
                     const std::vector<PartWindow>& windows) {
  PixelBox alone{seen.pixels, view.W, view.H, -1, -1};
  if (windows.empty()) return alone;
  int ua = view.W, ub = -1, va = view.H, vb = -1;
  for (const PartWindow& w : windows) {
    ua = std::min(ua, w.ua), ub = std::max(ub, w.ub), va = std::min(va, w.va), vb = std::max(vb, w.vb);
  }
  // Per pixel of the person's window: 1 where they cover it alone.
  const int mask_w = ub - ua + 1;
  std::vector<uint8_t> alone_mask(static_cast<size_t>(mask_w) * (vb - va + 1), 0);
  for (int y = std::max(va, seen.y0); y <= std::min(vb, seen.y1); ++y) {
    const int* row = view.instance_ids.ptr<int>(y);
    for (int x = std::max(ua, seen.x0); x <= std::min(ub, seen.x1); ++x) {
      if (row[x] == instance) alone_mask[(y - va) * mask_w + x - ua] = 1;
    }
  }
  Eigen::Vector3f directions[kRayPacketSize];
  int pixels[kRayPacketSize];
  RayHitPacket hits;
  for (const PartWindow& w : windows) {
    for (int by = w.va; by <= w.vb; by += 4) {
      for (int bx = w.ua; bx <= w.ub; bx += 4) {
        int count = 0;
        for (int y = by; y <= std::min(by + 3, w.vb); ++y) {
          for (int x = bx; x <= std::min(bx + 3, w.ub); ++x) {
            const int m = (y - va) * mask_w + x - ua;
            if (alone_mask[m]) continue;
            pixels[count] = m;
            directions[count++] = (view.R * view.intrinsics.Unproject(x, y).cast<float>()).normalized();
          }
        }
        if (count == 0) continue;
        view.world.caster().IntersectInstancePacket(w.instance, view.origin, directions, count, &hits);
        for (int i = 0; i < count; ++i) {
          if (hits.instance[i] < 0) continue;
          alone_mask[pixels[i]] = 1;
          ++alone.pixels;
          const int x = pixels[i] % mask_w + ua, y = pixels[i] / mask_w + va;
          alone.x0 = std::min(alone.x0, x), alone.x1 = std::max(alone.x1, x);
          alone.y0 = std::min(alone.y0, y), alone.y1 = std::max(alone.y1, y);
        }
      }
    }
  }
  return alone;
}

// The asset's 3-D contact points projected, each visible when the line of sight reaches the
// contact region: the first surface along the ray is the person's own body within 15 cm of the
// contact (a forearm resting on the table, seen from above), or anything within 5 cm of it.
std::vector<ContactRecord> ProjectedContacts(const FrameView& view, const Person& person) {
  std::vector<ContactRecord> out;
  for (const auto& [name, w] : person.contacts_m) {
    const Eigen::Vector3d p = view.cam_from_world * w;
    ContactRecord c;
    c.name = name;
    if (p.z() > 0.05) {
      const Eigen::Vector2d uv = view.intrinsics.Project(p);
      c.u_px = uv.x();
      c.v_px = uv.y();
      if (view.Inside(uv)) {
        const Eigen::Vector3f to = w.cast<float>() - view.origin;
        const RayHit hit = view.world.caster().Intersect(view.origin, to.normalized());
        const float gap = to.norm() - hit.distance_m;
        c.visible =
            hit.hit() && (gap <= 0.05f || (view.world.instance(hit.instance).label == person.instance && gap <= 0.15f));
      }
    } else {
      c.u_px = c.v_px = -1;
    }
    out.push_back(c);
  }
  return out;
}

// COCO keypoints; visible when inside the image and the depth buffer at its pixel is not closer
// than the person's own surface there (nothing else in front of the body). The rays of a
// person's keypoints are cast against each body part as packets.
std::vector<KeypointRecord> ProjectedKeypoints(const FrameView& view, const Person& person) {
  std::vector<KeypointRecord> out;
  std::array<Eigen::Vector3f, kCocoKeypointCount> key_rays, key_directions;
  std::array<float, kCocoKeypointCount> key_depth;
  std::array<int, kCocoKeypointCount> key_index;
  int key_count = 0;
  for (int k = 0; k < kCocoKeypointCount; ++k) {
    const Eigen::Vector3d& w = person.keypoints_m[k];
    KeypointRecord kp;
    kp.name = kCocoKeypointNames[k];
    kp.world_m = {w.x(), w.y(), w.z()};
    const Eigen::Vector3d p = view.cam_from_world * w;
    if (p.z() > 0.05) {
      const Eigen::Vector2d uv = view.intrinsics.Project(p);
      kp.u_px = uv.x();
      kp.v_px = uv.y();
      if (view.Inside(uv) && !view.depth_m.empty()) {
        const int u = std::clamp(static_cast<int>(std::lround(uv.x())), 0, view.W - 1);
        const int v = std::clamp(static_cast<int>(std::lround(uv.y())), 0, view.H - 1);
        key_rays[key_count] = view.intrinsics.Unproject(u, v).cast<float>().normalized();
        key_directions[key_count] = view.R * key_rays[key_count];
        key_depth[key_count] = view.depth_m.at<float>(v, u);
        key_index[key_count++] = k;
      }
    }
    out.push_back(kp);
  }
  std::array<float, kCocoKeypointCount> own;
  own.fill(std::numeric_limits<float>::infinity());
  RayHitPacket hits;
  for (int part : person.parts) {
    for (int begin = 0; begin < key_count; begin += kRayPacketSize) {
      const int count = std::min(kRayPacketSize, key_count - begin);
      view.world.caster().IntersectInstancePacket(part, view.origin, key_directions.data() + begin, count, &hits);
      for (int i = 0; i < count; ++i) own[begin + i] = std::min(own[begin + i], hits.distance_m[i]);
    }
  }
  for (int i = 0; i < key_count; ++i) {
    out[key_index[i]].visible = std::isfinite(own[i]) && key_depth[i] >= own[i] * key_rays[i].z() - 0.01f;
  }
  return out;
}

// Image-space contacts: where the bottom of the visible person (inside `box`) meets a table or
// chair in the image, i.e. what DLCD's HOI points recover. Up to 8 evenly spaced columns.
std::vector<ContactRecord> ImageContacts(const FrameView& view, int instance, const PixelBox& box) {
  std::vector<ContactRecord> edge;
  for (int x = box.x0; x <= box.x1; ++x) {
    for (int y = box.y1; y >= box.y0; --y) {
      if (view.instance_ids.at<int>(y, x) != instance) continue;
      const int below = y + 1 < view.H ? view.instance_ids.at<int>(y + 1, x) : -1;
      if (below >= 0) {
        const InstanceRole role = view.world.instance(below).role;
        if (role == InstanceRole::kTable || role == InstanceRole::kChair) {
          ContactRecord c;
          c.name = role == InstanceRole::kTable ? "table_edge" : "chair_edge";
          c.u_px = x;
          c.v_px = y;
          c.visible = true;
          edge.push_back(c);
        }
      }
      break;
    }
  }
  constexpr size_t kImageContacts = 8;
  std::vector<ContactRecord> out;
  for (size_t k = 0; k < std::min(kImageContacts, edge.size()); ++k) {
    out.push_back(edge[(2 * k + 1) * edge.size() / (2 * std::min(kImageContacts, edge.size()))]);
  }
  return out;
}

// One person's record, or none when they are absent or out of view.
std::optional<PersonRecord> PersonInView(const FrameView& view, const Person& person,
                                         const std::vector<PixelBox>& seen_pixels) {
  if (!person.present) return std::nullopt;
  const PixelBox& seen = seen_pixels[person.instance];
  bool in_front = false;
  const std::vector<PartWindow> windows = PartWindows(view, person, &in_front);
  if (!in_front && seen.pixels == 0) return std::nullopt;
  const PixelBox alone = AlonePixels(view, person.instance, seen, windows);
  // In view but hidden behind something: listed with visible fraction 0 and the box it would
  // cover alone, so occlusion statistics do not lose the people occluded completely.
  PixelBox box = seen;
  if (seen.pixels == 0) {
    if (alone.pixels == 0) return std::nullopt;
    box = alone;
  }
  PersonRecord record;
  record.id = person.person_id;
  record.box_px = cv::Rect2f(static_cast<float>(box.x0), static_cast<float>(box.y0),
                             static_cast<float>(box.x1 - box.x0 + 1), static_cast<float>(box.y1 - box.y0 + 1));
  record.visible_fraction = static_cast<double>(seen.pixels) / std::max(alone.pixels, seen.pixels);
  record.occlusion_fraction = 1.0 - record.visible_fraction;
  record.seated = person.seated;
  record.posture = person.posture;
  record.contacts = ProjectedContacts(view, person);
  record.keypoints = ProjectedKeypoints(view, person);
  for (ContactRecord& c : ImageContacts(view, person.instance, box)) record.contacts.push_back(std::move(c));
  return record;
}

}  // namespace

std::vector<PersonRecord> VisiblePersons(const World& world, const CameraIntrinsics& intrinsics, const CameraPose& pose,
                                         const cv::Mat& instance_ids, const cv::Mat& depth_m, int threads) {
  const FrameView view(world, intrinsics, pose, instance_ids, depth_m);
  const std::vector<PixelBox> seen = SeenPixels(view);
  // Each person on their own (in parallel): only their record changes.
  const std::vector<Person>& people = world.people();
  std::vector<std::optional<PersonRecord>> records(people.size());
  ParallelFor(static_cast<int64_t>(people.size()), threads,
              [&](int64_t i) { records[i] = PersonInView(view, people[i], seen); });
  std::vector<PersonRecord> out;
  for (std::optional<PersonRecord>& record : records) {
    if (record) out.push_back(std::move(*record));
  }
  return out;
}

}  // namespace hoilcd
