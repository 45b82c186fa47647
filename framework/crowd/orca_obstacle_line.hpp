#pragma once
// The ORCA half-plane that a static line segment induces on one agent (van den Berg, Guy, Lin,
// Manocha 2011, "Reciprocal n-Body Collision Avoidance", Sec. 5.1 "Static obstacles": the obstacle
// takes no responsibility, so the agent's velocity must leave the obstacle's truncated velocity
// obstacle entirely). Written from the paper and from the documented behaviour of RVO2 (the
// reference library by the same authors), not from its code.
//
// Geometry (velocity space, agent at p with radius r, horizon tau, segment [a, b]):
//   VO_tau = {v : exists t in [0, tau], dist(p + v t, [a, b]) < r}. Its boundary is made of
//   * two legs: the tangents from the origin to the discs D(a - p, r) / D(b - p, r) (or both to the
//     same end disc when the segment is seen end-on, "oblique" view);
//   * the cut-off: the segment [a, b] - p scaled by 1/tau and pushed out by r / tau, capped by the
//     end arcs of radius r / tau around (a - p)/tau and (b - p)/tau.
//   The current velocity v is projected onto the nearest of: the left/right cut-off arc, the
//   cut-off line, the left leg, the right leg; the half-plane is the tangent there (full
//   responsibility: the line passes through the projected point itself, not v + u/2).
// A segment blocks on both sides: it is treated as the two directed edges a->b and b->a, and the
// agent only sees the one it stands to the right of (RVO2's rule for a polygon's outside), whose
// end points are both convex. A leg that would point back along the segment itself ("foreign" leg,
// e.g. when the far end hides behind the near one) is replaced by the segment's direction and, if
// it is the nearest feature, contributes no half-plane (the other edge covers it).
// Already touching (dist < r): RVO2 asks only that the agent stop approaching (v . n >= 0); here
// the agent must leave the overlap within one step, v . n >= min(r - d, 0.5 v_max dt) / dt, the
// same 1/dt projection the paper uses for overlapping agents (Sec. 5.2), capped at half the speed
// limit so the program stays feasible.
// Redundancy: if the segment's whole cut-off lies beyond an earlier obstacle half-plane (both end
// discs), it adds nothing and is skipped; callers pass segments nearest first, as RVO2 does.
// Units: m, s, m/s. Header-only so it inlines into the per-agent loop.
#include <cmath>
#include <cstddef>
#include <limits>

#include "framework/crowd/orca_linear_program.hpp"

