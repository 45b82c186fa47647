#pragma once
// NeighborGrid: uniform-grid neighbour search over 2D points (Teschner et al. 2003, "Optimized Spatial
// Hashing for Collision Detection of Deformable Objects": cells hashed into a table of ~2N buckets), so
// memory and rebuild time are O(N) however far apart the points are.
//
// Bucket layout (ours): the plane is cut into windows of W x H cells (W H = table size, W = H or 2H),
// a window's cells fill the table in row-major order, and each window starts at a Fibonacci-hashed
// offset (Knuth, TAOCP vol. 3, 6.4). Any crowd denser than ~0.13 agents/m^2 fits in one window, so
// its cells never alias and the grid order (bucket order) is spatially coherent: a contiguous range of
// grid positions is a band of space. Parallel tasks over grid-order ranges then read mostly their own
// neighbours' data, which made the second core worth 1.73-1.8x instead of 1.56x on the 10k-agent
// benchmark (a pure hash scatters each task's agents over the whole crowd). Wider layouts alias like a
// hash, at random window offsets rather than in a pattern.
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

  /// rebuild() in three parts, so that the per-point part can run in parallel inside a caller's own
  /// loop: begin_rebuild(n) once, prepare_point(i, x_i, y_i) for every i (thread-safe for distinct i),
  /// then finish_rebuild(x, y, n) once (the counting sort, serial). Same result as rebuild().
  void begin_rebuild(std::size_t n);
  void prepare_point(std::size_t i, double x, double y) {
    const auto cx = cell_coord(x * inv_cell_), cy = cell_coord(y * inv_cell_);
    point_bucket_[i] = bucket_of(cx, cy);
    point_cx_[i] = cx;
    point_cy_[i] = cy;
  }
  void finish_rebuild(const double* x, const double* y, std::size_t n);

  std::size_t size() const { return count_; }

  /// Calls r2 = visit(j, dx, dy, d2, r2) for every point j with d2 = |p_j - q|^2 <= r2, where
  /// (dx, dy) = p_j - q and r2 starts at radius^2. `radius` must be <= cell_size(). Visit returns the
  /// squared radius it still wants (return r2 unchanged to keep it; smaller to prune, as kNN does).
  template <class Visit>
  void for_each_within(double qx, double qy, double radius, Visit&& visit) const {
    double r2 = radius * radius;
    const std::uint32_t* start = bucket_start_.data();
    const std::uint32_t* index = sorted_index_.data();
    const double* xs = sorted_x_.data();
    const double* ys = sorted_y_.data();
    const std::int32_t* cxs = sorted_cx_.data();
    const std::int32_t* cys = sorted_cy_.data();
    const auto cx = cell_coord(qx * inv_cell_);
    const auto cy = cell_coord(qy * inv_cell_);
    // Distance from q to the neighbouring cells' near edges: a cell farther than the (possibly
    // shrunk) radius is skipped without touching the table.
    const double fx = qx - cx * cell_, fy = qy - cy * cell_;
    const double gap_x[3] = {fx, 0.0, cell_ - fx}, gap_y[3] = {fy, 0.0, cell_ - fy};
    for (std::int32_t oy = -1; oy <= 1; ++oy) {
      for (std::int32_t ox = -1; ox <= 1; ++ox) {
        const double gx = gap_x[ox + 1], gy = gap_y[oy + 1];
        if (gx * gx + gy * gy > r2) continue;
        const std::int32_t ccx = cx + ox, ccy = cy + oy;
        const std::uint32_t b = bucket_of(ccx, ccy);
        for (std::uint32_t k = start[b], e = start[b + 1]; k < e; ++k) {
          if (cxs[k] != ccx || cys[k] != ccy) continue;  // hash alias
          const double dx = xs[k] - qx, dy = ys[k] - qy;
          const double d2 = dx * dx + dy * dy;
          if (d2 <= r2) r2 = visit(index[k], dx, dy, d2, r2);
        }
      }
    }
  }

  /// Point index at position k of the grid order (points grouped by bucket, ascending index within
  /// a bucket): a permutation of 0..size()-1, so iterating it visits every point once, neighbours
  /// close together in time.
  std::uint32_t order(std::size_t k) const { return sorted_index_[k]; }
  /// Inverse of order(): the grid-order position of point i.
  std::uint32_t position_of(std::size_t i) const { return position_of_[i]; }
  /// Coordinates of the point at grid-order position k (the same values as the input arrays).
  double x_at(std::size_t k) const { return sorted_x_[k]; }
  double y_at(std::size_t k) const { return sorted_y_[k]; }
  /// True when grid-order positions k and l lie in the same cell.
  bool same_cell(std::size_t k, std::size_t l) const {
    return sorted_cx_[k] == sorted_cx_[l] && sorted_cy_[k] == sorted_cy_[l];
  }

  /// Calls visit(j, x, y) for every point in the 3x3 cells around the cell of grid-order position
  /// k: the cell itself first, then its edge neighbours, then the corners, so that a k-nearest
  /// search over the block meets near points first and rejects most far ones without inserting
  /// them. Points in consecutive grid-order positions of one cell share this block, so a caller
  /// gathers it once per cell instead of once per point.
  template <class Visit>
  void for_each_in_block(std::size_t k, Visit&& visit) const {
    static constexpr std::int32_t kOffsets[9][2] = {{0, 0},   {-1, 0}, {1, 0},  {0, -1}, {0, 1},
                                                    {-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
    const std::int32_t cx = sorted_cx_[k], cy = sorted_cy_[k];
    for (const auto& o : kOffsets) {
      const std::int32_t ccx = cx + o[0], ccy = cy + o[1];
      const std::uint32_t b = bucket_of(ccx, ccy);
      for (std::uint32_t e = bucket_start_[b], end = bucket_start_[b + 1]; e < end; ++e)
        if (sorted_cx_[e] == ccx && sorted_cy_[e] == ccy) visit(sorted_index_[e], sorted_x_[e], sorted_y_[e]);
    }
  }

 private:
  /// floor() for cell indices without a libm call (x86-64 baseline has no SSE4.1 roundsd).
  static std::int32_t cell_coord(double v) {
    const auto i = static_cast<std::int32_t>(v);
    return i - (v < static_cast<double>(i) ? 1 : 0);
  }

  // Row-major position of the cell inside its window plus the window's hashed offset (see the header);
  // Fibonacci hashing takes the HIGH bits of the product, which are the well-mixed ones.
  std::uint32_t bucket_of(std::int32_t cx, std::int32_t cy) const {
    const unsigned bits = 64 - shift_, wbits = (bits + 1) / 2, hbits = bits / 2;
    const auto ux = static_cast<std::uint32_t>(cx), uy = static_cast<std::uint32_t>(cy);
    const std::uint32_t local = ((uy & ((1u << hbits) - 1)) << wbits) | (ux & ((1u << wbits) - 1));
    const std::uint64_t window = (static_cast<std::uint64_t>(ux >> wbits) << 32) | (uy >> hbits);
    const auto offset = static_cast<std::uint32_t>((window * 0x9E3779B97F4A7C15ull) >> shift_);
    return (local + offset) & ((1u << bits) - 1);
  }

  double cell_ = 2.0, inv_cell_ = 0.5;
  std::size_t count_ = 0;
  unsigned shift_ = 60;                      // 64 - log2(table size)
  std::vector<std::uint32_t> bucket_start_;  // (table + 1) prefix sums
  std::vector<std::uint32_t> point_bucket_;  // (n) bucket of each point (scratch)
  std::vector<std::uint32_t> sorted_index_;  // (n) point index in bucket order
  std::vector<std::uint32_t> position_of_;   // (n) inverse of sorted_index_
  std::vector<double> sorted_x_, sorted_y_;  // (n) coordinates in bucket order (cache locality)
  std::vector<std::int32_t> sorted_cx_, sorted_cy_;
  std::vector<std::int32_t> point_cx_, point_cy_;  // (n) cell of each point (scratch)
};

}  // namespace crowdlab
