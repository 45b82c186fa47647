#include "framework/crowd/place_poisson_disk.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"
#include "framework/crowd/neighbor_grid.hpp"

namespace crowdlab {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

bool is_convex(const Polygon2& p) {
  int sign = 0;
  for (std::size_t i = 0, n = p.size(); i < n; ++i) {
    const Vec2 e1 = p[(i + 1) % n] - p[i], e2 = p[(i + 2) % n] - p[(i + 1) % n];
    const double c = e1.x() * e2.y() - e1.y() * e2.x();
    if (std::fabs(c) < 1e-15) continue;
    const int s = c > 0 ? 1 : -1;
    if (sign != 0 && s != sign) return false;
    sign = s;
  }
  return true;
}

/// True when q is inside the area and at least `margin` from its boundary.
bool admissible(const Polygon2& area, const Vec2& q, double margin) {
  if (!polygon_contains(area, q)) return false;
  return margin <= 0.0 || (polygon_closest_boundary_point(area, q) - q).norm() >= margin;
}

/// Moves q to the closest admissible point when it is not admissible.
Vec2 project_inside(const Polygon2& area, const Vec2& q, double margin) {
  const bool inside = polygon_contains(area, q);
  const Vec2 c = polygon_closest_boundary_point(area, q);
  const Vec2 off = q - c;
  const double d = off.norm();
  if (inside && d >= margin) return q;
  if (d < 1e-12) return q;  // on the boundary with no margin wanted
  const Vec2 inward = inside ? Vec2(off / d) : Vec2(-off / d);
  return c + inward * std::max(margin, 1e-9);
}

}  // namespace

double oler_bound(double area_m2, double perimeter_m, double s) {
  return 2.0 * area_m2 / (std::sqrt(3.0) * s * s) + perimeter_m / (2.0 * s) + 1.0;
}

double min_pairwise_distance(const std::vector<Vec2>& pts) {
  const std::size_t n = pts.size();
  if (n < 2) return kInf;
  double best2 = kInf;
  if (n <= 256) {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) best2 = std::min(best2, (pts[i] - pts[j]).squaredNorm());
    return std::sqrt(best2);
  }
  Vec2 lo = pts[0], hi = pts[0];
  for (const Vec2& p : pts) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double area = std::max((hi - lo).prod(), 1e-12);
  const double cell = 2.0 * std::sqrt(area / static_cast<double>(n));
  std::vector<double> x(n), y(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = pts[i].x(), y[i] = pts[i].y();
  NeighborGrid grid(cell);
  grid.rebuild(x.data(), y.data(), n);
  for (std::size_t i = 0; i < n; ++i)
    grid.for_each_within(x[i], y[i], cell, [&](std::uint32_t j, double, double, double d2, double r2) {
      if (j != i) best2 = std::min(best2, d2);
      return r2;
    });
  if (best2 == kInf) {  // every point isolated beyond `cell`: fall back to all pairs
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) best2 = std::min(best2, (pts[i] - pts[j]).squaredNorm());
  }
  return std::sqrt(best2);
}

