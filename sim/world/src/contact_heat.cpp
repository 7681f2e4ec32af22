#include "hoilcd/sim/world/contact_heat.h"

#include <algorithm>
#include <cmath>

#include "hoilcd/core/util/random.h"

namespace hoilcd {

double ContactExcessK(const std::vector<ContactInterval>& intervals, const ContactResponse& response, double time_s) {
  const double ss = response.steady_k;
  double excess = 0, released_s = -std::numeric_limits<double>::infinity();
  for (const ContactInterval& c : intervals) {
    if (c.start_s > time_s) break;
    if (std::isfinite(released_s)) excess *= std::exp(-(c.start_s - released_s) / response.cool_s);
    // From −∞ the exponentials vanish: the steady state.
    if (time_s < c.end_s) return ss + (excess - ss) * std::exp(-(time_s - c.start_s) / response.warm_s);
    excess = ss + (excess - ss) * std::exp(-(c.end_s - c.start_s) / response.warm_s);
    released_s = c.end_s;
  }
  return std::isfinite(released_s) ? excess * std::exp(-(time_s - released_s) / response.cool_s) : excess;
}

float PrintShape::Weight(const Eigen::Vector3f& object_point) const {
  const Eigen::Vector3f local = axes.transpose() * (object_point - center_m);
  const float r2 = local.cwiseQuotient(half_m).squaredNorm();
  if (r2 >= 1.0f) return 0.0f;
  // Full inside 60 % of the radius, a smooth (cubic) edge outside: a pressed area with a soft rim.
  const float u = std::clamp((1.0f - std::sqrt(r2)) / 0.4f, 0.0f, 1.0f);
  return u * u * (3.0f - 2.0f * u);
}

void PrintField::SetTime(double time_s) {
  active_.clear();
  for (size_t i = 0; i < prints_.size(); ++i) {
    const double excess = ContactExcessK(prints_[i].intervals, prints_[i].response, time_s);
    if (std::abs(excess) > 1e-3) active_.emplace_back(i, static_cast<float>(excess));
  }
}

float PrintField::OffsetK(const Eigen::Vector3f& object_point, const Eigen::Vector3f&) const {
  float offset = 0;
  for (const auto& [i, excess] : active_) {
    const float w = prints_[i].shape.Weight(object_point);
    if (w > 0) offset += excess * w * (1.0f + 0.15f * ValueNoise3(HashCombine(key_, i), object_point * 40.0f));
  }
  return offset;
}

}  // namespace hoilcd
