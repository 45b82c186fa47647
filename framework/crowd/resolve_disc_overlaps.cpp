#include "framework/crowd/resolve_disc_overlaps.hpp"

#include <algorithm>
#include <cmath>

#include "framework/crowd/segment_distance.hpp"

namespace crowdlab {
namespace {

/// Collects the overlapping pairs and walls of the candidate agents (see the header).
void collect_contacts(const double* px, const double* py, const double* radius, std::size_t n,
                      const unsigned char* cand, const NeighborGrid& grid, double r_max, double stale,
                      const std::vector<ObstacleSegment>& walls, double margin,
                      std::vector<OverlapContact>& contacts) {
  contacts.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (!cand[i]) continue;
    const auto ii = static_cast<std::uint32_t>(i);
    auto consider = [&](std::uint32_t j) {
      if (j == ii || (cand[j] && j < ii)) return;  // a candidate pair is found once, from its lower index
      const double dx = px[j] - px[i], dy = py[j] - py[i];
      const double rr = radius[i] + radius[j] + margin;
      if (dx * dx + dy * dy < rr * rr) contacts.push_back({ii, j, 0});
    };
    const double reach = radius[i] + r_max + stale + margin;
    if (reach <= grid.cell_size() && grid.size() == n) {
      grid.for_each_within(px[i], py[i], reach, [&](std::uint32_t j, double, double, double, double r2) {
        consider(j);
        return r2;
      });
    } else {
      for (std::size_t j = 0; j < n; ++j) consider(static_cast<std::uint32_t>(j));
    }
    for (std::size_t k = 0; k < walls.size(); ++k) {
      const Vec2 c = closest_point_on_segment(walls[k].a, walls[k].b, Vec2(px[i], py[i]));
      const double dx = px[i] - c.x(), dy = py[i] - c.y();
      const double rr = radius[i] + margin;
      if (dx * dx + dy * dy < rr * rr)
        contacts.push_back({ii, OverlapContact::kWall, static_cast<std::uint32_t>(k)});
    }
  }
}

void push(double* px, double* py, std::vector<double>& shift, std::vector<unsigned char>& moved,
          std::uint32_t i, double nx, double ny, double amount) {
  px[i] += nx * amount;
  py[i] += ny * amount;
  shift[i] += std::fabs(amount);
  moved[i] = 1;
}

/// One Gauss-Seidel sweep over the contacts; returns the deepest overlap met before projecting.
double sweep(double* px, double* py, const double* radius, const std::vector<ObstacleSegment>& walls,
             const std::vector<OverlapContact>& contacts, double slack, OverlapResolutionScratch& s) {
  double worst = -std::numeric_limits<double>::infinity();
  for (const OverlapContact& c : contacts) {
    if (c.j == OverlapContact::kWall) {
      const ObstacleSegment& w = walls[c.wall];
      const Vec2 q = closest_point_on_segment(w.a, w.b, Vec2(px[c.i], py[c.i]));
      double nx = px[c.i] - q.x(), ny = py[c.i] - q.y();
      const double d = std::sqrt(nx * nx + ny * ny);
      const double overlap = radius[c.i] - d;
      worst = std::max(worst, overlap);
      if (overlap <= 0.0) continue;
      if (d > 1e-12) {
        nx /= d, ny /= d;
      } else {  // on the wall's line: leave along its left normal (deterministic)
        const Vec2 e = (w.b - w.a).normalized();
        nx = -e.y(), ny = e.x();
      }
      push(px, py, s.shift, s.moved, c.i, nx, ny, overlap + slack);
      continue;
    }
    double nx = px[c.j] - px[c.i], ny = py[c.j] - py[c.i];
    const double d = std::sqrt(nx * nx + ny * ny);
    const double overlap = radius[c.i] + radius[c.j] - d;
    worst = std::max(worst, overlap);
    if (overlap <= 0.0) continue;
    if (d > 1e-12) {
      nx /= d, ny /= d;
    } else {  // coincident centres: separate along +x (lower index to -x), deterministic
      nx = 1.0, ny = 0.0;
    }
    const double half = 0.5 * (overlap + slack);
    push(px, py, s.shift, s.moved, c.i, -nx, -ny, half);
    push(px, py, s.shift, s.moved, c.j, nx, ny, half);
  }
  return worst;
}

}  // namespace

OverlapResolutionResult resolve_disc_overlaps(double* px, double* py, const double* radius, std::size_t n,
                                              const unsigned char* check, const NeighborGrid& grid,
                                              double max_stale_m, const std::vector<ObstacleSegment>& walls,
                                              const OverlapResolutionOptions& options,
                                              OverlapResolutionScratch& scratch) {
  OverlapResolutionResult result;
  result.deepest_overlap_m = -std::numeric_limits<double>::infinity();
  if (n == 0) return result;
  if (scratch.candidate.size() < n) {
    scratch.candidate.resize(n);
    scratch.moved.resize(n);
    scratch.shift.resize(n);
  }
  double r_max = 0.0;
  for (std::size_t i = 0; i < n; ++i) r_max = std::max(r_max, radius[i]);
  bool any = false;
  for (std::size_t i = 0; i < n; ++i) {
    scratch.candidate[i] = check ? check[i] : 1;
    any = any || scratch.candidate[i];
    scratch.shift[i] = 0.0;
  }
  double stale = max_stale_m;
  for (int round = 0; round < options.max_rounds && any; ++round) {
    collect_contacts(px, py, radius, n, scratch.candidate.data(), grid, r_max, stale, walls,
                     options.contact_margin_m, scratch.contacts);
    if (scratch.contacts.empty()) break;
    ++result.rounds;
    result.contacts += scratch.contacts.size();
    std::fill(scratch.moved.begin(), scratch.moved.begin() + static_cast<std::ptrdiff_t>(n), 0);
    for (int k = 0; k < options.sweeps_per_round; ++k) {
      const double worst =
          sweep(px, py, radius, walls, scratch.contacts, options.separation_slack_m, scratch);
      if (worst <= options.tolerance_m) break;
    }
    // The pushed agents may now touch others: they are the next round's candidates.
    any = false;
    double max_shift = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      scratch.candidate[i] = scratch.moved[i];
      any = any || scratch.moved[i];
      max_shift = std::max(max_shift, scratch.shift[i]);
    }
    stale = max_stale_m + max_shift;
  }
  // Deepest overlap left among the last contacts (the tests measure all pairs by brute force).
  for (const OverlapContact& c : scratch.contacts) {
    double overlap;
    if (c.j == OverlapContact::kWall) {
      const ObstacleSegment& w = walls[c.wall];
      overlap = radius[c.i] -
                (Vec2(px[c.i], py[c.i]) - closest_point_on_segment(w.a, w.b, Vec2(px[c.i], py[c.i]))).norm();
    } else {
      overlap = radius[c.i] + radius[c.j] - std::hypot(px[c.j] - px[c.i], py[c.j] - py[c.i]);
    }
    result.deepest_overlap_m = std::max(result.deepest_overlap_m, overlap);
  }
  return result;
}

}  // namespace crowdlab
