#pragma once
// SocialForceModel: Helbing & Molnar 1995 ("Social force model for pedestrian dynamics", Phys. Rev. E
// 51) in the form and with the constants of Helbing, Farkas & Vicsek 2000 ("Simulating dynamical
// features of escape panic", Nature 407, p. 487 and its Methods):
//   m_i dv_i/dt = m_i (v0_i e_i - v_i) / tau                                   (driving term)
//               + sum_j [A exp((r_ij - d_ij)/B) + k g(r_ij - d_ij)] n_ij
//                       + kappa g(r_ij - d_ij) (dv_ji . t_ij) t_ij               (agents)
//               + sum_W [A exp((r_i - d_iW)/B) + k g(r_i - d_iW)] n_iW
//                       - kappa g(r_i - d_iW) (v_i . t_iW) t_iW                  (walls)
// with r_ij = r_i + r_j, d_ij the centre distance, n_ij = (x_i - x_j)/d_ij, t_ij = (-n_y, n_x),
// dv_ji = (v_j - v_i) . t_ij, g(x) = max(x, 0), and for walls d_iW / n_iW to the closest wall point.
// Constants (HFV 2000): A = 2000 N, B = 0.08 m, k = 1.2e5 kg/s^2, kappa = 2.4e5 kg/(m s), m = 80 kg,
// tau = 0.5 s. The driving term uses the preferred velocity v0_i e_i from the simulation; speeds
// are capped at the agent's max speed (HFV cap v_max). Integration: semi-implicit Euler with steps
// of at most 0.01 s (the contact terms are stiff: sqrt(k/m) = 39 rad/s and kappa/m*g ~ 150 1/s
// need h < ~0.013 s for stability); interactions beyond neighbor_distance are ignored
// (A exp(-1 m / B) < 0.01 N).
#include "framework/crowd/navigation_model.hpp"

namespace crowdlab {

struct SocialForceParams {
  double A_n = 2000.0;            ///< agent repulsion strength A (N)
  double B_m = 0.08;              ///< agent repulsion range B (m)
  double wall_A_n = 2000.0;       ///< wall repulsion strength (N)
  double wall_B_m = 0.08;         ///< wall repulsion range (m)
  double k_body = 1.2e5;          ///< body compression k (kg/s^2)
  double kappa_friction = 2.4e5;  ///< sliding friction kappa (kg/(m s))
  double mass_kg = 80.0;
  double relaxation_s = 0.5;  ///< tau
  double neighbor_distance_m = 2.0;
  double max_step_s = 0.01;
};

class SocialForceModel final : public NavigationModel {
 public:
  explicit SocialForceModel(const SocialForceParams& params);
  std::string_view name() const override { return "social"; }
  double max_step_s() const override { return params_.max_step_s; }
  double neighbor_radius_m() const override { return params_.neighbor_distance_m; }
  void compute_velocities(const CrowdWorld& world, std::size_t begin, std::size_t end, double* new_vx,
                          double* new_vy) const override;
  const SocialForceParams& params() const { return params_; }

 private:
  SocialForceParams params_;
};

}  // namespace crowdlab
