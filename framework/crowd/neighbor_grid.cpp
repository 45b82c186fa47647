#include "framework/crowd/neighbor_grid.hpp"

#include <algorithm>

#include "framework/core/bucket_sort.hpp"
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
  begin_rebuild(n);
  for (std::size_t i = 0; i < n; ++i) prepare_point(i, x[i], y[i]);
  finish_rebuild(x, y, n);
}

void NeighborGrid::begin_rebuild(std::size_t n) {
  count_ = n;
  std::size_t table = 16;
  unsigned bits = 4;
  while (table < 2 * n) table *= 2, ++bits;
  shift_ = 64 - bits;
  if (bucket_start_.size() != table + 1) bucket_start_.assign(table + 1, 0);
  if (sorted_index_.size() < n) {
    point_bucket_.resize(n);
    point_cx_.resize(n);
    point_cy_.resize(n);
    sorted_index_.resize(n);
    position_of_.resize(n);
    sorted_x_.resize(n);
    sorted_y_.resize(n);
    sorted_cx_.resize(n);
    sorted_cy_.resize(n);
  }
}

void NeighborGrid::finish_rebuild(const double* x, const double* y, std::size_t n) {
  bucket_sort(point_bucket_.data(), n, bucket_start_, [&](std::size_t i, std::uint32_t slot) {
    sorted_index_[slot] = static_cast<std::uint32_t>(i);
    position_of_[i] = slot;
    sorted_x_[slot] = x[i];
    sorted_y_[slot] = y[i];
    sorted_cx_[slot] = point_cx_[i];
    sorted_cy_[slot] = point_cy_[i];
  });
}

}  // namespace crowdlab
