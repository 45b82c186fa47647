#include "framework/crowd/orca_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "framework/core/error.hpp"
#include "framework/crowd/orca_linear_program.hpp"
#include "framework/crowd/segment_distance.hpp"

namespace crowdlab {
namespace {

using orca::Line;

/// The k nearest neighbours seen so far, sorted by (distance^2, index): a bounded priority list.
struct NearestNeighbors {
  std::array<double, OrcaModel::kMaxNeighbors> d2;
  std::array<std::uint32_t, OrcaModel::kMaxNeighbors> index;
  int size = 0;
  int capacity = 0;

  /// Inserts (j, dist2); returns the squared radius still worth searching.
  double insert(std::uint32_t j, double dist2, double r2) {
    int pos = size;
    if (size == capacity) {
      if (dist2 > d2[size - 1] || (dist2 == d2[size - 1] && j > index[size - 1])) return r2;
      --pos;  // drop the current furthest
    } else {
      ++size;
    }
    while (pos > 0 && (d2[pos - 1] > dist2 || (d2[pos - 1] == dist2 && index[pos - 1] > j))) {
      d2[pos] = d2[pos - 1];
      index[pos] = index[pos - 1];
      --pos;
    }
    d2[pos] = dist2;
    index[pos] = j;
    return size == capacity ? d2[size - 1] : r2;
  }
};

/// ORCA half-plane induced on agent i by neighbour j (see the header for the geometry).
Line agent_line(const CrowdWorld& w, std::size_t i, std::uint32_t j, double inv_tau) {
  const double rel_px = w.px[j] - w.px[i], rel_py = w.py[j] - w.py[i];
  const double rel_vx = w.vx[i] - w.vx[j], rel_vy = w.vy[i] - w.vy[j];
  const double dist2 = rel_px * rel_px + rel_py * rel_py;
  const double r = w.radius[i] + w.radius[j];
  const double r2 = r * r;
  Line line;
  double ux, uy;
  if (dist2 > r2) {
    // w_vec: from the cut-off centre p / tau to the relative velocity.
    const double wx = rel_vx - inv_tau * rel_px, wy = rel_vy - inv_tau * rel_py;
    const double w2 = wx * wx + wy * wy;
    const double dot1 = wx * rel_px + wy * rel_py;
    if (dot1 < 0.0 && dot1 * dot1 > r2 * w2) {
      // Closest boundary point is on the cut-off circle.
      const double wl = std::sqrt(w2);
      const double inv_wl = 1.0 / wl;
      const double nx = wx * inv_wl, ny = wy * inv_wl;
      line.dx = ny, line.dy = -nx;
      ux = (r * inv_tau - wl) * nx, uy = (r * inv_tau - wl) * ny;
    } else {
      // Closest boundary point is on a leg (tangent from the origin to D(p, r)).
      const double leg = std::sqrt(dist2 - r2);
      const double inv_dist2 = 1.0 / dist2;
      if (orca::det(rel_px, rel_py, wx, wy) > 0.0) {  // left leg
        line.dx = (rel_px * leg - rel_py * r) * inv_dist2;
        line.dy = (rel_px * r + rel_py * leg) * inv_dist2;
      } else {  // right leg, reversed so that the permitted side stays on the left
        line.dx = -(rel_px * leg + rel_py * r) * inv_dist2;
        line.dy = -(-rel_px * r + rel_py * leg) * inv_dist2;
      }
      const double proj = rel_vx * line.dx + rel_vy * line.dy;
      ux = proj * line.dx - rel_vx, uy = proj * line.dy - rel_vy;
    }
  } else {
    // Already overlapping: leave the cut-off disc of horizon dt.
    const double inv_dt = 1.0 / w.dt;
    const double wx = rel_vx - inv_dt * rel_px, wy = rel_vy - inv_dt * rel_py;
    const double wl = std::sqrt(wx * wx + wy * wy);
    double nx = 1.0, ny = 0.0;
    if (wl > 1e-12) {
      const double inv_wl = 1.0 / wl;
      nx = wx * inv_wl, ny = wy * inv_wl;
    }
    line.dx = ny, line.dy = -nx;
    ux = (r * inv_dt - wl) * nx, uy = (r * inv_dt - wl) * ny;
  }
  line.px = w.vx[i] + 0.5 * ux;
  line.py = w.vy[i] + 0.5 * uy;
  return line;
}

}  // namespace

OrcaModel::OrcaModel(const OrcaParams& p) : params_(p) {
  auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!positive(p.neighbor_distance_m)) throw InputError("crowd.neighbor_distance_m: must be > 0");
  if (p.max_neighbors < 1 || p.max_neighbors > kMaxNeighbors)
    throw InputError("crowd.max_neighbors: must be in [1, " + std::to_string(kMaxNeighbors) + "], got " +
                     std::to_string(p.max_neighbors));
  if (!positive(p.time_horizon_s)) throw InputError("crowd.time_horizon_s: must be > 0");
  if (!positive(p.obstacle_time_horizon_s)) throw InputError("crowd.obstacle_time_horizon_s: must be > 0");
}

