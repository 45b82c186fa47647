#include "framework/core/nearest_site.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "framework/core/aabb.hpp"
#include "framework/core/bucket_sort.hpp"

namespace crowdlab {
namespace {

constexpr double kSitesPerCell = 2.0;  // a few sites per cell: the first shells hold the answer
constexpr int kMaxCellsPerAxis = 256;

}  // namespace

NearestSiteGrid::NearestSiteGrid(const std::vector<Vec3>& points, const std::vector<int>& sites)
    : sites_(sites) {
  // A site with a non-finite coordinate is never nearer than anything (the scan's `d2 < best` is false
  // for NaN and infinity), so it is left out of the grid.
  std::vector<std::uint32_t> ranks;
  Aabb box;
  for (size_t rank = 0; rank < sites.size(); ++rank) {
    const Vec3& p = points[static_cast<size_t>(sites[rank])];
    if (!p.allFinite()) continue;
    ranks.push_back(static_cast<std::uint32_t>(rank));
    box.extend(p);
  }
  if (ranks.empty()) return;
  const Vec3 extent = (box.hi - box.lo).cwiseMax(1e-9);
  // Cubic cells holding about kSitesPerCell sites each if the sites filled their box.
  const double volume = extent.x() * extent.y() * extent.z();
  cell_m_ = std::max(std::cbrt(volume * kSitesPerCell / static_cast<double>(ranks.size())),
                     extent.maxCoeff() / kMaxCellsPerAxis);
  origin_ = box.lo;
  for (size_t a = 0; a < 3; ++a) {
    const double count = std::floor(extent[static_cast<int>(a)] / cell_m_) + 1.0;  // huge boxes: inf, NaN
    cells_[a] = count >= kMaxCellsPerAxis ? kMaxCellsPerAxis : count >= 1.0 ? static_cast<int>(count) : 1;
  }
  const size_t cell_count = static_cast<size_t>(cells_[0]) * cells_[1] * cells_[2];
  std::vector<std::uint32_t> bucket(ranks.size());
  for (size_t k = 0; k < ranks.size(); ++k) {
    const Vec3& p = points[static_cast<size_t>(sites[ranks[k]])];
    const int x = cell_coordinate(p, 0), y = cell_coordinate(p, 1), z = cell_coordinate(p, 2);
    bucket[k] = static_cast<std::uint32_t>((static_cast<size_t>(z) * cells_[1] + y) * cells_[0] + x);
  }
  start_.assign(cell_count + 1, 0);
  sorted_rank_.resize(ranks.size());
  sorted_point_.resize(ranks.size());
  bucket_sort(bucket.data(), bucket.size(), start_, [&](size_t k, std::uint32_t position) {
    sorted_rank_[position] = ranks[k];
    sorted_point_[position] = points[static_cast<size_t>(sites[ranks[k]])];
  });
}

int NearestSiteGrid::cell_coordinate(const Vec3& p, int a) const {
  const double c = std::floor((p[a] - origin_[a]) / cell_m_);
  if (!(c >= 0)) return 0;  // also NaN
  return static_cast<int>(std::min(c, static_cast<double>(cells_[static_cast<size_t>(a)] - 1)));
}

void NearestSiteGrid::scan_ring(const Vec3& query, const std::array<int, 3>& centre, int ring,
                                double& best_d2, int& best_rank) const {
  std::array<int, 3> lo{}, hi{};
  for (size_t a = 0; a < 3; ++a) {
    lo[a] = std::max(centre[a] - ring, 0);
    hi[a] = std::min(centre[a] + ring, cells_[a] - 1);
  }
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x) {
        const int chebyshev =
            std::max({std::abs(x - centre[0]), std::abs(y - centre[1]), std::abs(z - centre[2])});
        if (chebyshev != ring) continue;  // scanned in an earlier shell
        const size_t cell = (static_cast<size_t>(z) * cells_[1] + y) * cells_[0] + x;
        for (std::uint32_t k = start_[cell]; k < start_[cell + 1]; ++k) {
          const int rank = static_cast<int>(sorted_rank_[k]);
          const double d2 = (sorted_point_[k] - query).squaredNorm();
          if (d2 < best_d2 || (d2 == best_d2 && rank < best_rank)) {
            best_d2 = d2;
            best_rank = rank;
          }
        }
      }
}

int NearestSiteGrid::nearest(const Vec3& query) const {
  if (sorted_rank_.empty()) return -1;
  const std::array<int, 3> centre{cell_coordinate(query, 0), cell_coordinate(query, 1),
                                  cell_coordinate(query, 2)};
  double best_d2 = std::numeric_limits<double>::infinity();
  int best_rank = -1;
  for (int ring = 0;; ++ring) {
    scan_ring(query, centre, ring, best_d2, best_rank);
    // Every site not scanned yet lies outside the block of cells centre +- ring; the query's distance
    // to that block's nearest open face bounds their distance from below. A face beyond the grid has
    // no sites behind it. Stop only when the best is strictly closer, so that an equally near site
    // listed earlier is never missed.
    double bound = std::numeric_limits<double>::infinity();
    for (size_t a = 0; a < 3; ++a) {
      const int a_int = static_cast<int>(a);
      if (centre[a] - ring > 0)
        bound = std::min(bound, query[a_int] - (origin_[a_int] + (centre[a] - ring) * cell_m_));
      if (centre[a] + ring < cells_[a] - 1)
        bound = std::min(bound, origin_[a_int] + (centre[a] + ring + 1) * cell_m_ - query[a_int]);
    }
    if (bound == std::numeric_limits<double>::infinity()) break;  // every cell scanned
    // The margin covers the rounding of the cell a site was sorted into (an ulp of its coordinate).
    bound -= 1e-9 * cell_m_;
    if (bound > 0 && best_d2 < bound * bound) break;
  }
  // No site compared finite (a NaN query): the scan chooses none either.
  return best_rank < 0 ? -1 : sites_[static_cast<size_t>(best_rank)];
}

}  // namespace crowdlab
