// Contact heat (docs/models/contact_heat.md): the warm prints people leave where they touch a
// surface (a chair's seat and backrest, a table top under their forearms, a laptop's palm rest,
// a cup's handle), and the first-order response behind them and behind cups and laptops warming
// and cooling. Everything is a closed-form function of time over planned contact intervals, so
// a frame's state never depends on the frames rendered before it.
#pragma once

#include <limits>
#include <vector>

#include <Eigen/Core>

#include "hoilcd/sim/assets/surface_field.h"

namespace hoilcd {

// A contact from start_s to end_s; start_s = −∞ for contacts that began long before the run
// (steady state at its start), end_s = +∞ for contacts that never end.
struct ContactInterval {
  double start_s = 0, end_s = std::numeric_limits<double>::infinity();
};

// First-order response to contact: toward steady_k with warm_s while in contact, toward 0 with
// cool_s after release.
struct ContactResponse {
  double steady_k = 0, warm_s = 1, cool_s = 1;
};

// The excess, K, at time t after the contact intervals (sorted, not overlapping) of a surface
// that was at 0 before the first: each interval's exponential approach and each gap's
// exponential decay, chained in closed form.
double ContactExcessK(const std::vector<ContactInterval>& intervals, const ContactResponse& response, double time_s);

// Where a contact touches, in the touched instance's own frame: an ellipsoid with semi-axes
// half_m along the orthonormal axes (columns; the third is the surface normal, its semi-axis the
// thickness of the band around the surface that shows the print). The print's weight is 1 in
// its inner part and falls smoothly to 0 at its edge.
struct PrintShape {
  Eigen::Vector3f center_m = Eigen::Vector3f::Zero();
  Eigen::Matrix3f axes = Eigen::Matrix3f::Identity();
  Eigen::Vector3f half_m = Eigen::Vector3f::Constant(0.1f);
  float Weight(const Eigen::Vector3f& object_point) const;
};

struct Print {
  PrintShape shape;
  ContactResponse response;
  std::vector<ContactInterval> intervals;
};

// The prints on one instance. SetTime (between frames) evaluates each print's excess; OffsetK
// (while a frame renders, from many threads) only reads them. Overlapping prints add; a small
// keyed texture (skin and fabric do not touch evenly) varies each print by ±15 %.
class PrintField : public SurfaceField {
 public:
  explicit PrintField(uint64_t key) : key_(key) {}
  void Add(Print print) { prints_.push_back(std::move(print)); }
  void SetTime(double time_s);
  float OffsetK(const Eigen::Vector3f& object_point, const Eigen::Vector3f& world_point) const override;
  const std::vector<Print>& prints() const { return prints_; }

 private:
  uint64_t key_;
  std::vector<Print> prints_;
  std::vector<std::pair<size_t, float>> active_;  // prints with a visible excess now, K
};

}  // namespace hoilcd
