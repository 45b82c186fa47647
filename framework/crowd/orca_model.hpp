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
// Obstacles (line segments, Sec. 5.1, full responsibility): the exact segment velocity obstacle
// (legs, cut-off line and end arcs; orca_obstacle_line.hpp), nearest segment first, redundant
// segments skipped, all lines before the agents' and hard in lp3 (RVO2's order). Touching a wall:
// leave within one step along the normal (the 1/dt projection the paper uses for agents).
// Neighbours: the max_neighbors nearest within neighbor_distance, ties by index. Agents are visited
// in NeighborGrid::order() and the candidates of each 3x3 cell block are gathered once per cell with
// the neighbours' velocities and radii (data-oriented; results do not depend on visiting order).
// Solve: lp2 with v_pref as the optimum and |v'| <= max_speed; on failure lp3 (Sec. 5.2, the "3D"
// program: minimise the largest violation of the agent lines, obstacle lines hard).
// Behaviour in jams (measured, as the paper predicts): while every program is feasible, discs never
// overlap (tests/crowd/test_orca.cpp); when a jam makes them infeasible, lp3 only minimises the largest
// violation, so discs can overlap: up to ~0.29 m for 250 agents meeting at the centre of the 0.6 m
// antipodal circle at dt = 0.1 s. RVO2 behaves the same way (same programs).
// Overlap-free mode (params.resolve_overlaps, spec key crowd.overlap_free, off by default;
// crowdlab's addition, not the paper's):
//   * step guards: for each neighbour j that one step could bring into contact
//     (|p_j - p_i| < r_i + r_j + (v_max,i + v_max,j) dt), the half-plane v_i . n_ij <= b_ij, where the
//     pair's allowance gap / dt is shared by the pair's common motion along n_ij (step_guard in the
//     .cpp). If both keep their guards the pair cannot overlap by the end of the step; v = 0 satisfies
//     all guards, so they are always jointly feasible. They join the obstacles as HARD lines of lp3
//     only (in feasible steps ORCA is left exactly as published);
//   * agents that may still end the step overlapping (already touching, breaking a guard, or with
//     a full neighbour list inside the guard reach) are flagged; the simulation then projects the
//     remaining overlaps out (resolve_disc_overlaps.hpp) and sets v to the motion actually made.
//   Measured (plain ORCA -> overlap-free; last arrival / mean arrival, dt 0.1 s, jitter 0.01 m/s):
//     250-agent circle (plain 2 runs, overlap-free 5): deepest overlap 0.29-0.31 m -> <= 0.8 mm
//       (equal halves: up to 2.0 mm in 1 of 5); 81 / 58 s -> 102 / 81 s (equal halves 103 / 82 s);
//     24 agents through a 1.4 m doorway (10 seeds): 3-4.5 cm -> 0; 16.0 / 7.9 s -> 19.2 / 9.0 s;
//     40 agents in a 2.9 m corridor, two groups swapping ends (10 seeds): 11-12.5 cm -> 0;
//       77 / 33.6 s -> 97 / 36.8 s.
//   Equal halves (b_ij = gap / (2 dt), the first version) were slower: doorway 20.6 / 9.9 s,
//   corridor 122 / 40.1 s. Dense scenes still clear more slowly than with plain
//   ORCA (discs that must not interpenetrate queue instead), so it stays opt-in; the papers' studies
//   want the residual collisions of plain 2D models anyway.
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
