#pragma once
// CostGradientModel: agents that choose their next velocity by locally minimising a cost, with no
// collision constraint, in the spirit of the gradient-based simulator seed 001 used (Hoyet et al. 2016
// §4.1, "similar to [Treuille et al. 2006]": characters move so as to locally optimise a cost
// function; residual collisions are produced on purpose by tuning its weights).
// Treuille, Cooper & Popovic 2006 (Continuum Crowds) weigh path length, time and discomfort; this
// local form keeps those three ingredients for one step ahead:
//   C(v) = w_goal   |v - v_pref|^2                         (length/time: keep the preferred velocity)
//        + w_smooth |v - v_old|^2                          (inertia: no instantaneous turns)
//        + w_sep    sum_j exp(-(|q_j(v)| - r_ij) / sigma)  (discomfort near neighbours)
//        + w_wall   sum_W exp(-(d_W(v) - r_i) / sigma)     (discomfort near walls)
//   q_j(v) = (p_i - p_j) + (v - v_j) t_j  predicted separation at the closest approach within the
//            look-ahead T (s): t_j = clamp(ttca_ij(v), 0, T), ttca as seed 001 eq. 2, so |q_j| is
//            dtca (eq. 3) when the closest approach lies within T. Anticipating the closest approach
//            (rather than the position after a fixed T) is what makes agents on a collision course
//            sidestep early: for a head-on pair q_j is the lateral miss distance, so the gradient is
//            lateral. With a fixed T it pointed mostly along the line of approach and only braked,
//            and every head-on pair of a bidirectional flow collided (seed 001 Table 2, B at 0.5/m^2:
//            2153 colliding pair-frames vs the paper's 28). Gradient-based steering on ttca/dtca is
//            also Dutra et al. 2017 (Comput. Graph. Forum 36(2)), from seed 001's group.
//            Gradient: d|q_j|/dv = t_j q_j/|q_j| (|q_j| is a minimum over t; Danskin's theorem);
//   d_W(v)  distance from p_i + v T to wall W.
// Minimised by `iterations` gradient steps from the minimiser of the two quadratic terms, each with
// a diagonal Gauss-Newton step size 1 / (2 (w_goal + w_smooth) + sum of exp-term curvatures), then
// capped at max speed. Because separation is only a soft cost, w_sep dials residual collisions: low
// values give many overlaps (Table 2 of seed 001), high values few.
// Spec keys (crowd.cost_weights): goal, smoothness, separation, walls, sigma_m, lookahead_s,
// iterations. The defaults below are generic; experiments/hoyet2016_crowds.yaml sets separation 1.0,
// sigma_m 0.3, lookahead_s 2.0 for seed 001 Table 2 (chosen once for the whole table; its comment
// and docs/reproductions.md say why).
#include <map>
#include <string>

#include "framework/crowd/navigation_model.hpp"

namespace crowdlab {

struct CostGradientParams {
  double goal = 1.0;         ///< w_goal, (s/m)^2
  double smoothness = 0.5;   ///< w_smooth, (s/m)^2
  double separation = 0.3;   ///< w_sep (cost units)
  double walls = 1.0;        ///< w_wall
  double sigma_m = 0.15;     ///< discomfort fall-off length sigma (m)
  double lookahead_s = 1.0;  ///< T (s)
  int iterations = 4;
  double neighbor_distance_m = 2.0;
  int max_neighbors = 16;  ///< [1, 64] nearest neighbours considered
};

/// Reads the spec's crowd.cost_weights map over the defaults. Unknown keys or bad values throw
/// InputError naming the key ("crowd.cost_weights.<key>").
CostGradientParams cost_gradient_params_from_weights(const std::map<std::string, double>& weights,
                                                     CostGradientParams defaults = {});

class CostGradientModel final : public NavigationModel {
 public:
  static constexpr int kMaxNeighbors = 64;
  explicit CostGradientModel(const CostGradientParams& params);
  std::string_view name() const override { return "cost"; }
  double neighbor_radius_m() const override { return params_.neighbor_distance_m; }
  void compute_velocities(const CrowdWorld& world, std::size_t begin, std::size_t end, double* new_vx,
                          double* new_vy) const override;
  const CostGradientParams& params() const { return params_; }

 private:
  CostGradientParams params_;
};

}  // namespace crowdlab
