// NeighborGrid (framework/crowd/neighbor_grid.hpp) against brute force, on layouts that fit one bucket
// window and on layouts far wider than it (where cells alias), and its grid-order invariants.
#include <algorithm>
#include <catch2/catch.hpp>
#include <vector>

#include "framework/core/seed.hpp"
#include "framework/crowd/neighbor_grid.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_neighbor_grid {

using namespace crowdlab;

namespace {
void check_against_brute_force(const std::vector<double>& x, const std::vector<double>& y, double radius) {
  NeighborGrid grid(radius);
  grid.rebuild(x.data(), y.data(), x.size());
  std::vector<char> seen(x.size());
  for (std::size_t q = 0; q < x.size(); q += 7) {
    std::vector<std::uint32_t> found;
    grid.for_each_within(x[q], y[q], radius, [&](std::uint32_t j, double, double, double, double r2) {
      found.push_back(j);
      return r2;
    });
    std::vector<std::uint32_t> expected;
    for (std::size_t j = 0; j < x.size(); ++j) {
      const double dx = x[j] - x[q], dy = y[j] - y[q];
      if (dx * dx + dy * dy <= radius * radius) expected.push_back(static_cast<std::uint32_t>(j));
    }
    std::sort(found.begin(), found.end());
    REQUIRE(found == expected);  // each neighbour exactly once
  }
  // order() is a permutation and position_of() its inverse.
  for (std::size_t k = 0; k < x.size(); ++k) {
    REQUIRE(grid.position_of(grid.order(k)) == k);
    seen[grid.order(k)] = 1;
  }
  CHECK(std::all_of(seen.begin(), seen.end(), [](char c) { return c == 1; }));
}
}  // namespace

TEST_CASE("neighbour grid: a dense crowd and a layout far wider than one bucket window", "[grid]") {
  Rng rng(11);
  for (const double extent_m : {20.0, 3000.0}) {  // 3 km: cells alias across windows
    std::vector<double> x(2000), y(2000);
    for (std::size_t i = 0; i < x.size(); ++i) {
      x[i] = extent_m * (uniform01(rng) - 0.5);
      y[i] = (i % 2 == 0 ? extent_m : 3.0) * (uniform01(rng) - 0.5);  // half of them on a long strip
    }
    check_against_brute_force(x, y, 2.0);
  }
}

TEST_CASE("neighbour grid: split rebuild (prepare_point in any order) equals rebuild", "[grid]") {
  Rng rng(12);
  std::vector<double> x(500), y(500);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 40 * uniform01(rng) - 20, y[i] = 40 * uniform01(rng) - 20;
  NeighborGrid a(2.0), b(2.0);
  a.rebuild(x.data(), y.data(), x.size());
  b.begin_rebuild(x.size());
  for (std::size_t i = x.size(); i-- > 0;) b.prepare_point(i, x[i], y[i]);
  b.finish_rebuild(x.data(), y.data(), x.size());
  for (std::size_t k = 0; k < x.size(); ++k) CHECK(a.order(k) == b.order(k));
}

}  // namespace test_neighbor_grid
