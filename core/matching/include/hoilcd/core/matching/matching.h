// Point matching shared by SLCD and DLCD (paper 4.1.1, 4.1.2, 5.2): mutual nearest neighbours on
// 2-D coordinates, the vertical-consistency filter, and the full pair score
// (MNN -> vertical filter -> RANSAC homography inlier count).
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <opencv2/core/types.hpp>

#include "hoilcd/core/estimators/homography_ransac.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// Point2 is defined in core/geometry/point.h; Correspondence in homography_ransac.h.

// Defaults and ranges: Table() in matching.cpp.
struct MatchOptions {
  double vertical_tolerance;  // τ_y, fraction of image height (|y_q - y_r| <= τ_y * H)
  int image_height_px;        // H, px

  MatchOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<MatchOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

inline bool operator==(const MatchOptions& a, const MatchOptions& b) {
  return a.vertical_tolerance == b.vertical_tolerance && a.image_height_px == b.image_height_px;
}
inline bool operator!=(const MatchOptions& a, const MatchOptions& b) { return !(a == b); }

// Exact nearest-neighbour queries on one point set in about O(1) each. Small sets (up to 96
// points, as frames' keypoints and HOI points) are scanned whole, eight points at a time. Larger
// ones get a uniform bucket grid: points stored reordered by cell (structure of arrays) for
// locality and scanned eight at a time, plus a finer candidate lattice over the set's bounding
// box (and a margin) that lists, per lattice cell, every point that can be nearest to some
// position in it (four fixed slots, coordinates included), so a query there compares four points
// at once without branches; queries outside it, in cells with more candidates, or in sets far
// from the origin search the grid.
class PointGrid {
 public:
  PointGrid() = default;
  PointGrid(const Point2* points, int count);
  int size() const { return count_; }
  // Index of the point nearest to p (squared Euclidean distance in float; ties go to the lower
  // index); -1 when the grid is empty.
  int Nearest(Point2 p) const;

 private:
  // Nearest() by rings of cells around p's cell, for when the 3x3 block cannot decide.
  int NearestByRings(Point2 p) const;
  // Nearest() from the 3x3 block of grid cells around p (or by rings).
  int NearestInGrid(Point2 p) const;
  // Nearest() by comparing p with every point, eight at a time (small sets).
  int NearestOfAll(Point2 p) const;
  // Fills the candidate lattice (after the grid is built; not for small sets).
  void BuildLattice();
  // The candidates of lattice cell (x, y) whose box reaches `slack` px beyond its nominal one;
  // slot_of_id maps an original index to its slot; near is scratch.
  struct LatticeCell;
  LatticeCell LatticeCellAt(int x, int y, float slack, const std::vector<int>& slot_of_id,
                            std::vector<int>* near) const;
  // (squared distance bits, original index) of stored point k from p: the bits of a
  // non-negative float order like the float, so the least key is the nearest point with ties
  // going to the lower index.
  uint64_t DistanceKey(int k, Point2 p) const {
    const float dx = xs_[k] - p.x, dy = ys_[k] - p.y;
    const float d = dx * dx + dy * dy;
    uint32_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    return (static_cast<uint64_t>(bits) << 32) | static_cast<uint32_t>(ids_[k]);
  }
  // Index into cell_start_ of cell (x, y), for x in [-1, nx_] and y in [-1, ny_]: the grid has
  // a border of empty cells, so a 3x3 block never needs clipping.
  int Slot(int x, int y) const { return (y + 1) * stride_ + x + 1; }

