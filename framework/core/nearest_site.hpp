#pragma once
// NearestSiteGrid: for a query point, the nearest of a fixed set of sites, chosen exactly as a brute-force
// scan of the sites in their listed order would choose it (the smallest squared distance, computed as
// (site - query).squaredNorm(); ties go to the site listed first), through a uniform grid of the sites
// searched in growing shells of cells (the cell technique of Bentley, Weide & Yao, "Optimal
// expected-time algorithms for closest point problems", ACM TOMS 6(4), 1980).
//
//   Inputs:  points, every point (m); sites, the indices into `points` that may be chosen (any order,
//            repeats allowed); the grid keeps copies of what it needs. Queries: any point (m).
//   Outputs: nearest(query) is the index into `points` of the chosen site; -1 when there is no site.
// Why a grid and not a scan: the MPFB2 model anchors its ~5,800 helper vertices to the nearest of its
// ~13,400 body vertices on every load, which every `crowdlab` command that reads a spec paid as 78
// million distances (issue 31: about a third of `crowdlab validate`'s CPU). The result is the scan's.
#include <array>
#include <cstdint>
#include <vector>

#include "framework/core/math_types.hpp"

namespace crowdlab {

class NearestSiteGrid {
 public:
  NearestSiteGrid(const std::vector<Vec3>& points, const std::vector<int>& sites);

  /// The index into `points` of the nearest site to `query` (ties: the site listed first); -1 if none.
  int nearest(const Vec3& query) const;

 private:
  /// Cell coordinate of `p` along axis `a`, clamped into the grid.
  int cell_coordinate(const Vec3& p, int a) const;
  /// Scans the sites of the cells at Chebyshev distance exactly `ring` from `centre`.
  void scan_ring(const Vec3& query, const std::array<int, 3>& centre, int ring, double& best_d2,
                 int& best_rank) const;

  std::vector<int> sites_;      ///< a copy of the constructor's `sites`
  Vec3 origin_ = Vec3::Zero();  ///< the low corner of cell (0, 0, 0) (m)
  double cell_m_ = 1.0;         ///< edge of a cubic cell (m)
  std::array<int, 3> cells_{1, 1, 1};
  std::vector<std::uint32_t> start_;        ///< cell c's sites are sorted_rank_[start_[c] .. start_[c + 1])
  std::vector<std::uint32_t> sorted_rank_;  ///< ranks (positions in `sites`) sorted by cell
  std::vector<Vec3> sorted_point_;          ///< their points, in the same order (m)
};

}  // namespace crowdlab
