#include "hoilcd/sim/visibility.h"

#include <algorithm>
#include <cmath>

namespace hoilcd {

std::vector<PersonRecord> VisiblePersons(const World& world, const CameraIntrinsics& intrinsics,
                                         const CameraPose& pose, const cv::Mat& instance_ids) {
  const Rigid3 world_from_cam = pose.WorldFromCam();
  const Rigid3 cam_from_world = world_from_cam.Inverse();
  const Eigen::Matrix3f R = world_from_cam.rotation.toRotationMatrix().cast<float>();
  const Eigen::Vector3f origin = world_from_cam.translation.cast<float>();
  const int W = intrinsics.width, H = intrinsics.height;
  std::vector<PersonRecord> out;
  for (const Person& person : world.people()) {
    if (!person.present) continue;
    const int instance = person.instance;
    const Eigen::Matrix4f& world_from_object = world.caster().transform_of(instance);
    const Asset& asset = *world.instance(instance).asset;

    // Visible pixels and their box.
    int visible = 0, x0 = W, y0 = H, x1 = -1, y1 = -1;
    for (int y = 0; y < H; ++y) {
      const int* row = instance_ids.ptr<int>(y);
      for (int x = 0; x < W; ++x) {
        if (row[x] != instance) continue;
        ++visible;
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      }
    }
    // Pixels the person would cover alone: cast against its instance only, within the
    // projection of its bounding box.
    double u_min = W, u_max = -1, v_min = H, v_max = -1;
    const Eigen::AlignedBox3f& b = asset.bounds_m;
    bool in_front = false;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3f c = b.corner(static_cast<Eigen::AlignedBox3f::CornerType>(corner));
      const Eigen::Vector3d w = (world_from_object * c.homogeneous()).head<3>().cast<double>();
      Eigen::Vector3d p = cam_from_world * w;
      in_front |= p.z() > 0.05;
      p.z() = std::max(p.z(), 0.05);
      const Eigen::Vector2d uv = intrinsics.Project(p);
      u_min = std::min(u_min, uv.x()), u_max = std::max(u_max, uv.x());
      v_min = std::min(v_min, uv.y()), v_max = std::max(v_max, uv.y());
    }
    const int ua = std::max(0, static_cast<int>(std::floor(u_min))), ub = std::min(W - 1, static_cast<int>(std::ceil(u_max)));
    const int va = std::max(0, static_cast<int>(std::floor(v_min))), vb = std::min(H - 1, static_cast<int>(std::ceil(v_max)));
    if (!in_front && visible == 0) continue;
    int alone = 0, ax0 = W, ay0 = H, ax1 = -1, ay1 = -1;
    for (int y = va; y <= vb; ++y) {
      for (int x = ua; x <= ub; ++x) {
        const Eigen::Vector3f d = (R * intrinsics.Unproject(x, y).cast<float>()).normalized();
        if (!world.caster().IntersectInstance(instance, origin, d).hit()) continue;
        ++alone;
        ax0 = std::min(ax0, x), ax1 = std::max(ax1, x), ay0 = std::min(ay0, y), ay1 = std::max(ay1, y);
      }
    }
    // In view but hidden behind something: listed with visible fraction 0 and the box it would
    // cover alone, so occlusion statistics do not lose the people occluded completely.
    if (visible == 0) {
      if (alone == 0) continue;
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
    for (const ContactPoint& contact : asset.contacts) {
      const Eigen::Vector3d w =
          (world_from_object * contact.position_m.homogeneous()).head<3>().cast<double>();
      const Eigen::Vector3d p = cam_from_world * w;
      ContactRecord c;
      c.name = contact.name;
      if (p.z() > 0.05) {
        const Eigen::Vector2d uv = intrinsics.Project(p);
        c.u_px = uv.x();
        c.v_px = uv.y();
        const bool inside = uv.x() >= -0.5 && uv.y() >= -0.5 && uv.x() < W - 0.5 && uv.y() < H - 0.5;
        if (inside) {
          // Visible when the line of sight reaches the contact region: the first surface along
          // the ray is the person's own body within 15 cm of the contact (a forearm resting on
          // the table, seen from above), or anything within 5 cm of it (the contact itself).
          const Eigen::Vector3f to = w.cast<float>() - origin;
          const RayHit hit = world.caster().Intersect(origin, to.normalized());
          const float gap = to.norm() - hit.distance_m;
          c.visible = hit.hit() && (gap <= 0.05f || (hit.instance == instance && gap <= 0.15f));
        }
      } else {
        c.u_px = c.v_px = -1;
      }
      record.contacts.push_back(c);
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
    out.push_back(std::move(record));
  }
  return out;
}

}  // namespace hoilcd
