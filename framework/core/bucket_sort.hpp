#pragma once
// bucket_sort: a stable counting sort of n items by bucket (Knuth, TAOCP vol. 3, §5.2, "distribution
// counting"), the rebuild step of the uniform grids: the 2D neighbour grid of the crowd stage
// (framework/crowd/neighbor_grid.hpp) and the 3D grid of body centres of surface crowds
// (framework/surface/surface_crowd.cpp).
//
//   Inputs:  bucket[i] in [0, start.size() - 1) for the n items i; `start` sized to buckets + 1.
//   Outputs: start[b] .. start[b + 1] is the range of sorted positions of bucket b (start[buckets] = n);
//            visit(i, position) is called once per item with its sorted position, items of one bucket in
//            increasing index order (stable), so callers scatter their per-item data in the same pass.
// The count is turned into inclusive prefix sums and the items are placed in reverse with a
// pre-decrement: each start then ends at its bucket's begin with no extra pass or scratch array.
// O(n + buckets) time, no allocation.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace crowdlab {

template <class Visit>
void bucket_sort(const std::uint32_t* bucket, std::size_t n, std::vector<std::uint32_t>& start,
                 Visit&& visit) {
  const std::size_t buckets = start.size() - 1;
  std::fill(start.begin(), start.end(), 0u);
  for (std::size_t i = 0; i < n; ++i) ++start[bucket[i]];
  for (std::size_t b = 1; b < buckets; ++b) start[b] += start[b - 1];
  start[buckets] = static_cast<std::uint32_t>(n);
  for (std::size_t i = n; i-- > 0;) visit(i, --start[bucket[i]]);
}

}  // namespace crowdlab
