#pragma once
// CrowdSimulation: mutable agent state (structure-of-arrays) advanced by a NavigationModel in two-phase
// steps (see navigation_model.hpp). Agents steer toward goals at their preferred speed.
//
// Preferred velocity (the usual goal-seeking rule of ORCA/RVO2 and Helbing 2000's e_i v0_i):
//   v_pref = v0 * (g - p) / |g - p|, shortened to (g - p) / dt within one step of the goal.
// Models that ask for it (ORCA) get a position-level overlap projection after the commit, seeded by
// the agents they flag (resolve_disc_overlaps.hpp); it is sequential and ordered.
// Parallelism: TBB parallel_for over agent ranges (the model's phase over grid-order ranges); each
// agent writes only its own slot, so 1 or N threads give bit-identical states. Buffers are sized once; a step
// allocates nothing.
#include <cstdint>
#include <memory>
#include <vector>

#include "framework/crowd/navigation_model.hpp"
#include "framework/crowd/neighbor_grid.hpp"
#include "framework/crowd/resolve_disc_overlaps.hpp"

namespace crowdlab {

struct AgentInit {
  Vec2 position = Vec2::Zero();  ///< m
  Vec2 velocity = Vec2::Zero();  ///< m/s
  Vec2 goal = Vec2::Zero();      ///< m; the agent walks toward it
  double radius_m = 0.25;
  double preferred_speed_mps = 1.3;
  double max_speed_mps = 1.5;
};

class CrowdSimulation {
 public:
  /// dt_s > 0: the step advanced by step(); subdivided to the model's max_step_s().
  /// Throws InputError on non-finite or out-of-range agent values.
  CrowdSimulation(std::shared_ptr<const NavigationModel> model, std::vector<AgentInit> agents,
                  std::vector<ObstacleSegment> obstacles, double dt_s);

  /// Advances the state by dt (one or more substeps).
  void step();

  std::size_t size() const { return px_.size(); }
  double time_s() const { return time_; }
  double dt_s() const { return dt_; }
  int substeps() const { return substeps_; }
  Vec2 position(std::size_t i) const { return {px_[i], py_[i]}; }
  Vec2 velocity(std::size_t i) const { return {vx_[i], vy_[i]}; }
  double radius(std::size_t i) const { return radius_[i]; }
  const std::vector<ObstacleSegment>& obstacles() const { return obstacles_; }
  void set_goal(std::size_t i, const Vec2& goal) { gx_[i] = goal.x(), gy_[i] = goal.y(); }
  /// Overlap projections run so far, and contacts they projected (see resolve_disc_overlaps.hpp).
  long long overlap_resolutions() const { return overlap_resolutions_; }
  long long overlap_contacts() const { return overlap_contacts_; }

  /// Adds a tiny pseudo-random perturbation (uniform in a disc of radius `mps`) to every preferred
  /// velocity, drawn from (seed, agent, substep) so it is deterministic and thread-independent.
  /// Perfectly symmetric set-ups (agents on a circle) otherwise deadlock in ORCA; the RVO2 examples
  /// perturb preferred velocities for the same reason (van den Berg et al. 2011, Sec. 6). 0 = off.
  void set_preferred_velocity_jitter(double mps, std::uint64_t seed);

 private:
  void substep(double h);
  void update_preferred_velocity(double h, std::size_t i);

  std::shared_ptr<const NavigationModel> model_;
  std::vector<ObstacleSegment> obstacles_;
  double dt_ = 0.1, time_ = 0.0;
  int substeps_ = 1;
  long long substep_count_ = 0;
  double jitter_ = 0.0;
  std::uint64_t jitter_seed_ = 0;
  std::vector<double> px_, py_, vx_, vy_, gx_, gy_, pref_speed_, max_speed_, radius_;
  std::vector<double> pref_vx_, pref_vy_;
  std::vector<double> grid_vx_, grid_vy_;  // phase-1 velocities in grid order (NeighborGrid::order)
  std::vector<double> pre_x_, pre_y_;      // positions before the overlap projection
  std::vector<unsigned char> contact_flags_;
  NeighborGrid grid_;
  OverlapResolutionScratch overlap_scratch_;
  long long overlap_resolutions_ = 0, overlap_contacts_ = 0;
};

}  // namespace crowdlab
