#include "hoilcd/sim/render/visibility.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "hoilcd/core/util/parallel.h"

namespace hoilcd {

std::vector<PersonRecord> VisiblePersons(const World& world, const CameraIntrinsics& intrinsics,
                                         const CameraPose& pose, const cv::Mat& instance_ids,
                                         const cv::Mat& depth_m, int threads) {
  const Rigid3 world_from_cam = pose.WorldFromCam();
  const Rigid3 cam_from_world = world_from_cam.Inverse();
  const Eigen::Matrix3f R = world_from_cam.rotation.toRotationMatrix().cast<float>();
  const Eigen::Vector3f origin = world_from_cam.translation.cast<float>();
  const int W = intrinsics.width, H = intrinsics.height;
  std::vector<PersonRecord> out;
  // Every person's visible pixels and their box, in one pass over the instance ids.
  struct Seen {
    int pixels = 0, x0, y0, x1 = -1, y1 = -1;
  };
  int max_label = -1;
  for (const Person& person : world.people()) max_label = std::max(max_label, person.instance);
  std::vector<Seen> seen(max_label + 1, Seen{0, W, H, -1, -1});
  for (int y = 0; y < H; ++y) {
    const int* row = instance_ids.ptr<int>(y);
    for (int x = 0; x < W; ++x) {
      const int label = row[x];
      if (label < 0 || label > max_label) continue;
      Seen& s = seen[label];
      ++s.pixels;
      s.x0 = std::min(s.x0, x), s.x1 = std::max(s.x1, x), s.y0 = std::min(s.y0, y), s.y1 = std::max(s.y1, y);
    }
  }
  // Each person on their own (in parallel): only their record and their own scratch change.
  const std::vector<Person>& people = world.people();
  std::vector<std::optional<PersonRecord>> records(people.size());
  ParallelFor(static_cast<int64_t>(people.size()), threads, [&](int64_t person_index) {
    const Person& person = people[person_index];
    std::vector<uint8_t> alone_mask;  // per pixel of the person's window: 1 where they cover it alone
    if (!person.present) return;
    const int instance = person.instance;
    int visible = seen[instance].pixels, x0 = seen[instance].x0, y0 = seen[instance].y0,
        x1 = seen[instance].x1, y1 = seen[instance].y1;
    // Pixels the person would cover alone: their visible pixels, and those of the rest of each
    // body part's window (the projection of its bounding box) that a ray against the part alone
    // hits, cast as packets of 4×4 pixels.
    struct PartWindow {
      int instance, ua, ub, va, vb;
    };
    std::vector<PartWindow> windows;
    int ua = W, ub = -1, va = H, vb = -1;
    bool in_front = false;
    for (int part : person.parts) {
      const Eigen::Matrix4f& world_from_object = world.caster().transform_of(part);
      const Eigen::AlignedBox3f& b = world.instance(part).asset->bounds_m;
      double u_min = W, u_max = -1, v_min = H, v_max = -1;
      bool part_in_front = false;
      for (int corner = 0; corner < 8; ++corner) {
        const Eigen::Vector3f c = b.corner(static_cast<Eigen::AlignedBox3f::CornerType>(corner));
        const Eigen::Vector3d w = (world_from_object * c.homogeneous()).head<3>().cast<double>();
        Eigen::Vector3d p = cam_from_world * w;
        part_in_front |= p.z() > 0.05;
        p.z() = std::max(p.z(), 0.05);
        const Eigen::Vector2d uv = intrinsics.Project(p);
        u_min = std::min(u_min, uv.x()), u_max = std::max(u_max, uv.x());
        v_min = std::min(v_min, uv.y()), v_max = std::max(v_max, uv.y());
      }
      in_front |= part_in_front;
      if (!part_in_front) continue;
      PartWindow w{part, std::max(0, static_cast<int>(std::floor(u_min))), std::min(W - 1, static_cast<int>(std::ceil(u_max))),
                   std::max(0, static_cast<int>(std::floor(v_min))), std::min(H - 1, static_cast<int>(std::ceil(v_max)))};
      if (w.ua > w.ub || w.va > w.vb) continue;
      windows.push_back(w);
      ua = std::min(ua, w.ua), ub = std::max(ub, w.ub), va = std::min(va, w.va), vb = std::max(vb, w.vb);
    }
    if (!in_front && visible == 0) return;
    int alone = visible, ax0 = W, ay0 = H, ax1 = -1, ay1 = -1;
    RayHitPacket hits;
    if (!windows.empty()) {
      const int mask_w = ub - ua + 1;
      alone_mask.assign(static_cast<size_t>(mask_w) * (vb - va + 1), 0);
      for (int y = std::max(va, y0); y <= std::min(vb, y1); ++y) {
        const int* row = instance_ids.ptr<int>(y);
        for (int x = std::max(ua, x0); x <= std::min(ub, x1); ++x) {
          if (row[x] == instance) alone_mask[(y - va) * mask_w + x - ua] = 1;
        }
      }
      Eigen::Vector3f directions[kRayPacketSize];
      int pixels[kRayPacketSize];
      for (const PartWindow& w : windows) {
        for (int by = w.va; by <= w.vb; by += 4) {
          for (int bx = w.ua; bx <= w.ub; bx += 4) {
            int count = 0;
            for (int y = by; y <= std::min(by + 3, w.vb); ++y) {
              for (int x = bx; x <= std::min(bx + 3, w.ub); ++x) {
                const int m = (y - va) * mask_w + x - ua;
                if (alone_mask[m]) continue;
                pixels[count] = m;
                directions[count++] = (R * intrinsics.Unproject(x, y).cast<float>()).normalized();
              }
            }
            if (count == 0) continue;
            world.caster().IntersectInstancePacket(w.instance, origin, directions, count, &hits);
            for (int i = 0; i < count; ++i) {
              if (hits.instance[i] < 0) continue;
              alone_mask[pixels[i]] = 1;
              ++alone;
              const int x = pixels[i] % mask_w + ua, y = pixels[i] / mask_w + va;
              ax0 = std::min(ax0, x), ax1 = std::max(ax1, x), ay0 = std::min(ay0, y), ay1 = std::max(ay1, y);
            }
          }
        }
      }
    }
    // In view but hidden behind something: listed with visible fraction 0 and the box it would
    // cover alone, so occlusion statistics do not lose the people occluded completely.
    if (visible == 0) {
      if (alone == 0) return;
      x0 = ax0, x1 = ax1, y0 = ay0, y1 = ay1;
    }
    alone = std::max(alone, visible);

    PersonRecord record;
    record.id = person.person_id;
    record.box_px = cv::Rect2f(static_cast<float>(x0), static_cast<float>(y0),
                               static_cast<float>(x1 - x0 + 1), static_cast<float>(y1 - y0 + 1));
    record.visible_fraction = static_cast<double>(visible) / alone;
    record.occlusion_fraction = 1.0 - record.visible_fraction;
    record.seated = person.seated;
    record.posture = person.posture;
    auto inside = [&](const Eigen::Vector2d& uv) {
      return uv.x() >= -0.5 && uv.y() >= -0.5 && uv.x() < W - 0.5 && uv.y() < H - 0.5;
    };
    for (const auto& [name, w] : person.contacts_m) {
      const Eigen::Vector3d p = cam_from_world * w;
      ContactRecord c;
      c.name = name;
      if (p.z() > 0.05) {
        const Eigen::Vector2d uv = intrinsics.Project(p);
        c.u_px = uv.x();
        c.v_px = uv.y();
        if (inside(uv)) {
          // Visible when the line of sight reaches the contact region: the first surface along
          // the ray is the person's own body within 15 cm of the contact (a forearm resting on
          // the table, seen from above), or anything within 5 cm of it (the contact itself).
          const Eigen::Vector3f to = w.cast<float>() - origin;
          const RayHit hit = world.caster().Intersect(origin, to.normalized());
          const float gap = to.norm() - hit.distance_m;
          c.visible = hit.hit() && (gap <= 0.05f || (world.instance(hit.instance).label == instance && gap <= 0.15f));
        }
      } else {
        c.u_px = c.v_px = -1;
      }
      record.contacts.push_back(c);
    }
    // COCO keypoints; visible when inside the image and the depth buffer at its pixel is not
    // closer than the person's own surface there (nothing else in front of the body). The rays
    // of a person's keypoints are cast against each body part as packets.
    std::array<Eigen::Vector3f, kCocoKeypointCount> key_rays, key_directions;
    std::array<float, kCocoKeypointCount> key_depth;
    std::array<int, kCocoKeypointCount> key_index;
    int key_count = 0;
    for (int k = 0; k < kCocoKeypointCount; ++k) {
      const Eigen::Vector3d& w = person.keypoints_m[k];
      KeypointRecord kp;
      kp.name = kCocoKeypointNames[k];
      kp.world_m = {w.x(), w.y(), w.z()};
      const Eigen::Vector3d p = cam_from_world * w;
      if (p.z() > 0.05) {
        const Eigen::Vector2d uv = intrinsics.Project(p);
        kp.u_px = uv.x();
        kp.v_px = uv.y();
        if (inside(uv) && !depth_m.empty()) {
          const int u = std::clamp(static_cast<int>(std::lround(uv.x())), 0, W - 1);
          const int v = std::clamp(static_cast<int>(std::lround(uv.y())), 0, H - 1);
          key_rays[key_count] = intrinsics.Unproject(u, v).cast<float>().normalized();
          key_directions[key_count] = R * key_rays[key_count];
          key_depth[key_count] = depth_m.at<float>(v, u);
          key_index[key_count++] = k;
        }
      }
      record.keypoints.push_back(kp);
    }
    std::array<float, kCocoKeypointCount> own;
    own.fill(std::numeric_limits<float>::infinity());
    for (int part : person.parts) {
      for (int begin = 0; begin < key_count; begin += kRayPacketSize) {
        const int count = std::min(kRayPacketSize, key_count - begin);
        world.caster().IntersectInstancePacket(part, origin, key_directions.data() + begin, count, &hits);
        for (int i = 0; i < count; ++i) own[begin + i] = std::min(own[begin + i], hits.distance_m[i]);
      }
    }
    for (int i = 0; i < key_count; ++i) {
      record.keypoints[key_index[i]].visible =
          std::isfinite(own[i]) && key_depth[i] >= own[i] * key_rays[i].z() - 0.01f;
    }
    // Image-space contacts: where the bottom of the visible person meets a table or chair in
    // the image, i.e. what DLCD's HOI points recover. Up to kImageContacts evenly spaced columns.
    std::vector<ContactRecord> edge;
    for (int x = x0; x <= x1; ++x) {
      for (int y = y1; y >= y0; --y) {
        if (instance_ids.at<int>(y, x) != instance) continue;
        const int below = y + 1 < H ? instance_ids.at<int>(y + 1, x) : -1;
        if (below >= 0) {
          const InstanceRole role = world.instance(below).role;
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
    for (size_t k = 0; k < std::min(kImageContacts, edge.size()); ++k) {
      record.contacts.push_back(edge[(2 * k + 1) * edge.size() / (2 * std::min(kImageContacts, edge.size()))]);
    }
    records[person_index] = std::move(record);
  });
  for (std::optional<PersonRecord>& record : records) {
    if (record) out.push_back(std::move(*record));
  }
  return out;
}

}  // namespace hoilcd
