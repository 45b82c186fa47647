#pragma once
// The low-dimensional linear programs of ORCA (van den Berg, Guy, Lin, Manocha 2011, "Reciprocal
// n-Body Collision Avoidance", Section 5.2), written from the paper's description:
//   * each constraint is a half-plane {v : det(d, v - p) >= 0}, i.e. the LEFT side of the directed
//     line through p with unit direction d;
//   * lp2 finds the velocity closest to v_opt (or furthest along a direction) inside the disc
//     |v| <= R and all half-planes, by the randomised-incremental method of de Berg et al.
//     (Computational Geometry, 3rd ed., Section 4.4): when constraint i is violated, the optimum lies
//     on its line, which is a 1D program (lp1) over the earlier constraints;
//   * lp3 handles infeasibility (dense crowds): it minimises the largest violation of the agent
//     constraints while keeping the obstacle constraints hard, as a 2D program over the bisectors
//     between the most violated constraint and the earlier ones (the paper's 3D fallback).
// Header-only so the per-agent solve inlines into the model loop. Units: m/s.
#include <cmath>
#include <cstddef>

namespace crowdlab::orca {

struct Line {
  double px = 0, py = 0;  ///< a point on the line (velocity space)
  double dx = 1, dy = 0;  ///< unit direction; the permitted side is on the left
};

inline double det(double ax, double ay, double bx, double by) {
  return ax * by - ay * bx;
}

/// Numerical tolerance for parallel lines (m/s)^2.
constexpr double kEpsilon = 1e-9;

/// Optimum on line `i` subject to lines[0..i) and |v| <= radius. Returns false when infeasible.
inline bool lp1(const Line* lines, std::size_t i, double radius, double opt_x, double opt_y,
                bool direction_opt, double& rx, double& ry) {
  const Line& L = lines[i];
  const double dot = L.px * L.dx + L.py * L.dy;
  const double disc = dot * dot + radius * radius - (L.px * L.px + L.py * L.py);
  if (disc < 0.0) return false;  // the line misses the speed disc
  const double s = std::sqrt(disc);
  double t_left = -dot - s, t_right = -dot + s;
  for (std::size_t j = 0; j < i; ++j) {
    const Line& M = lines[j];
    const double denom = det(L.dx, L.dy, M.dx, M.dy);
    const double numer = det(M.dx, M.dy, L.px - M.px, L.py - M.py);
    if (std::fabs(denom) <= kEpsilon) {
      if (numer < 0.0) return false;  // parallel and on the forbidden side
      continue;
    }
    const double t = numer / denom;
    if (denom >= 0.0)
      t_right = std::fmin(t_right, t);
    else
      t_left = std::fmax(t_left, t);
    if (t_left > t_right) return false;
  }
  double t;
  if (direction_opt) {
    t = (opt_x * L.dx + opt_y * L.dy) > 0.0 ? t_right : t_left;
  } else {
    t = L.dx * (opt_x - L.px) + L.dy * (opt_y - L.py);
    t = t < t_left ? t_left : (t > t_right ? t_right : t);
  }
  rx = L.px + t * L.dx;
  ry = L.py + t * L.dy;
  return true;
}

/// 2D program over lines[0..n). direction_opt: (opt_x, opt_y) is a unit direction to go furthest
/// along. Returns n on success, else the index of the first line that could not be satisfied
/// (rx, ry then hold the best point found before it).
inline std::size_t lp2(const Line* lines, std::size_t n, double radius, double opt_x, double opt_y,
                       bool direction_opt, double& rx, double& ry) {
  if (direction_opt) {
    rx = opt_x * radius, ry = opt_y * radius;
  } else if (opt_x * opt_x + opt_y * opt_y > radius * radius) {
    const double s = radius / std::sqrt(opt_x * opt_x + opt_y * opt_y);
    rx = opt_x * s, ry = opt_y * s;
  } else {
    rx = opt_x, ry = opt_y;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (det(lines[i].dx, lines[i].dy, lines[i].px - rx, lines[i].py - ry) > 0.0) {
      const double keep_x = rx, keep_y = ry;
      if (!lp1(lines, i, radius, opt_x, opt_y, direction_opt, rx, ry)) {
        rx = keep_x, ry = keep_y;
        return i;
      }
    }
  }
  return n;
}

/// Infeasible case: lines[0..num_hard) are hard (obstacles), lines[num_hard..n) soft. Starting at
/// `begin` (the line lp2 failed on), minimises the maximum violation of the soft lines.
/// `scratch` must hold n lines.
inline void lp3(const Line* lines, std::size_t n, std::size_t num_hard, std::size_t begin, double radius,
                Line* scratch, double& rx, double& ry) {
  double distance = 0.0;
  for (std::size_t i = begin; i < n; ++i) {
    const Line& L = lines[i];
    if (det(L.dx, L.dy, L.px - rx, L.py - ry) <= distance) continue;  // not worse than the current worst
    std::size_t m = 0;
    for (std::size_t j = 0; j < num_hard; ++j) scratch[m++] = lines[j];
    for (std::size_t j = num_hard; j < i; ++j) {
      const Line& M = lines[j];
      Line b;
      const double d = det(L.dx, L.dy, M.dx, M.dy);
      if (std::fabs(d) <= kEpsilon) {
        if (L.dx * M.dx + L.dy * M.dy > 0.0) continue;  // same direction: j is implied by i
        b.px = 0.5 * (L.px + M.px);                     // opposite: the midline
        b.py = 0.5 * (L.py + M.py);
      } else {
        const double t = det(M.dx, M.dy, L.px - M.px, L.py - M.py) / d;
        b.px = L.px + t * L.dx;
        b.py = L.py + t * L.dy;
      }
      double bx = M.dx - L.dx, by = M.dy - L.dy;  // bisector direction
      const double len = std::sqrt(bx * bx + by * by);
      if (len <= kEpsilon) continue;
      b.dx = bx / len, b.dy = by / len;
      scratch[m++] = b;
    }
    const double keep_x = rx, keep_y = ry;
    // Go as far as possible into line i's permitted side (its left normal).
    if (lp2(scratch, m, radius, -L.dy, L.dx, true, rx, ry) < m) {
      rx = keep_x, ry = keep_y;  // numerical failure only: keep the previous best
    }
    distance = det(L.dx, L.dy, L.px - rx, L.py - ry);
  }
}

}  // namespace crowdlab::orca
