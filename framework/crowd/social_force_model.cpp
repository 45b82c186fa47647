#include "framework/crowd/social_force_model.hpp"

#include <cmath>
#include <cstdint>

#include "framework/core/error.hpp"
#include "framework/crowd/segment_distance.hpp"

namespace crowdlab {

SocialForceModel::SocialForceModel(const SocialForceParams& p) : params_(p) {
  auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  auto non_negative = [](double v) { return v >= 0.0 && std::isfinite(v); };
  if (!non_negative(p.A_n) || !positive(p.B_m) || !non_negative(p.wall_A_n) || !positive(p.wall_B_m))
    throw InputError("social force: A must be >= 0 N and B > 0 m");
  if (!non_negative(p.k_body) || !non_negative(p.kappa_friction))
    throw InputError("social force: k and kappa must be >= 0");
  if (!positive(p.mass_kg) || !positive(p.relaxation_s) || !positive(p.neighbor_distance_m) ||
      !positive(p.max_step_s))
    throw InputError("social force: mass, relaxation time, neighbour distance and step must be > 0");
}

void SocialForceModel::compute_velocities(const CrowdWorld& w, std::size_t begin, std::size_t end,
                                          double* new_vx, double* new_vy) const {
  const SocialForceParams& P = params_;
  const double inv_m = 1.0 / P.mass_kg;
  for (std::size_t k = begin; k < end; ++k) {
    const std::uint32_t i = w.grid->order(k);
    const double xi = w.px[i], yi = w.py[i], vxi = w.vx[i], vyi = w.vy[i], ri = w.radius[i];
    // Driving term, per unit mass.
    double ax = (w.pref_vx[i] - vxi) / P.relaxation_s;
    double ay = (w.pref_vy[i] - vyi) / P.relaxation_s;
    w.grid->for_each_within(xi, yi, P.neighbor_distance_m,
                            [&](std::uint32_t j, double dx, double dy, double d2, double r2) {
                              if (j == i || d2 <= 1e-20) return r2;
                              const double d = std::sqrt(d2);
                              const double nx = -dx / d, ny = -dy / d;  // from j to i
                              const double overlap = ri + w.radius[j] - d;
                              const double g = overlap > 0.0 ? overlap : 0.0;
                              const double fn = P.A_n * std::exp(overlap / P.B_m) + P.k_body * g;
                              const double tx = -ny, ty = nx;
                              const double dv_t = (w.vx[j] - vxi) * tx + (w.vy[j] - vyi) * ty;
                              const double ft = P.kappa_friction * g * dv_t;
                              ax += inv_m * (fn * nx + ft * tx);
                              ay += inv_m * (fn * ny + ft * ty);
                              return r2;
                            });
    for (const ObstacleSegment& s : *w.obstacles) {
      const Vec2 c = closest_point_on_segment(s.a, s.b, Vec2(xi, yi));
      const double ox = xi - c.x(), oy = yi - c.y();
      const double d = std::sqrt(ox * ox + oy * oy);
      if (d > P.neighbor_distance_m || d <= 1e-12) continue;
      const double nx = ox / d, ny = oy / d;
      const double overlap = ri - d;
      const double g = overlap > 0.0 ? overlap : 0.0;
      const double fn = P.wall_A_n * std::exp(overlap / P.wall_B_m) + P.k_body * g;
      const double tx = -ny, ty = nx;
      const double ft = -P.kappa_friction * g * (vxi * tx + vyi * ty);
      ax += inv_m * (fn * nx + ft * tx);
      ay += inv_m * (fn * ny + ft * ty);
    }
    double nvx = vxi + w.dt * ax, nvy = vyi + w.dt * ay;
    clamp_speed(nvx, nvy, w.max_speed[i]);
    new_vx[k] = nvx;
    new_vy[k] = nvy;
  }
}

}  // namespace crowdlab
