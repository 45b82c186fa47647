#include "framework/crowd/cost_gradient_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "framework/core/error.hpp"
#include "framework/crowd/segment_distance.hpp"

namespace crowdlab {

CostGradientParams cost_gradient_params_from_weights(const std::map<std::string, double>& weights,
                                                     CostGradientParams p) {
  for (const auto& [key, value] : weights) {
    const std::string where = "crowd.cost_weights." + key;
    if (!std::isfinite(value)) throw InputError(where + ": must be a finite number");
    if (key == "goal")
      p.goal = value;
    else if (key == "smoothness")
      p.smoothness = value;
    else if (key == "separation")
      p.separation = value;
    else if (key == "walls")
      p.walls = value;
    else if (key == "sigma_m")
      p.sigma_m = value;
    else if (key == "lookahead_s")
      p.lookahead_s = value;
    else if (key == "iterations")
      p.iterations = static_cast<int>(std::lround(value));
    else
      throw InputError(where +
                       ": unknown weight (known: goal, smoothness, separation, walls, sigma_m, lookahead_s, "
                       "iterations)");
  }
  return p;
}

CostGradientModel::CostGradientModel(const CostGradientParams& p) : params_(p) {
  auto non_negative = [](double v) { return v >= 0.0 && std::isfinite(v); };
  auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!non_negative(p.goal) || !non_negative(p.smoothness) || !non_negative(p.separation) ||
      !non_negative(p.walls))
    throw InputError("crowd.cost_weights: goal, smoothness, separation and walls must be >= 0");
  if (!(p.goal + p.smoothness > 0.0)) throw InputError("crowd.cost_weights: goal + smoothness must be > 0");
  if (!positive(p.sigma_m)) throw InputError("crowd.cost_weights.sigma_m: must be > 0");
  if (!positive(p.lookahead_s)) throw InputError("crowd.cost_weights.lookahead_s: must be > 0");
  if (p.iterations < 1 || p.iterations > 100)
    throw InputError("crowd.cost_weights.iterations: must be in [1, 100]");
  if (!positive(p.neighbor_distance_m)) throw InputError("crowd.neighbor_distance_m: must be > 0");
  if (p.max_neighbors < 1 || p.max_neighbors > kMaxNeighbors)
    throw InputError("crowd.max_neighbors: must be in [1, 64]");
}

void CostGradientModel::compute_velocities(const CrowdWorld& w, std::size_t begin, std::size_t end,
                                           double* new_vx, double* new_vy) const {
  const CostGradientParams& P = params_;
  const double T = P.lookahead_s, inv_sigma = 1.0 / P.sigma_m;
  const double quad = P.goal + P.smoothness;
  std::array<std::uint32_t, kMaxNeighbors> nb;
  std::array<double, kMaxNeighbors> nb_d2;
  for (std::size_t k_order = begin; k_order < end; ++k_order) {
    const std::uint32_t i = w.grid->order(k_order);
    const double xi = w.px[i], yi = w.py[i], ri = w.radius[i];
    // Nearest neighbours (sorted by distance, ties by index), as in ORCA.
    int count = 0;
    w.grid->for_each_within(
        xi, yi, P.neighbor_distance_m, [&](std::uint32_t j, double, double, double d2, double r2) {
          if (j == i) return r2;
          int pos = count;
          if (count == P.max_neighbors) {
            if (d2 > nb_d2[count - 1] || (d2 == nb_d2[count - 1] && j > nb[count - 1])) return r2;
            --pos;
          } else {
            ++count;
          }
          while (pos > 0 && (nb_d2[pos - 1] > d2 || (nb_d2[pos - 1] == d2 && nb[pos - 1] > j))) {
            nb_d2[pos] = nb_d2[pos - 1];
            nb[pos] = nb[pos - 1];
            --pos;
          }
          nb_d2[pos] = d2;
          nb[pos] = j;
          return count == P.max_neighbors ? nb_d2[count - 1] : r2;
        });
    // Start at the minimiser of the quadratic terms.
    double vx = (P.goal * w.pref_vx[i] + P.smoothness * w.vx[i]) / quad;
    double vy = (P.goal * w.pref_vy[i] + P.smoothness * w.vy[i]) / quad;
    for (int it = 0; it < P.iterations; ++it) {
      double gx = 2.0 * P.goal * (vx - w.pref_vx[i]) + 2.0 * P.smoothness * (vx - w.vx[i]);
      double gy = 2.0 * P.goal * (vy - w.pref_vy[i]) + 2.0 * P.smoothness * (vy - w.vy[i]);
      double curvature = 2.0 * quad;
      for (int k = 0; k < count; ++k) {
        const std::uint32_t j = nb[k];
        // Closest approach within the look-ahead (seed 001 eqs. 2-3): t = clamp(ttca, 0, T).
        const double px = xi - w.px[j], py = yi - w.py[j], dvx = vx - w.vx[j], dvy = vy - w.vy[j];
        const double dv2 = dvx * dvx + dvy * dvy;
        const double t = dv2 > 1e-12 ? std::clamp(-(px * dvx + py * dvy) / dv2, 0.0, T) : T;
        const double qx = px + dvx * t, qy = py + dvy * t;
        const double q = std::sqrt(qx * qx + qy * qy);
        if (q <= 1e-9) continue;
        const double e = P.separation * std::exp(-(q - ri - w.radius[j]) * inv_sigma);
        // d|q|/dv = t q/|q| (Danskin: |q| is the minimum over t, so t's own dependence on v drops).
        const double s = -e * inv_sigma * t / q;  // d/dv of the exp term is s * q_vec
        gx += s * qx, gy += s * qy;
        curvature += e * inv_sigma * inv_sigma * t * t;
      }
      if (P.walls > 0.0) {
        for (const ObstacleSegment& seg : *w.obstacles) {
          const Vec2 x(xi + vx * T, yi + vy * T);
          const Vec2 c = closest_point_on_segment(seg.a, seg.b, x);
          const Vec2 o = x - c;
          const double d = o.norm();
          if (d <= 1e-9 || d > P.neighbor_distance_m) continue;
          const double e = P.walls * std::exp(-(d - ri) * inv_sigma);
          const double s = -e * inv_sigma * T / d;
          gx += s * o.x(), gy += s * o.y();
          curvature += e * inv_sigma * inv_sigma * T * T;
        }
      }
      vx -= gx / curvature;
      vy -= gy / curvature;
    }
    clamp_speed(vx, vy, w.max_speed[i]);
    new_vx[k_order] = vx;
    new_vy[k_order] = vy;
  }
}

}  // namespace crowdlab
