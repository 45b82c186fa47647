#pragma once
// OrcaModel: Optimal Reciprocal Collision Avoidance (van den Berg, Guy, Lin, Manocha 2011,
// "Reciprocal n-Body Collision Avoidance", ISRR 2009 / STAR 70), written from the paper.
//
// Per agent A and neighbour B (relative position p = p_B - p_A, relative velocity v = v_A - v_B,
// combined radius r = r_A + r_B, horizon tau):
//   VO_tau = {v : exists t in [0, tau], |v t - p| < r} is a cone with legs tangent to the disc
//   D(p, r) truncated by the disc D(p / tau, r / tau). u is the smallest change of v that leaves it
//   (projection onto the cut-off circle or onto the nearer leg), n its outward normal, and
//   ORCA = {v' : (v' - (v_A + u / 2)) . n >= 0}   (each agent takes half the responsibility, Sec. 4).
//   When the discs already overlap, the horizon becomes the step dt (resolve within one step).
// Obstacles (line segments, Sec. 5.1 with full responsibility): this implementation uses, for each
// segment within reach, the supporting half-plane at the segment's closest point c with normal
// n = (p_A - c) / |p_A - c| and offset (|p_A - c| - r_A) / tau_obst: v' . n >= -(d - r_A) / tau_obst.
// It is conservative (a subset of the paper's segment ORCA, which also admits velocities past an
// end point) and provably safe for tau_obst (any segment point lies behind the plane through c);
// if already overlapping, v' . n >= (r_A - d) / dt pushes the agent out within one step.
// Neighbours: the max_neighbors nearest within neighbor_distance (bounded sorted list, ties by index).
// Solve: lp2 with v_pref as the optimum and |v'| <= max_speed; on failure lp3 (Sec. 5.2).
// Behaviour in jams (measured, as the paper predicts): while every program is feasible, discs never
// overlap (tests/crowd/test_orca.cpp); when a jam makes them infeasible, lp3 only minimises the largest
// violation, so discs can overlap: up to ~0.28 m for 250 agents meeting at the centre of the 0.6 m
// antipodal circle at dt = 0.1 s, ~5 mm at dt = 0.01 s. Smaller dt reduces it.
#include "framework/crowd/navigation_model.hpp"

namespace crowdlab {

struct OrcaParams {
  double neighbor_distance_m = 2.0;      ///< (0, inf); RVO2 example default 15 m, crowdlab 2 m
  int max_neighbors = 10;                ///< [1, 64]
  double time_horizon_s = 2.0;           ///< tau for agents (> 0)
  double obstacle_time_horizon_s = 2.0;  ///< tau for obstacles (> 0)
  /// Overlap-free mode (off by default: plain ORCA as in the paper and RVO2). See the header.
  bool resolve_overlaps = false;
};

class OrcaModel final : public NavigationModel {
 public:
  static constexpr int kMaxNeighbors = 64;
  static constexpr int kMaxObstacleLines = 32;

  /// Throws InputError when a parameter is out of range.
  explicit OrcaModel(const OrcaParams& params);
  std::string_view name() const override { return "orca"; }
  double neighbor_radius_m() const override { return params_.neighbor_distance_m; }
  bool resolves_overlaps() const override { return params_.resolve_overlaps; }
  void compute_velocities(const CrowdWorld& world, std::size_t begin, std::size_t end, double* new_vx,
                          double* new_vy) const override;
  const OrcaParams& params() const { return params_; }

 private:
  OrcaParams params_;
};

}  // namespace crowdlab
