#include "hoilcd/core/matching/matching.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/random.h"

namespace hoilcd {
namespace {

// Grid density: about this many points per cell.
constexpr float kPointsPerCell = 1.0f;
// Upper bound on cells per axis, so a few far-off points cannot blow up the grid.
constexpr int kMaxCellsPerAxis = 1024;
// The coordinate and id arrays run this far past the last point, so that eight-lane loads
// starting at any point stay inside them.
constexpr int kPadding = 8;

// Candidate lattice: cells per grid cell side (finer cells have fewer candidates each), and
// the margin of lattice cells around the bounding box of the points.
constexpr int kLatticeCellsPerGridCell = 2;
constexpr int kLatticeMarginCells = 4;
// Candidate slots per lattice cell; a cell with more candidates is marked crowded and searched
// in the grid instead (a few % of cells).
constexpr int kLatticeWidth = 4;
// Build limits: a cell whose candidate search reaches further than this many lattice cells, or
// finds more than this many points, is marked crowded; sets reaching further than this from the
// origin get no lattice.
constexpr float kMaxReachCells = 8;
constexpr size_t kMaxNearCandidates = 48;
constexpr float kMaxLatticeCoordinate = 1e15f;
// Sets of at most this many points are searched by comparing every point, eight at a time, and
// get no lattice. Frames' points cluster (people, furniture edges), so on paper_room a third of
// the lattice's queries fell through to the grid (outside the lattice or in crowded cells);
// scanning 48 points costs less than that mix. Scoring's CPU was flat for limits from 96 to 320.
constexpr int kScanAllMax = 96;
// Eight lanes (GCC vector extensions, which clang shares; a default-target build lowers them to
// SSE halves).
using Floats8 = float __attribute__((vector_size(32)));
using Ints8 = int32_t __attribute__((vector_size(32)));
using Floats4 = float __attribute__((vector_size(16)));
using Ints4 = int32_t __attribute__((vector_size(16)));

// Smallest lane of v (Floats8 or Ints8): lanes fold onto themselves through three shuffles.
template <typename Vector>
[[gnu::always_inline]] inline auto LaneMin(const Vector& v) {
  Vector m = v;
  Vector other = __builtin_shufflevector(m, m, 4, 5, 6, 7, 0, 1, 2, 3);
  m = other < m ? other : m;
  other = __builtin_shufflevector(m, m, 2, 3, 0, 1, 6, 7, 4, 5);
  m = other < m ? other : m;
  other = __builtin_shufflevector(m, m, 1, 0, 3, 2, 5, 4, 7, 6);
  m = other < m ? other : m;
  return m[0];
}

// LaneMin for four lanes.
template <typename Vector>
[[gnu::always_inline]] inline auto LaneMin4(const Vector& v) {
  Vector m = v;
  Vector other = __builtin_shufflevector(m, m, 2, 3, 0, 1);
  m = other < m ? other : m;
  other = __builtin_shufflevector(m, m, 1, 0, 3, 2);
  m = other < m ? other : m;
  return m[0];
}

// Clang cannot combine flatten with target_clones: there the clones call the grid queries
// instead of inlining them (the same arithmetic, so the same results).
#if defined(__clang__)
#define HOILCD_CLONES_FLATTENED __attribute__((target_clones("avx2", "default")))
#else
#define HOILCD_CLONES_FLATTENED __attribute__((target_clones("avx2", "default"), flatten))
#endif

// Mutual nearest neighbours in three passes without data-dependent branches: every query point's
// nearest reference point, every reference point's nearest query point, then the pairs that agree
// (each the other's nearest, by the same float distances and tie rule in both directions). The
// lookups of a pass are independent, so they overlap; on paper_room's all-pairs scoring this
// took 4 % less CPU than looking up each reference's nearest on demand.
// Cloned for AVX2 with run-time dispatch, with the grid queries inlined into each clone.
HOILCD_CLONES_FLATTENED void MutualNearestNeighboursOnGrids(const Point2* query_points, const PointGrid& query_grid,
                                                            const Point2* reference_points,
                                                            const PointGrid& reference_grid, std::vector<int>* nearest,
                                                            std::vector<Correspondence>* matches) {
  matches->clear();
  const int nq = query_grid.size(), nr = reference_grid.size();
  if (nq == 0 || nr == 0) return;
  nearest->resize(static_cast<size_t>(nq) + nr);
  int* forward = nearest->data();  // query i -> nearest reference
  int* backward = forward + nq;    // reference j -> nearest query
  for (int i = 0; i < nq; ++i) forward[i] = reference_grid.Nearest(query_points[i]);
  for (int j = 0; j < nr; ++j) backward[j] = query_grid.Nearest(reference_points[j]);
  matches->resize(nq);
  Correspondence* out = matches->data();
  int kept = 0;
  for (int i = 0; i < nq; ++i) {
    out[kept] = {i, forward[i]};
    kept += backward[forward[i]] == i ? 1 : 0;
  }
  matches->resize(kept);
}

bool WithinVerticalTolerance(float query_y, float reference_y, double tolerance_px) {
  return std::abs(static_cast<double>(query_y) - static_cast<double>(reference_y)) <= tolerance_px;
}

}  // namespace

MatchOptions::MatchOptions() { Table().FillDefaults(this); }

const OptionTable<MatchOptions>& MatchOptions::Table() {
  using O = MatchOptions;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("vertical_tolerance", &O::vertical_tolerance, 0.1, "", OptionRange::Closed(0, 1),
               "vertical filter: |y_q - y_r| at most this fraction of the image height")
          .Add("image_height_px", &O::image_height_px, 192, "px", OptionRange::Any().AtLeast(1),
               "image height the vertical tolerance is a fraction of");
  return table;
}

std::string MatchOptions::Check() const { return Table().FirstProblem(*this); }

PointGrid::PointGrid(const Point2* points, int count) {
  if (count <= 0) return;
  float min_x = points[0].x, max_x = min_x, min_y = points[0].y, max_y = min_y;
  for (int i = 0; i < count; ++i) {
    HOILCD_CHECK_MSG(std::isfinite(points[i].x) && std::isfinite(points[i].y),
                     "point " << i << " has a non-finite coordinate");
    min_x = std::min(min_x, points[i].x);
    max_x = std::max(max_x, points[i].x);
    min_y = std::min(min_y, points[i].y);
    max_y = std::max(max_y, points[i].y);
  }
  const float width = max_x - min_x, height = max_y - min_y;
  const float extent = std::max(width, height);
  origin_x_ = min_x;
  origin_y_ = min_y;
  if (extent > 0) {
    // Thin sets (a row of points) get cells sized as if the short side were extent/count.
    const float floor_side = extent / static_cast<float>(count);
    // In double: the product of two large extents overflows float.
    const double area = static_cast<double>(std::max(width, floor_side)) * std::max(height, floor_side);
    cell_px_ = static_cast<float>(std::sqrt(area * kPointsPerCell / count));
    cell_px_ = std::max(cell_px_, extent / static_cast<float>(kMaxCellsPerAxis));
  } else {
    cell_px_ = 1.0f;
  }
  inv_cell_ = 1.0f / cell_px_;
  nx_ = std::min(kMaxCellsPerAxis, static_cast<int>(width * inv_cell_) + 1);
  ny_ = std::min(kMaxCellsPerAxis, static_cast<int>(height * inv_cell_) + 1);
  slack_px_ = 1e-3f * cell_px_ + 1e-5f * (std::abs(origin_x_) + std::abs(origin_y_) + (nx_ + ny_) * cell_px_);
  // Counting sort of the points by cell; stable, so each cell lists its points by index.
  std::vector<int> cell_of(count);
  stride_ = nx_ + 2;
  cell_start_.assign(static_cast<size_t>(stride_) * (ny_ + 2) + 1, 0);
  for (int i = 0; i < count; ++i) {
    const int cx = std::min(nx_ - 1, static_cast<int>((points[i].x - origin_x_) * inv_cell_));
    const int cy = std::min(ny_ - 1, static_cast<int>((points[i].y - origin_y_) * inv_cell_));
    cell_of[i] = Slot(cx, cy);
    ++cell_start_[cell_of[i] + 1];
  }
  for (size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  count_ = count;
  xs_.assign(count + kPadding, 0.0f);
  ys_.assign(count + kPadding, 0.0f);
  ids_.assign(count + kPadding, 0);
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (int i = 0; i < count; ++i) {
    const int slot = fill[cell_of[i]]++;
    xs_[slot] = points[i].x;
    ys_[slot] = points[i].y;
    ids_[slot] = i;
  }
  BuildLattice();
}

int PointGrid::Nearest(Point2 p) const {
  if (count_ == 0) return -1;
  if (count_ <= kScanAllMax) return NearestOfAll(p);
  const float fx = (p.x - lattice_origin_x_) * lattice_inv_;
  const float fy = (p.y - lattice_origin_y_) * lattice_inv_;
  if (!(fx >= 0 && fy >= 0 && fx < static_cast<float>(lattice_nx_) && fy < static_cast<float>(lattice_ny_))) {
    return NearestInGrid(p);
  }
  const LatticeCell& c = lattice_[static_cast<int>(fy) * lattice_nx_ + static_cast<int>(fx)];
  if (c.id[0] < 0) return NearestInGrid(p);
  // Same float distances and (distance, index) order as the grid search, over the four slots
  // at once: the least distance, then the least index among the slots at that distance.
  Floats4 xs, ys;
  Ints4 ids;
  std::memcpy(&xs, c.x, sizeof xs);
  std::memcpy(&ys, c.y, sizeof ys);
  std::memcpy(&ids, c.id, sizeof ids);
  const Floats4 dx = xs - p.x, dy = ys - p.y;
  const Floats4 d = dx * dx + dy * dy;
  const float nearest_d = LaneMin4(d);
  return LaneMin4(d == nearest_d ? ids : Ints4{} + std::numeric_limits<int32_t>::max());
}

void PointGrid::BuildLattice() {
  if (count_ <= kScanAllMax) return;
  // Far from the origin, squared float distances could overflow; the grid alone stays exact.
  const float far_corner = std::max({std::abs(origin_x_), std::abs(origin_y_), std::abs(origin_x_ + nx_ * cell_px_),
                                     std::abs(origin_y_ + ny_ * cell_px_)});
  if (!(far_corner <= kMaxLatticeCoordinate)) return;
  lattice_px_ = cell_px_ / kLatticeCellsPerGridCell;
  lattice_inv_ = 1.0f / lattice_px_;
  lattice_origin_x_ = origin_x_ - kLatticeMarginCells * lattice_px_;
  lattice_origin_y_ = origin_y_ - kLatticeMarginCells * lattice_px_;
  lattice_nx_ = nx_ * kLatticeCellsPerGridCell + 2 * kLatticeMarginCells;
  lattice_ny_ = ny_ * kLatticeCellsPerGridCell + 2 * kLatticeMarginCells;
  // Positions in a cell round into it from up to `slack` outside its nominal box.
  const float slack = slack_px_ + 1e-5f * (std::abs(lattice_origin_x_) + std::abs(lattice_origin_y_) +
                                           (lattice_nx_ + lattice_ny_) * lattice_px_);
  static_assert(kLatticeWidth == 4, "LatticeCell holds four slots");
  lattice_.assign(static_cast<size_t>(lattice_nx_) * lattice_ny_, LatticeCell{});
  std::vector<int> slot_of_id(count_), near;
  for (int slot = 0; slot < count_; ++slot) slot_of_id[ids_[slot]] = slot;
  for (int y = 0; y < lattice_ny_; ++y) {
    for (int x = 0; x < lattice_nx_; ++x) {
      lattice_[static_cast<size_t>(y) * lattice_nx_ + x] = LatticeCellAt(x, y, slack, slot_of_id, &near);
    }
  }
}

PointGrid::LatticeCell PointGrid::LatticeCellAt(int x, int y, float slack, const std::vector<int>& slot_of_id,
                                                std::vector<int>* near) const {
  const float x0 = lattice_origin_x_ + x * lattice_px_ - slack;
  const float x1 = lattice_origin_x_ + (x + 1) * lattice_px_ + slack;
  const float y0 = lattice_origin_y_ + y * lattice_px_ - slack;
  const float y1 = lattice_origin_y_ + (y + 1) * lattice_px_ + slack;
  // Every position in the box is within `reach` of the point nearest to the box centre, so
  // its nearest point lies within `reach` of the box: those are the candidates.
  const Point2 centre(0.5f * (x0 + x1), 0.5f * (y0 + y1));
  const int anchor_slot = slot_of_id[NearestInGrid(centre)];
  const double far_x = std::max(std::abs(xs_[anchor_slot] - x0), std::abs(xs_[anchor_slot] - x1));
  const double far_y = std::max(std::abs(ys_[anchor_slot] - y0), std::abs(ys_[anchor_slot] - y1));
  const double reach = std::sqrt(far_x * far_x + far_y * far_y) * (1 + 1e-5) + slack;
  const auto grid_x = [&](double v) {
    return static_cast<int>(std::clamp((v - origin_x_) * inv_cell_, 0.0, nx_ - 1.0));
  };
  const auto grid_y = [&](double v) {
    return static_cast<int>(std::clamp((v - origin_y_) * inv_cell_, 0.0, ny_ - 1.0));
  };
  LatticeCell cell{};
  const auto crowded = [&cell] {
    cell.id[0] = -1;
    return cell;
  };
  // A cell far from every point (an outlier's margin) would gather many candidates: the
  // grid answers its queries instead, which keeps the build linear in the point count.
  if (reach > kMaxReachCells * lattice_px_) {
    return crowded();
  }
  const int gx0 = grid_x(x0 - reach - cell_px_), gx1 = grid_x(x1 + reach + cell_px_);
  const int gy0 = grid_y(y0 - reach - cell_px_), gy1 = grid_y(y1 + reach + cell_px_);
  near->clear();
  for (int gy = gy0; gy <= gy1; ++gy) {
    for (int k = cell_start_[Slot(gx0, gy)], end = cell_start_[Slot(gx1, gy) + 1]; k < end; ++k) {
      const double dx = std::max({0.0, x0 - static_cast<double>(xs_[k]), xs_[k] - static_cast<double>(x1)});
      const double dy = std::max({0.0, y0 - static_cast<double>(ys_[k]), ys_[k] - static_cast<double>(y1)});
      if (dx * dx + dy * dy <= reach * reach) near->push_back(k);
    }
  }
  // A point is no candidate if another one is nearer to all four corners of the box, hence
  // (the set where one point is nearer than another being a half-plane) to all of it. The
  // margin keeps float distances at a query ordered the same way.
  const double corners[4][2] = {{x0, y0}, {x1, y0}, {x0, y1}, {x1, y1}};
  const auto dominates = [&](int k, int j) {
    for (const auto& c : corners) {
      const double kx = xs_[k] - c[0], ky = ys_[k] - c[1];
      const double jx = xs_[j] - c[0], jy = ys_[j] - c[1];
      const double dk = kx * kx + ky * ky, dj = jx * jx + jy * jy;
      if (!(dk < dj * (1 - 1e-4) - 1e-6)) return false;
    }
    return true;
  };
  if (near->size() > kMaxNearCandidates) {
    return crowded();
  }
  int slots[kLatticeWidth] = {}, kept = 0;  // kept >= 1: some point is nearest to each corner
  bool too_many = false;
  for (int j : *near) {
    bool dominated = false;
    for (int k : *near) dominated = dominated || (k != j && dominates(k, j));
    if (dominated) continue;
    if (kept == kLatticeWidth) {
      too_many = true;
      break;
    }
    slots[kept++] = j;
  }
  if (too_many) {
    return crowded();
  }
  for (int c = 0; c < kLatticeWidth; ++c) {  // unused slots repeat the first
    const int slot = slots[c < kept ? c : 0];
    cell.x[c] = xs_[slot], cell.y[c] = ys_[slot], cell.id[c] = ids_[slot];
  }
  return cell;
}

int PointGrid::NearestOfAll(Point2 p) const {
  // Each lane keeps its least (squared distance, index) pair, as in NearestInGrid. The loop is
  // written out twice on purpose: shared through an inline helper (as a class, free functions,
  // by value; five variants), this scan ran 11-14 % slower in matching_bench.
  const Floats8 px = Floats8{} + p.x, py = Floats8{} + p.y;
  const Ints8 lane = {0, 1, 2, 3, 4, 5, 6, 7};
  Floats8 best_d = Floats8{} + std::numeric_limits<float>::infinity();
  Ints8 best_id = Ints8{} + std::numeric_limits<int32_t>::max();
  for (int begin = 0; begin < count_; begin += 8) {
    Floats8 xs, ys;
    Ints8 ids;
    std::memcpy(&xs, xs_.data() + begin, sizeof xs);
    std::memcpy(&ys, ys_.data() + begin, sizeof ys);
    std::memcpy(&ids, ids_.data() + begin, sizeof ids);
    const Floats8 dx = xs - px, dy = ys - py;
    const Floats8 d = dx * dx + dy * dy;
    const Ints8 better = (lane < count_ - begin) & ((d < best_d) | ((d == best_d) & (ids < best_id)));
    best_d = better ? d : best_d;
    best_id = better ? ids : best_id;
  }
  const float nearest_d = LaneMin(best_d);
  return LaneMin(best_d == nearest_d ? best_id : Ints8{} + std::numeric_limits<int32_t>::max());
}

int PointGrid::NearestInGrid(Point2 p) const {
  if (count_ == 0) return -1;
  // Cell of p, clamped into the grid (p may lie outside the bounding box of the set).
  const float fx = std::clamp((p.x - origin_x_) * inv_cell_, 0.0f, static_cast<float>(nx_ - 1));
  const float fy = std::clamp((p.y - origin_y_) * inv_cell_, 0.0f, static_cast<float>(ny_ - 1));
  const int cx = static_cast<int>(fx), cy = static_cast<int>(fy);
  // The 3x3 block around the cell (border cells are empty), eight points at a time: the cells
  // of one row of the block are consecutive in storage, so a row is one range. Each lane keeps
  // its least (squared distance, index) pair. A row of more than eight points goes to rings.
  const Floats8 px = Floats8{} + p.x, py = Floats8{} + p.y;
  const Ints8 lane = {0, 1, 2, 3, 4, 5, 6, 7};
  Floats8 best_d = Floats8{} + std::numeric_limits<float>::infinity();
  Ints8 best_id = Ints8{} + std::numeric_limits<int32_t>::max();
  for (int y = cy - 1; y <= cy + 1; ++y) {
    const int begin = cell_start_[Slot(cx - 1, y)], end = cell_start_[Slot(cx + 1, y) + 1];
    if (end - begin > 8) return NearestByRings(p);
    Floats8 xs, ys;
    Ints8 ids;
    std::memcpy(&xs, xs_.data() + begin, sizeof xs);
    std::memcpy(&ys, ys_.data() + begin, sizeof ys);
    std::memcpy(&ids, ids_.data() + begin, sizeof ids);
    const Floats8 dx = xs - px, dy = ys - py;
    const Floats8 d = dx * dx + dy * dy;
    const Ints8 better = (lane < end - begin) & ((d < best_d) | ((d == best_d) & (ids < best_id)));
    best_d = better ? d : best_d;
    best_id = better ? ids : best_id;
  }
  const float nearest_d = LaneMin(best_d);
  const int nearest = LaneMin(best_d == nearest_d ? best_id : Ints8{} + std::numeric_limits<int32_t>::max());
  // Every point outside the block lies beyond one of the block's sides that are inside the grid.
  float bound = std::numeric_limits<float>::infinity();
  if (cx - 1 > 0) bound = std::min(bound, p.x - (origin_x_ + (cx - 1) * cell_px_));
  if (cx + 1 < nx_ - 1) bound = std::min(bound, origin_x_ + (cx + 2) * cell_px_ - p.x);
  if (cy - 1 > 0) bound = std::min(bound, p.y - (origin_y_ + (cy - 1) * cell_px_));
  if (cy + 1 < ny_ - 1) bound = std::min(bound, origin_y_ + (cy + 2) * cell_px_ - p.y);
  if (bound == std::numeric_limits<float>::infinity()) return nearest;
  bound -= slack_px_;
  if (bound > 0 && nearest_d < bound * bound) return nearest;
  return NearestByRings(p);
}

int PointGrid::NearestByRings(Point2 p) const {
  // Cell of p, clamped into the grid (p may lie outside the bounding box of the set).
  const float fx = std::clamp((p.x - origin_x_) * inv_cell_, 0.0f, static_cast<float>(nx_ - 1));
  const float fy = std::clamp((p.y - origin_y_) * inv_cell_, 0.0f, static_cast<float>(ny_ - 1));
  const int cx = static_cast<int>(fx), cy = static_cast<int>(fy);
  // Candidates compare by DistanceKey, without unpredictable branches.
  uint64_t best_key = std::numeric_limits<uint64_t>::max();
  auto scan = [&](int begin, int end) {
    for (int k = begin; k < end; ++k) best_key = std::min(best_key, DistanceKey(k, p));
  };
  // The cells x0..x1 of one row are consecutive in storage, so a row span is one range.
  auto scan_row = [&](int y, int x0, int x1) { scan(cell_start_[Slot(x0, y)], cell_start_[Slot(x1, y) + 1]); };
  // Ring 1 is the 3x3 block around the cell (scanned as three row spans); ring r > 1 adds the
  // top and bottom rows of the (2r+1)² block and the cells at its sides.
  for (int r = 1;; ++r) {
    const int x0 = cx - r, x1 = cx + r, y0 = cy - r, y1 = cy + r;
    const int xa = std::max(x0, 0), xb = std::min(x1, nx_ - 1);
    if (r == 1) {
      for (int y = std::max(y0, 0); y <= std::min(y1, ny_ - 1); ++y) scan_row(y, xa, xb);
    } else {
      if (y0 >= 0) scan_row(y0, xa, xb);
      if (y1 < ny_) scan_row(y1, xa, xb);
      for (int y = std::max(y0 + 1, 0); y <= std::min(y1 - 1, ny_ - 1); ++y) {
        if (x0 >= 0) scan_row(y, x0, x0);
        if (x1 < nx_) scan_row(y, x1, x1);
      }
    }
    // Every point not yet scanned lies beyond one of the block's sides that are inside the grid.
    float bound = std::numeric_limits<float>::infinity();
    if (x0 > 0) bound = std::min(bound, p.x - (origin_x_ + x0 * cell_px_));
    if (x1 < nx_ - 1) bound = std::min(bound, origin_x_ + (x1 + 1) * cell_px_ - p.x);
    if (y0 > 0) bound = std::min(bound, p.y - (origin_y_ + y0 * cell_px_));
    if (y1 < ny_ - 1) bound = std::min(bound, origin_y_ + (y1 + 1) * cell_px_ - p.y);
    if (bound == std::numeric_limits<float>::infinity()) break;
    bound -= slack_px_;
    if (best_key != std::numeric_limits<uint64_t>::max()) {
      uint32_t bits = static_cast<uint32_t>(best_key >> 32);
      float best_d;
      std::memcpy(&best_d, &bits, sizeof best_d);
      if (bound > 0 && best_d < bound * bound) break;
    }
  }
  return static_cast<int>(best_key & 0xffffffffu);
}

void MutualNearestNeighbours(const Point2* query_points, const PointGrid& query_grid, const Point2* reference_points,
                             const PointGrid& reference_grid, std::vector<Correspondence>* matches) {
  HOILCD_CHECK(matches != nullptr);
  std::vector<int> nearest;
  MutualNearestNeighboursOnGrids(query_points, query_grid, reference_points, reference_grid, &nearest, matches);
}

std::vector<Correspondence> MutualNearestNeighbours(const std::vector<Point2>& query,
                                                    const std::vector<Point2>& reference) {
  const PointGrid query_grid(query.data(), static_cast<int>(query.size()));
  const PointGrid reference_grid(reference.data(), static_cast<int>(reference.size()));
  std::vector<Correspondence> matches;
  MutualNearestNeighbours(query.data(), query_grid, reference.data(), reference_grid, &matches);
  return matches;
}

std::vector<Correspondence> FilterVertical(const std::vector<Point2>& query, const std::vector<Point2>& reference,
                                           const std::vector<Correspondence>& matches, const MatchOptions& options) {
  const std::string problem = options.Check();
  HOILCD_CHECK_MSG(problem.empty(), problem);
  const double tolerance_px = options.vertical_tolerance * options.image_height_px;
  std::vector<Correspondence> kept;
  kept.reserve(matches.size());
  for (const Correspondence& m : matches) {
    HOILCD_CHECK_MSG(m.query >= 0 && m.query < static_cast<int>(query.size()) && m.reference >= 0 &&
                         m.reference < static_cast<int>(reference.size()),
                     "match (" << m.query << ", " << m.reference << ") is out of range");
    if (WithinVerticalTolerance(query[m.query].y, reference[m.reference].y, tolerance_px)) {
      kept.push_back(m);
    }
  }
  return kept;
}

uint64_t PairSeed(uint64_t seed, int query_id, int reference_id) {
  return HashCombine(seed, HashString("ransac"), static_cast<uint64_t>(query_id), static_cast<uint64_t>(reference_id));
}

int PairScorer::Match(const Point2* query_points, const PointGrid& query_grid, const Point2* reference_points,
                      const PointGrid& reference_grid, const MatchOptions& match_options) {
  MutualNearestNeighboursOnGrids(query_points, query_grid, reference_points, reference_grid, &nearest_, &matches_);
  const double tolerance_px = match_options.vertical_tolerance * match_options.image_height_px;
  const size_t capacity = matches_.size();
  ref_x_.resize(capacity);
  ref_y_.resize(capacity);
  query_x_.resize(capacity);
  query_y_.resize(capacity);
  size_t kept = 0;
  for (const Correspondence& m : matches_) {
    const Point2 q = query_points[m.query], r = reference_points[m.reference];
    ref_x_[kept] = r.x;
    ref_y_[kept] = r.y;
    query_x_[kept] = q.x;
    query_y_[kept] = q.y;
    kept += WithinVerticalTolerance(q.y, r.y, tolerance_px) ? 1 : 0;
  }
  return static_cast<int>(kept);
}

int PairScorer::Score(const Point2* query_points, const PointGrid& query_grid, const Point2* reference_points,
                      const PointGrid& reference_grid, const MatchOptions& match_options,
                      const RansacOptions& ransac_options, uint64_t pair_seed) {
  int inliers = 0;
  ScoreVariants(query_points, query_grid, reference_points, reference_grid, match_options, &ransac_options, 1,
                pair_seed, &inliers, nullptr, nullptr);
  return inliers;
}

void PairScorer::ScoreVariants(const Point2* query_points, const PointGrid& query_grid, const Point2* reference_points,
                               const PointGrid& reference_grid, const MatchOptions& match_options,
                               const RansacOptions* variants, int count, uint64_t pair_seed, int* inliers,
                               int64_t* alone_ns, int64_t* total_ns) {
  const int kept = Match(query_points, query_grid, reference_points, reference_grid, match_options);
  ransac_.Count(ref_x_.data(), ref_y_.data(), query_x_.data(), query_y_.data(), kept, variants, count, pair_seed,
                inliers, alone_ns, total_ns);
}

int ScorePair(const std::vector<Point2>& query, const std::vector<Point2>& reference, const MatchOptions& match_options,
              const RansacOptions& ransac_options, uint64_t seed, int query_id, int reference_id) {
  const std::string match_problem = match_options.Check();
  HOILCD_CHECK_MSG(match_problem.empty(), match_problem);
  const std::string ransac_problem = ransac_options.Check();
  HOILCD_CHECK_MSG(ransac_problem.empty(), ransac_problem);
  const PointGrid query_grid(query.data(), static_cast<int>(query.size()));
  const PointGrid reference_grid(reference.data(), static_cast<int>(reference.size()));
  PairScorer scorer;
  return scorer.Score(query.data(), query_grid, reference.data(), reference_grid, match_options, ransac_options,
                      PairSeed(seed, query_id, reference_id));
}

PairMatches MatchPair(const std::vector<Point2>& query, const std::vector<Point2>& reference,
                      const MatchOptions& match_options, const RansacOptions& ransac_options, uint64_t seed,
                      int query_id, int reference_id) {
  const std::string match_problem = match_options.Check();
  HOILCD_CHECK_MSG(match_problem.empty(), match_problem);
  PairMatches out;
  out.matches = FilterVertical(query, reference, MutualNearestNeighbours(query, reference), match_options);
  if (out.matches.size() < 4) {  // as the scorer: fewer than 4 matches run no RANSAC and score 0
    out.inlier.assign(out.matches.size(), 0);
    return out;
  }
  HomographyResult ransac =
      EstimateHomographyRansac(query, reference, out.matches, ransac_options, PairSeed(seed, query_id, reference_id));
  out.inlier = std::move(ransac.inlier_mask);
  out.inliers = ransac.inliers;
  return out;
}

}  // namespace hoilcd