Placement place_poisson_disk(const Polygon2& area, int count, std::uint64_t seed,
                             const PlacementOptions& opt) {
  validate_polygon(area, "placement area");
  if (count < 1)
    throw InputError("placement: the number of characters must be >= 1, got " + std::to_string(count));
  if (!(opt.min_spacing_m >= 0.0) || !std::isfinite(opt.min_spacing_m))
    throw InputError("placement: minimum spacing must be >= 0 m, got " + fmt(opt.min_spacing_m));
  if (!(opt.boundary_margin_m >= 0.0) || !std::isfinite(opt.boundary_margin_m))
    throw InputError("placement: boundary margin must be >= 0 m, got " + fmt(opt.boundary_margin_m));
  if (opt.relaxation_iterations < 0) throw InputError("placement: relaxation iterations must be >= 0");
  const double A = polygon_area(area), P = polygon_perimeter(area);
  const double s_req = opt.min_spacing_m;
  if (s_req > 0.0 && is_convex(area) && count > oler_bound(A, P, s_req))
    throw InputError("placement: " + std::to_string(count) + " characters cannot fit in " + fmt(A) +
                     " m^2 with a minimum spacing of " + fmt(s_req) + " m (at most " +
                     std::to_string(static_cast<int>(oler_bound(A, P, s_req))) + " fit, Oler 1961)");

  const std::size_t n = static_cast<std::size_t>(count);
  const double d_hex = std::sqrt(2.0 * A / (std::sqrt(3.0) * count));
  Vec2 lo = area[0], hi = area[0];
  for (const Vec2& v : area) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  Rng rng(seed);
  auto sample = [&]() -> Vec2 {
    for (int tries = 0; tries < 1000000; ++tries) {
      const Vec2 q(lo.x() + uniform01(rng) * (hi.x() - lo.x()), lo.y() + uniform01(rng) * (hi.y() - lo.y()));
      if (admissible(area, q, opt.boundary_margin_m)) return q;
    }
    throw InputError("placement: no admissible point found in the area (boundary margin " +
                     fmt(opt.boundary_margin_m) + " m too large?)");
  };

  // 1. Dart throwing with a shrinking radius.
  std::vector<Vec2> pts;
  pts.reserve(n);
  std::vector<double> xs, ys;
  xs.reserve(n), ys.reserve(n);
  NeighborGrid grid(d_hex);
  const bool plain_poisson = opt.personal_space_m > 0.0 && opt.personal_space_m < d_hex;
  double r = plain_poisson ? opt.personal_space_m : d_hex;
  int failures = 0;
  grid.rebuild(xs.data(), ys.data(), 0);
  while (pts.size() < n) {
    const Vec2 q = sample();
    bool ok = true;
    grid.for_each_within(q.x(), q.y(), r, [&](std::uint32_t, double, double, double, double r2) {
      ok = false;
      return r2;
    });
    if (ok) {
      pts.push_back(q);
      xs.push_back(q.x()), ys.push_back(q.y());
      grid.rebuild(xs.data(), ys.data(), pts.size());
      failures = 0;
    } else if (++failures >= 100) {
      r *= 0.97;
      failures = 0;
    }
  }

  // 2. Relaxation by soft-disc repulsion; keep the best configuration. With a personal space only where
  // the dart throwing had to shrink below it (it jams near r ~ 0.78 d_hex), and then only pairs closer
  // than the personal space push apart: the closest pairs reach it as far as the density allows, and
  // the others keep their irregular spacing.
  std::vector<Vec2> best = pts, next(n);
  double best_spacing = min_pairwise_distance(pts);
  const bool relax = !plain_poisson || r < opt.personal_space_m;
  const double target = plain_poisson ? opt.personal_space_m : 1.1 * d_hex;
  for (int it = 0; it < (relax ? opt.relaxation_iterations : 0) && n > 1; ++it) {
    for (std::size_t i = 0; i < n; ++i) xs[i] = pts[i].x(), ys[i] = pts[i].y();
    NeighborGrid g(target);
    g.rebuild(xs.data(), ys.data(), n);
    for (std::size_t i = 0; i < n; ++i) {
      Vec2 push = Vec2::Zero();
      g.for_each_within(xs[i], ys[i], target,
                        [&](std::uint32_t j, double dx, double dy, double d2, double r2) {
                          if (j == i || d2 <= 1e-24) return r2;
                          const double d = std::sqrt(d2);
                          push -= Vec2(dx, dy) / d * (0.5 * (target - d));
                          return r2;
                        });
      // Project back; near reflex corners one projection can land within the margin of another
      // edge, so repeat, and keep the old (admissible) point if that does not settle.
      Vec2 q = pts[i] + 0.5 * push;
      bool ok = false;
      for (int k = 0; k < 8 && !ok; ++k) {
        q = project_inside(area, q, opt.boundary_margin_m);
        ok = opt.boundary_margin_m <= 0.0 || admissible(area, q, opt.boundary_margin_m * (1.0 - 1e-9));
      }
      next[i] = ok ? q : pts[i];
    }
    pts.swap(next);
    const double s = min_pairwise_distance(pts);
    if (s > best_spacing) best_spacing = s, best = pts;
  }

  if (s_req > 0.0 && best_spacing < s_req)
    throw InputError("placement: " + std::to_string(count) + " characters cannot be placed in " + fmt(A) +
                     " m^2 with a minimum spacing of " + fmt(s_req) + " m (best found " + fmt(best_spacing) +
                     " m)");
  Placement out;
  out.positions = std::move(best);
  out.min_spacing_m = best_spacing;
  out.area_m2 = A;
  out.density_per_m2 = count / A;
  return out;
}

}  // namespace crowdlab