namespace crowdlab::orca {

/// Agent state for obstacle_line(): position (m), velocity (m/s), radius (m).
struct ObstacleAgent {
  double px = 0, py = 0, vx = 0, vy = 0, radius = 0.25, max_speed = 1.5;
};

/// Writes the half-plane of segment [(ax, ay), (bx, by)] for `agent` into `line` and returns true;
/// returns false when the segment imposes nothing (degenerate, covered by one of the `num_prev`
/// earlier obstacle lines, or only a foreign leg is near). inv_tau = 1 / obstacle horizon (1/s),
/// dt = the step (s), used when already touching.
inline bool obstacle_line(double ax, double ay, double bx, double by, const ObstacleAgent& agent,
                          double inv_tau, double dt, const Line* prev, std::size_t num_prev, Line& line) {
  const double px = agent.px, py = agent.py, r = agent.radius, r2 = r * r;
  // Orient so that the agent stands to the right of a -> b (or on its line).
  if (det(bx - ax, by - ay, px - ax, py - ay) > 0.0) {
    double t = ax;
    ax = bx, bx = t;
    t = ay;
    ay = by, by = t;
  }
  const double ex0 = bx - ax, ey0 = by - ay;
  const double len2 = ex0 * ex0 + ey0 * ey0;
  if (!(len2 > 1e-18)) return false;
  const double inv_len = 1.0 / std::sqrt(len2);
  const double ex = ex0 * inv_len, ey = ey0 * inv_len;  // unit direction a -> b
  const double r1x = ax - px, r1y = ay - py, r2x = bx - px, r2y = by - py;

  // Skip when an earlier obstacle line already excludes both end discs of the cut-off.
  for (std::size_t j = 0; j < num_prev; ++j) {
    const Line& L = prev[j];
    if (det(inv_tau * r1x - L.px, inv_tau * r1y - L.py, L.dx, L.dy) - inv_tau * r >= -kEpsilon &&
        det(inv_tau * r2x - L.px, inv_tau * r2y - L.py, L.dx, L.dy) - inv_tau * r >= -kEpsilon)
      return false;
  }

  const double d1sq = r1x * r1x + r1y * r1y, d2sq = r2x * r2x + r2y * r2y;
  const double s = (-r1x * ex0 - r1y * ey0) / len2;  // closest point a + s (b - a)
  const double cx = -r1x - s * ex0, cy = -r1y - s * ey0;
  const double dline_sq = cx * cx + cy * cy;  // squared distance to the supporting line

  // Already touching: leave within one step along the normal away from the closest point.
  auto push_out = [&](double nx_raw, double ny_raw, double dist) {
    const double inv = 1.0 / std::sqrt(nx_raw * nx_raw + ny_raw * ny_raw);
    const double nx = nx_raw * inv, ny = ny_raw * inv;
    const double speed = std::fmin(r - dist, 0.5 * agent.max_speed * dt) / dt;
    line.px = nx * speed, line.py = ny * speed;
    line.dx = ny, line.dy = -nx;  // permitted side (left) is +n
    return true;
  };
  if (s < 0.0 && d1sq <= r2) {
    if (d1sq <= 1e-24) return false;
    return push_out(-r1x, -r1y, std::sqrt(d1sq));
  }
  if (s > 1.0 && d2sq <= r2) {
    if (d2sq <= 1e-24) return false;
    return push_out(-r2x, -r2y, std::sqrt(d2sq));
  }
  if (s >= 0.0 && s <= 1.0 && dline_sq <= r2) return push_out(ey, -ex, std::sqrt(dline_sq));

  // Legs. o1/o2: the end points the left/right legs start from (0 = a, 1 = b).
  int o1 = 0, o2 = 1;
  double llx, lly, rlx, rly;  // left and right leg directions (unit)
  auto left_leg = [&](double qx, double qy, double dsq) {
    const double leg = std::sqrt(dsq - r2), inv = 1.0 / dsq;
    llx = (qx * leg - qy * r) * inv, lly = (qx * r + qy * leg) * inv;
  };
  auto right_leg = [&](double qx, double qy, double dsq) {
    const double leg = std::sqrt(dsq - r2), inv = 1.0 / dsq;
    rlx = (qx * leg + qy * r) * inv, rly = (-qx * r + qy * leg) * inv;
  };
  if (s < 0.0 && dline_sq <= r2) {  // seen end-on past a: both legs from a
    o2 = 0;
    left_leg(r1x, r1y, d1sq);
    right_leg(r1x, r1y, d1sq);
  } else if (s > 1.0 && dline_sq <= r2) {  // seen end-on past b: both legs from b
    o1 = 1;
    left_leg(r2x, r2y, d2sq);
    right_leg(r2x, r2y, d2sq);
  } else {
    left_leg(r1x, r1y, d1sq);
    right_leg(r2x, r2y, d2sq);
  }
  // Foreign legs: a leg may not point back into the segment (the edge's neighbour is the reverse
  // edge, so the neighbouring directions are +-e).
  const double lnx = o1 == 0 ? ex : -ex, lny = o1 == 0 ? ey : -ey;  // minus the left neighbour's direction
  const double rnx = o2 == 1 ? -ex : ex, rny = o2 == 1 ? -ey : ey;  // the right end's own direction
  bool left_foreign = false, right_foreign = false;
  if (det(llx, lly, lnx, lny) >= 0.0) llx = lnx, lly = lny, left_foreign = true;
  if (det(rlx, rly, rnx, rny) <= 0.0) rlx = rnx, rly = rny, right_foreign = true;

  const double lcx = inv_tau * (o1 == 0 ? r1x : r2x), lcy = inv_tau * (o1 == 0 ? r1y : r2y);
  const double rcx = inv_tau * (o2 == 0 ? r1x : r2x), rcy = inv_tau * (o2 == 0 ? r1y : r2y);
  const double cvx = rcx - lcx, cvy = rcy - lcy;
  const bool same = o1 == o2;
  const double vx = agent.vx, vy = agent.vy;
  const double t = same ? 0.5 : ((vx - lcx) * cvx + (vy - lcy) * cvy) / (cvx * cvx + cvy * cvy);
  const double t_left = (vx - lcx) * llx + (vy - lcy) * lly;
  const double t_right = (vx - rcx) * rlx + (vy - rcy) * rly;
  const double rt = r * inv_tau;

  auto arc = [&](double ccx, double ccy) {
    double wx = vx - ccx, wy = vy - ccy;
    const double wl = std::sqrt(wx * wx + wy * wy);
    if (wl > 1e-12) {
      wx /= wl, wy /= wl;
    } else {  // v at the arc's centre: push straight away from the obstacle
      wx = -ey, wy = ex;
    }
    line.dx = wy, line.dy = -wx;
    line.px = ccx + rt * wx, line.py = ccy + rt * wy;
    return true;
  };
  if ((t < 0.0 && t_left < 0.0) || (same && t_left < 0.0 && t_right < 0.0)) return arc(lcx, lcy);
  if (t > 1.0 && t_right < 0.0) return arc(rcx, rcy);

  constexpr double kInf = std::numeric_limits<double>::infinity();
  auto sq = [](double x, double y) { return x * x + y * y; };
  const double dist_cut =
      (t < 0.0 || t > 1.0 || same) ? kInf : sq(vx - (lcx + t * cvx), vy - (lcy + t * cvy));
  const double dist_left = t_left < 0.0 ? kInf : sq(vx - (lcx + t_left * llx), vy - (lcy + t_left * lly));
  const double dist_right = t_right < 0.0 ? kInf : sq(vx - (rcx + t_right * rlx), vy - (rcy + t_right * rly));
  if (dist_cut <= dist_left && dist_cut <= dist_right) {
    line.dx = -ex, line.dy = -ey;  // the cut-off line, pushed out by r / tau toward the agent
    line.px = lcx + rt * (-line.dy), line.py = lcy + rt * line.dx;
    return true;
  }
  if (dist_left <= dist_right) {
    if (left_foreign) return false;
    line.dx = llx, line.dy = lly;
    line.px = lcx + rt * (-line.dy), line.py = lcy + rt * line.dx;
    return true;
  }
  if (right_foreign) return false;
  line.dx = -rlx, line.dy = -rly;
  line.px = rcx + rt * (-line.dy), line.py = rcy + rt * line.dx;
  return true;
}

}  // namespace crowdlab::orca