void OrcaModel::compute_velocities(const CrowdWorld& w, std::size_t begin, std::size_t end, double* new_vx,
                                   double* new_vy) const {
  std::array<Line, kMaxNeighbors + kMaxObstacleLines> lines;
  std::array<Line, kMaxNeighbors + kMaxObstacleLines> scratch;
  NearestNeighbors nn;
  nn.capacity = params_.max_neighbors;
  const double inv_tau = 1.0 / params_.time_horizon_s;
  const double tau_obst = params_.obstacle_time_horizon_s;
  const double range = params_.neighbor_distance_m;
  const std::vector<ObstacleSegment>& obstacles = *w.obstacles;

  for (std::size_t i = begin; i < end; ++i) {
    const double pix = w.px[i], piy = w.py[i];
    const double max_speed = w.max_speed[i];
    std::size_t n = 0;
    // Obstacle lines first: they stay hard constraints in lp3.
    const double obstacle_reach = tau_obst * max_speed + w.radius[i];
    for (const ObstacleSegment& s : obstacles) {
      if (n == static_cast<std::size_t>(kMaxObstacleLines)) break;
      const Vec2 c = closest_point_on_segment(s.a, s.b, Vec2(pix, piy));
      const double ox = pix - c.x(), oy = piy - c.y();
      const double d = std::sqrt(ox * ox + oy * oy);
      if (d > obstacle_reach || d <= 1e-12) continue;
      const double nx = ox / d, ny = oy / d;
      const double horizon = d > w.radius[i] ? tau_obst : w.dt;
      const double offset = (w.radius[i] - d) / horizon;  // v . n >= offset
      Line& L = lines[n++];
      L.px = nx * offset, L.py = ny * offset;
      L.dx = ny, L.dy = -nx;  // left normal of (dx, dy) is n: the permitted side
    }
    const std::size_t num_obstacle_lines = n;

    nn.size = 0;
    w.grid->for_each_within(pix, piy, range, [&](std::uint32_t j, double, double, double d2, double r2) {
      if (j == i) return r2;
      return nn.insert(j, d2, r2);
    });
    for (int k = 0; k < nn.size; ++k) lines[n++] = agent_line(w, i, nn.index[k], inv_tau);

    double rx = 0.0, ry = 0.0;
    const std::size_t failed =
        orca::lp2(lines.data(), n, max_speed, w.pref_vx[i], w.pref_vy[i], false, rx, ry);
    if (failed < n) orca::lp3(lines.data(), n, num_obstacle_lines, failed, max_speed, scratch.data(), rx, ry);
    new_vx[i] = rx;
    new_vy[i] = ry;
  }
}

}  // namespace crowdlab
