#include "framework/crowd/neighbor_grid.hpp"

#include <algorithm>

#include "framework/core/error.hpp"

namespace crowdlab {

NeighborGrid::NeighborGrid(double cell_size_m) {
  set_cell_size(cell_size_m);
}

void NeighborGrid::set_cell_size(double cell_size_m) {
  if (!(cell_size_m > 0.0) || !std::isfinite(cell_size_m))
    throw InputError("neighbour grid: cell size must be a positive finite number of metres");
  cell_ = cell_size_m;
  inv_cell_ = 1.0 / cell_size_m;
}

void NeighborGrid::rebuild(const double* x, const double* y, std::size_t n) {
  count_ = n;
  std::size_t table = 16;
  unsigned bits = 4;
  while (table < 2 * n) table *= 2, ++bits;
  shift_ = 64 - bits;
  if (bucket_start_.size() != table + 1) bucket_start_.assign(table + 1, 0);
  std::fill(bucket_start_.begin(), bucket_start_.end(), 0u);
  if (sorted_index_.size() < n) {
    point_bucket_.resize(n);
    sorted_index_.resize(n);
    sorted_x_.resize(n);
    sorted_y_.resize(n);
    sorted_cx_.resize(n);
    sorted_cy_.resize(n);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto cx = cell_coord(x[i] * inv_cell_);
    const auto cy = cell_coord(y[i] * inv_cell_);
    const std::uint32_t b = bucket_of(cx, cy);
    point_bucket_[i] = b;
    ++bucket_start_[b + 1];
  }
  for (std::size_t b = 0; b < table; ++b) bucket_start_[b + 1] += bucket_start_[b];
  // Stable scatter: within a bucket, points keep increasing index order.
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t slot = bucket_start_[point_bucket_[i]]++;
    sorted_index_[slot] = static_cast<std::uint32_t>(i);
    sorted_x_[slot] = x[i];
    sorted_y_[slot] = y[i];
    sorted_cx_[slot] = cell_coord(x[i] * inv_cell_);
    sorted_cy_[slot] = cell_coord(y[i] * inv_cell_);
  }
  // Scatter advanced each start to the next bucket's start: shift back by one bucket.
  for (std::size_t b = table; b > 0; --b) bucket_start_[b] = bucket_start_[b - 1];
  bucket_start_[0] = 0;
}

}  // namespace crowdlab
