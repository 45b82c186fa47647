#pragma once
// NeighborGrid: uniform-grid neighbour search over 2D points (Teschner et al. 2003, "Optimized Spatial
// Hashing for Collision Detection of Deformable Objects": cells hashed into a table of ~2N buckets), so
// memory and rebuild time are O(N) however far apart the points are.
//
// Rebuild is a stable counting sort of the points by bucket into reused buffers: no allocation once
// the capacity has been reached, and the visit order is a deterministic function of the input.
// A query scans the 3x3 cells around the query point, so every query radius must be <= cell size.
// Entries whose cell differs from the scanned cell (hash aliases) are skipped, so nothing is visited
// twice. Coordinates are (x, y) in metres; the crowd layer maps world (x, z) to (x, y).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace crowdlab {

class NeighborGrid {
 public:
  /// cell_size_m: > 0 and >= every radius later passed to for_each_within().
  explicit NeighborGrid(double cell_size_m = 2.0);

  void set_cell_size(double cell_size_m);
  double cell_size() const { return cell_; }

  /// Rebuilds the grid from n points given as separate x and y arrays (metres).
  void rebuild(const double* x, const double* y, std::size_t n);

  std::size_t size() const { return count_; }

  /// Calls r2 = visit(j, dx, dy, d2, r2) for every point j with d2 = |p_j - q|^2 <= r2, where
  /// (dx, dy) = p_j - q and r2 starts at radius^2. `radius` must be <= cell_size(). Visit returns the
  /// squared radius it still wants (return r2 unchanged to keep it; smaller to prune, as kNN does).
  template <class Visit>
  void for_each_within(double qx, double qy, double radius, Visit&& visit) const {
    double r2 = radius * radius;
    const auto cx = static_cast<std::int32_t>(std::floor(qx * inv_cell_));
    const auto cy = static_cast<std::int32_t>(std::floor(qy * inv_cell_));
    for (std::int32_t oy = -1; oy <= 1; ++oy) {
      for (std::int32_t ox = -1; ox <= 1; ++ox) {
        const std::int32_t ccx = cx + ox, ccy = cy + oy;
        const std::uint32_t b = bucket_of(ccx, ccy);
        for (std::uint32_t k = bucket_start_[b], e = bucket_start_[b + 1]; k < e; ++k) {
          if (sorted_cx_[k] != ccx || sorted_cy_[k] != ccy) continue;  // hash alias
          const double dx = sorted_x_[k] - qx, dy = sorted_y_[k] - qy;
          const double d2 = dx * dx + dy * dy;
          if (d2 <= r2) r2 = visit(sorted_index_[k], dx, dy, d2, r2);
        }
      }
    }
  }

 private:
  std::uint32_t bucket_of(std::int32_t cx, std::int32_t cy) const {
    std::uint32_t h =
        static_cast<std::uint32_t>(cx) * 0x9E3779B1u ^ static_cast<std::uint32_t>(cy) * 0x85EBCA77u;
    h ^= h >> 15;
    return h & mask_;
  }

  double cell_ = 2.0, inv_cell_ = 0.5;
  std::size_t count_ = 0;
  std::uint32_t mask_ = 0;
  std::vector<std::uint32_t> bucket_start_;  // (table + 1) prefix sums
  std::vector<std::uint32_t> point_bucket_;  // (n) bucket of each point (scratch)
  std::vector<std::uint32_t> sorted_index_;  // (n) point index in bucket order
  std::vector<double> sorted_x_, sorted_y_;  // (n) coordinates in bucket order (cache locality)
  std::vector<std::int32_t> sorted_cx_, sorted_cy_;
};

}  // namespace crowdlab
