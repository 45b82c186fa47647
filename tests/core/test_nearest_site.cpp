// Properties of core/nearest_site.hpp: the grid chooses exactly the site a brute-force scan in listed
// order chooses (the smallest squared distance, ties to the site listed first), for queries inside and
// far outside the sites' box, on lattices full of ties, with repeated sites, flat site sets, one site,
// no site and a NaN query; and the MPFB2 model's helper anchors are the scan's.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "framework/core/nearest_site.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_nearest_site {

using namespace crowdlab;

namespace {

int scan_nearest(const std::vector<Vec3>& points, const std::vector<int>& sites, const Vec3& query) {
  int best = -1;
  double best_d2 = HUGE_VAL;
  for (int s : sites) {
    const double d2 = (points[static_cast<size_t>(s)] - query).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = s;
    }
  }
  return best;
}

/// Every point queried against a grid of `sites`: the grid's choice equals the scan's for all of them.
int mismatches(const std::vector<Vec3>& points, const std::vector<int>& sites,
               const std::vector<Vec3>& queries) {
  const NearestSiteGrid grid(points, sites);
  int wrong = 0;
  for (const Vec3& q : queries) wrong += grid.nearest(q) != scan_nearest(points, sites, q);
  return wrong;
}

}  // namespace

TEST_CASE("nearest site: the grid chooses what a scan in listed order chooses") {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SECTION("random sites; queries inside the box and up to 5x outside it") {
    std::vector<Vec3> points;
    for (int i = 0; i < 3000; ++i) points.emplace_back(u(rng), 2 * u(rng), 0.3 * u(rng));
    std::vector<int> sites;
    for (int i = 0; i < 3000; i += 3) sites.push_back(i);
    std::vector<Vec3> queries = points;
    for (int i = 0; i < 500; ++i) queries.emplace_back(5 * u(rng), 10 * u(rng), 5 * u(rng));
    CHECK(mismatches(points, sites, queries) == 0);
  }
  SECTION("an integer lattice: most queries have several equally near sites, listed in shuffled order") {
    std::vector<Vec3> points;
    for (int x = 0; x < 12; ++x)
      for (int y = 0; y < 9; ++y)
        for (int z = 0; z < 7; ++z) points.emplace_back(0.1 * x, 0.1 * y, 0.1 * z);
    std::vector<int> sites(points.size());
    for (size_t i = 0; i < sites.size(); ++i) sites[i] = static_cast<int>(i);
    std::shuffle(sites.begin(), sites.end(), rng);
    sites.resize(sites.size() / 2);
    std::vector<Vec3> queries;
    for (int i = 0; i < 2000; ++i)  // half-lattice points: equidistant from 2, 4 or 8 lattice sites
      queries.emplace_back(0.05 * std::floor(26 * (u(rng) + 1) / 2), 0.05 * std::floor(20 * (u(rng) + 1) / 2),
                           0.05 * std::floor(16 * (u(rng) + 1) / 2));
    CHECK(mismatches(points, sites, queries) == 0);
  }
  SECTION("repeated sites, coincident points, a flat set and a single site") {
    std::vector<Vec3> points = {{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0.5, 0, 0}, {0.25, 0, 0}};
    std::vector<Vec3> queries = {{0.5, 1, 0}, {0.75, 0, 0}, {0, 0, 0}, {-3, 2, 1}, {0.3, -0.2, 0.1}};
    CHECK(mismatches(points, {1, 0, 3, 2, 3, 1}, queries) == 0);
    CHECK(mismatches(points, {4, 5}, queries) == 0);
    CHECK(mismatches(points, {2}, queries) == 0);
    const NearestSiteGrid one(points, {2});
    CHECK(one.nearest({-100, 50, 7}) == 2);
  }
  SECTION("no site, and a NaN query, choose none; non-finite sites are never chosen; huge boxes") {
    const double nan = std::numeric_limits<double>::quiet_NaN(),
                 inf = std::numeric_limits<double>::infinity();
    const std::vector<Vec3> points = {{0, 0, 0},   {1, 1, 1},      {nan, 0, 0},
                                      {0, inf, 0}, {-1e300, 0, 0}, {1e300, 0, 0}};
    CHECK(NearestSiteGrid(points, {}).nearest({0, 0, 0}) == -1);
    CHECK(NearestSiteGrid(points, {0, 1}).nearest({nan, 0, 0}) == -1);
    CHECK(NearestSiteGrid(points, {2, 3}).nearest({0, 0, 0}) == -1);
    const std::vector<Vec3> queries = {
        {0.1, 0.2, 0}, {0.9, 2, 1}, {-5e299, 0, 0}, {6e299, 1, 1}, {0, 0, inf}};
    CHECK(mismatches(points, {2, 3, 1, 0}, queries) == 0);
    CHECK(mismatches(points, {4, 0, 5, 1, 2}, queries) == 0);
  }
}

}  // namespace test_nearest_site
