#include "framework/crowd/orca_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "framework/core/error.hpp"
#include "framework/crowd/orca_linear_program.hpp"
#include "framework/crowd/orca_obstacle_line.hpp"
#include "framework/crowd/segment_distance.hpp"

namespace crowdlab {
namespace {

using orca::Line;

/// The k nearest neighbours seen so far, sorted by (distance^2, index): a bounded priority list.
struct NearestNeighbors {
  std::array<double, OrcaModel::kMaxNeighbors> d2;
  std::array<std::uint32_t, OrcaModel::kMaxNeighbors> index;
  std::array<std::uint32_t, OrcaModel::kMaxNeighbors> slot;  ///< where the caller keeps j's data
  int size = 0;
  int capacity = 0;

  /// Inserts (j, dist2); returns the squared radius still worth searching.
  double insert(std::uint32_t j, std::uint32_t j_slot, double dist2, double r2) {
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
      slot[pos] = slot[pos - 1];
      --pos;
    }
    d2[pos] = dist2;
    index[pos] = j;
    slot[pos] = j_slot;
    return size == capacity ? d2[size - 1] : r2;
  }
};

/// ORCA half-plane induced on an agent with velocity (vix, viy) by a neighbour at relative position
/// rel_p = p_j - p_i, relative velocity rel_v = v_i - v_j, combined radius r (header: geometry).
Line agent_line(double rel_px, double rel_py, double rel_vx, double rel_vy, double r, double vix, double viy,
                double inv_tau, double dt) {
  const double dist2 = rel_px * rel_px + rel_py * rel_py;
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
    const double inv_dt = 1.0 / dt;
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
  line.px = vix + 0.5 * ux;
  line.py = viy + 0.5 * uy;
  return line;
}

/// Step guard of agent i against neighbour j: v_i . n_ij <= b_ij, with n_ij the unit vector toward j,
/// gap = |p_j - p_i| - (r_i + r_j) and the pair's allowance gap / dt shared as
///   b_ij = gap / (2 dt) + s_ij,   s_ij = clamp((v_i + v_j) . n_ij / 2, -gap / (2 dt), gap / (2 dt))
/// from the current velocities. s_ji = -s_ij (n_ji = -n_ij), so b_ij + b_ji = gap / dt: if both agents
/// keep their guards, (v_i - v_j) . n_ij <= gap / dt and the distance along n_ij shrinks by at most the
/// gap during the step, so the discs cannot overlap by its end (nor in between: motion is linear).
/// Both shares lie in [0, gap / dt], so v = 0 satisfies every guard: a set of guards is feasible.
/// Sharing by the common motion (ORCA's reciprocity applied to the one-step constraint) lets a
/// follower keep pace with the neighbour it follows, which equal halves (s = 0) do not: measured in
/// orca_model.hpp.
Line step_guard(const CrowdWorld& w, std::size_t i, std::uint32_t j, double dist2, double rr) {
  const double d = std::sqrt(dist2);
  double nx = 1.0, ny = 0.0;
  if (d > 1e-12) nx = (w.px[j] - w.px[i]) / d, ny = (w.py[j] - w.py[i]) / d;
  const double half = std::fmax(d - rr, 0.0) / (2.0 * w.dt);
  const double common = 0.5 * ((w.vx[i] + w.vx[j]) * nx + (w.vy[i] + w.vy[j]) * ny);
  const double limit = half + std::clamp(common, -half, half);
  Line g;
  g.px = nx * limit, g.py = ny * limit;
  g.dx = -ny, g.dy = nx;  // left normal (-dy, dx) = -n: the permitted side is "not toward j"
  return g;
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
  constexpr std::size_t kMaxLines = 2 * kMaxNeighbors + kMaxObstacleLines;
  std::array<Line, kMaxLines> lines;      // [obstacles][agents]: the ORCA program
  std::array<Line, kMaxLines> hard_soft;  // [obstacles][step guards][agents]: the infeasible case
  std::array<Line, kMaxLines> scratch;
  std::array<Line, kMaxNeighbors> guards;
  NearestNeighbors nn;
  nn.capacity = params_.max_neighbors;
  const double inv_tau = 1.0 / params_.time_horizon_s;
  const double inv_tau_obst = 1.0 / params_.obstacle_time_horizon_s;
  const double tau_obst = params_.obstacle_time_horizon_s;
  std::array<double, kMaxObstacleLines> near_d2;
  std::array<std::uint32_t, kMaxObstacleLines> near_index;
  const double range = params_.neighbor_distance_m;
  const std::vector<ObstacleSegment>& obstacles = *w.obstacles;

  // Agents are visited in grid order (the range [begin, end) indexes NeighborGrid::order()), and
  // the candidates of the 3x3 cell block are gathered once per cell and shared by its agents.
  const NeighborGrid& grid = *w.grid;
  const bool grid_order = grid.size() == w.count;
  constexpr int kBlockCapacity = 256;
  constexpr std::uint32_t kNoSlot = 0xffffffffu;
  std::array<double, kBlockCapacity> block_x, block_y, block_vx, block_vy, block_r;
  std::array<std::uint32_t, kBlockCapacity> block_j;
  int block_size = -1;  // -1: overflowed, use per-agent queries
  const double range2 = range * range;
  // Overlap-free mode (see the header): step guards in the infeasible case and flags for the
  // simulation's projection. Off: the plain ORCA of the paper / RVO2.
  const bool guarded = params_.resolve_overlaps && w.needs_contact_check != nullptr;

  for (std::size_t k_order = begin; k_order < end; ++k_order) {
    const std::size_t i = grid_order ? grid.order(k_order) : k_order;
    if (grid_order && (k_order == begin || !grid.same_cell(k_order, k_order - 1))) {
      block_size = 0;
      grid.for_each_in_block(k_order, [&](std::uint32_t j, double x, double y) {
        if (block_size < 0) return;
        if (block_size == kBlockCapacity) {
          block_size = -1;
          return;
        }
        block_x[block_size] = x, block_y[block_size] = y, block_j[block_size] = j;
        block_vx[block_size] = w.vx[j], block_vy[block_size] = w.vy[j], block_r[block_size] = w.radius[j];
        ++block_size;
      });
    }
    const double pix = grid_order ? grid.x_at(k_order) : w.px[i],
                 piy = grid_order ? grid.y_at(k_order) : w.py[i];
    const double max_speed = w.max_speed[i];
    std::size_t n = 0;
    // Obstacle lines first, nearest segment first (Sec. 5.1): they stay hard constraints in lp3.
    const double obstacle_reach = tau_obst * max_speed + w.radius[i];
    const double reach2 = obstacle_reach * obstacle_reach;
    int num_near = 0;
    for (std::size_t k = 0; k < obstacles.size(); ++k) {
      const ObstacleSegment& s = obstacles[k];
      const Vec2 c = closest_point_on_segment(s.a, s.b, Vec2(pix, piy));
      const double d2 = (c.x() - pix) * (c.x() - pix) + (c.y() - piy) * (c.y() - piy);
      if (!(d2 < reach2)) continue;
      // Insertion into the nearest-first list (ties keep segment order).
      int pos = num_near;
      if (num_near < kMaxObstacleLines) {
        ++num_near;
      } else {
        if (near_d2[kMaxObstacleLines - 1] <= d2) continue;  // farther than all kept
        pos = kMaxObstacleLines - 1;
      }
      while (pos > 0 && near_d2[pos - 1] > d2) {
        near_d2[pos] = near_d2[pos - 1];
        near_index[pos] = near_index[pos - 1];
        --pos;
      }
      near_d2[pos] = d2;
      near_index[pos] = static_cast<std::uint32_t>(k);
    }
    const orca::ObstacleAgent self{pix, piy, w.vx[i], w.vy[i], w.radius[i], max_speed};
    for (int k = 0; k < num_near; ++k) {
      const ObstacleSegment& s = obstacles[near_index[k]];
      if (orca::obstacle_line(s.a.x(), s.a.y(), s.b.x(), s.b.y(), self, inv_tau_obst, w.dt, lines.data(), n,
                              lines[n]))
        ++n;
    }
    const std::size_t num_obstacle_lines = n;

    nn.size = 0;
    if (grid_order && block_size >= 0) {
      double r2 = range2;
      for (int c = 0; c < block_size; ++c) {
        const double dx = block_x[c] - pix, dy = block_y[c] - piy;
        const double d2 = dx * dx + dy * dy;
        if (d2 <= r2 && block_j[c] != i) r2 = nn.insert(block_j[c], static_cast<std::uint32_t>(c), d2, r2);
      }
    } else {
      grid.for_each_within(pix, piy, range, [&](std::uint32_t j, double, double, double d2, double r2) {
        if (j == i) return r2;
        return nn.insert(j, kNoSlot, d2, r2);
      });
    }
    bool touching = num_near > 0 && near_d2[0] < w.radius[i] * w.radius[i];
    std::size_t num_guards = 0;
    const double vix = w.vx[i], viy = w.vy[i], ri = w.radius[i];
    for (int k = 0; k < nn.size; ++k) {
      const std::uint32_t j = nn.index[k], c = nn.slot[k];
      const bool in_block = c != kNoSlot;
      const double rel_px = in_block ? block_x[c] - pix : w.px[j] - pix;
      const double rel_py = in_block ? block_y[c] - piy : w.py[j] - piy;
      const double vjx = in_block ? block_vx[c] : w.vx[j], vjy = in_block ? block_vy[c] : w.vy[j];
      const double rr = ri + (in_block ? block_r[c] : w.radius[j]);
      if (guarded) {
        const double guard_reach = rr + (max_speed + w.max_speed[j]) * w.dt;
        if (nn.d2[k] < guard_reach * guard_reach) {
          touching = touching || nn.d2[k] <= rr * rr;
          guards[num_guards++] = step_guard(w, i, j, nn.d2[k], rr);
        }
      }
      lines[n++] = agent_line(rel_px, rel_py, vix - vjx, viy - vjy, rr, vix, viy, inv_tau, w.dt);
    }

    double rx = 0.0, ry = 0.0;
    const std::size_t failed =
        orca::lp2(lines.data(), n, max_speed, w.pref_vx[i], w.pref_vy[i], false, rx, ry);
    if (failed < n && !guarded) {
      orca::lp3(lines.data(), n, num_obstacle_lines, failed, max_speed, scratch.data(), rx, ry);
    } else if (failed < n) {
      // Infeasible: the step guards join the obstacles as hard constraints of the 3D program.
      std::size_t m = 0;
      for (std::size_t k = 0; k < num_obstacle_lines; ++k) hard_soft[m++] = lines[k];
      for (std::size_t k = 0; k < num_guards; ++k) hard_soft[m++] = guards[k];
      const std::size_t num_hard = m;
      for (std::size_t k = num_obstacle_lines; k < n; ++k) hard_soft[m++] = lines[k];
      orca::lp3(hard_soft.data(), m, num_hard, num_hard, max_speed, scratch.data(), rx, ry);
    }
    if (guarded) {
      // Flag the agent for the overlap projection when it may end the step overlapping: it already
      // does, it breaks a step guard (allowed to ORCA agents whose neighbours keep their half), or
      // its neighbour list is full inside the guard reach (an agent within reach may be unseen).
      bool flag = touching;
      for (std::size_t k = 0; k < num_guards && !flag; ++k)
        flag = orca::det(guards[k].dx, guards[k].dy, guards[k].px - rx, guards[k].py - ry) > 1e-9;
      if (!flag && nn.size == nn.capacity) {
        const double reach = 2.0 * (w.radius[i] + max_speed * w.dt);
        flag = nn.d2[nn.size - 1] < reach * reach;
      }
      if (flag) w.needs_contact_check[i] = 1;
    }
    new_vx[k_order] = rx;
    new_vy[k_order] = ry;
  }
}

}  // namespace crowdlab