  int count_ = 0;                      // number of points
  std::vector<float> xs_, ys_;         // point coordinates in cell order (padded), px
  std::vector<int> ids_;               // original index of each stored point (padded)
  std::vector<int> cell_start_;        // points of the cell at slot s are
                                       // [cell_start_[s], cell_start_[s+1])
  float origin_x_ = 0, origin_y_ = 0;  // lower corner of the grid, px
  float cell_px_ = 1, inv_cell_ = 1;   // cell side, px, and its inverse
  float slack_px_ = 0;                 // cell-assignment rounding can put a point this far
                                       // outside its cell's nominal box, px
  int nx_ = 0, ny_ = 0;                // cells per row and per column
  int stride_ = 2;                     // slots per row, nx_ + 2
  // Candidate lattice: cell (x, y) spans lattice_origin + [x, x+1) * lattice_px_, and its
  // candidates' coordinates and original indices sit in lattice_[y * lattice_nx_ + x], in four
  // slots (unused ones repeat the first; id[0] < 0: crowded, search the grid). Empty when not
  // built. The coordinates are copies, so a query reads one cell instead of following slots.
  struct LatticeCell {
    float x[4], y[4];
    int32_t id[4];
  };
  float lattice_origin_x_ = 0, lattice_origin_y_ = 0;
  float lattice_px_ = 1, lattice_inv_ = 1;
  int lattice_nx_ = 0, lattice_ny_ = 0;
  std::vector<LatticeCell> lattice_;
};

// Mutual nearest neighbours on 2-D coordinates (PointGrid lookups: about O(n + m) for large sets,
// vector scans of up to 96 points for small ones), ties broken by lower index. Pairs are sorted
// by query index.
std::vector<Correspondence> MutualNearestNeighbours(const std::vector<Point2>& query,
                                                    const std::vector<Point2>& reference);
// The same on prebuilt grids; query_points/reference_points are the sets the grids were built on.
void MutualNearestNeighbours(const Point2* query_points, const PointGrid& query_grid, const Point2* reference_points,
                             const PointGrid& reference_grid, std::vector<Correspondence>* matches);

// Drops pairs with |y_q - y_r| > τ_y * H.
std::vector<Correspondence> FilterVertical(const std::vector<Point2>& query, const std::vector<Point2>& reference,
                                           const std::vector<Correspondence>& matches, const MatchOptions& options);

// The RANSAC stream of one (query, reference) pair: KeyedRng(seed, "ransac", query_id,
// reference_id) is Rng(PairSeed(seed, query_id, reference_id)).
uint64_t PairSeed(uint64_t seed, int query_id, int reference_id);

// Full score of a pair: MNN -> vertical filter -> RANSAC; returns the inlier count. The RANSAC
// stream is keyed by (seed, "ransac", query_id, reference_id).
int ScorePair(const std::vector<Point2>& query, const std::vector<Point2>& reference, const MatchOptions& match_options,
              const RansacOptions& ransac_options, uint64_t seed, int query_id, int reference_id);

// The matches behind one pair's score, for pictures (the report's gallery): the matches RANSAC
// ran on (indices into query and reference) and which of them it counts as inliers.
struct PairMatches {
  std::vector<Correspondence> matches;  // MatchPair's: after the vertical filter, sorted by query index
  std::vector<uint8_t> inlier;          // per match: 1 when a RANSAC inlier
  int inliers = 0;                      // the pair's score
};
// The pairs kept by MNN and the vertical filter, and RANSAC's inliers among them; inliers equals
// ScorePair(...) with the same arguments.
PairMatches MatchPair(const std::vector<Point2>& query, const std::vector<Point2>& reference,
                      const MatchOptions& match_options, const RansacOptions& ransac_options, uint64_t seed,
                      int query_id, int reference_id);

// Scores pairs of prebuilt grids, reusing its scratch buffers between calls (one per thread).
// Score() equals ScorePair() on the same points; options are not re-checked here.
class PairScorer {
 public:
  int Score(const Point2* query_points, const PointGrid& query_grid, const Point2* reference_points,
            const PointGrid& reference_grid, const MatchOptions& match_options, const RansacOptions& ransac_options,
            uint64_t pair_seed);
  // Score() under each of `count` RANSAC variants, the MNN and vertical filter done once for all
  // and the samples drawn once for variants that share them (RansacCounter): inliers[v] =
  // Score(..., variants[v], pair_seed). alone_ns and total_ns as in RansacCounter::Count (both null:
  // not timed; 0 when fewer than 4 matches are kept: no RANSAC runs).
  void ScoreVariants(const Point2* query_points, const PointGrid& query_grid, const Point2* reference_points,
                     const PointGrid& reference_grid, const MatchOptions& match_options, const RansacOptions* variants,
                     int count, uint64_t pair_seed, int* inliers, int64_t* alone_ns, int64_t* total_ns);

 private:
  std::vector<Correspondence> matches_;
  std::vector<int> nearest_;  // MNN scratch: each point's nearest in the other set
  std::vector<float> ref_x_, ref_y_, query_x_, query_y_;
  RansacCounter ransac_;

  // MNN and the vertical filter into the coordinate arrays; returns how many matches are kept.
  int Match(const Point2* query_points, const PointGrid& query_grid, const Point2* reference_points,
            const PointGrid& reference_grid, const MatchOptions& match_options);
};

}  // namespace hoilcd
