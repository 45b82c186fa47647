#pragma once
// NavigationModel: the one interface every 2D navigation model implements (ORCA, social forces,
// cost-gradient). A model is immutable; CrowdSimulation owns the mutable state and runs each step in
// two phases:
//   1. compute: every agent's new velocity from the OLD state only (compute_velocities, in parallel
//      over agent ranges, each agent writing its own slot);
//   2. commit:  velocities and positions are updated for all agents at once.
// So the result does not depend on agent order or on the number of threads.
//
// Frame: the ground plane as 2D (x, y) = world (x, z), metres, seconds.
#include <cmath>
#include <cstddef>
#include <limits>
#include <string_view>
#include <vector>

#include "framework/core/math_types.hpp"
#include "framework/crowd/neighbor_grid.hpp"

namespace crowdlab {

/// A static line-segment obstacle (a wall), metres. Both sides block.
struct ObstacleSegment {
  Vec2 a = Vec2::Zero();
  Vec2 b = Vec2::Zero();
};

/// Read-only view of the old state handed to a model in phase 1. Arrays have `count` entries.
struct CrowdWorld {
  std::size_t count = 0;
  const double* px = nullptr;  ///< positions (m)
  const double* py = nullptr;
  const double* vx = nullptr;  ///< current velocities (m/s)
  const double* vy = nullptr;
  const double* pref_vx = nullptr;  ///< preferred velocities this step (m/s)
  const double* pref_vy = nullptr;
  const double* radius = nullptr;      ///< disc radii (m)
  const double* max_speed = nullptr;   ///< speed limits (m/s)
  const NeighborGrid* grid = nullptr;  ///< built over (px, py); cell >= model's neighbour radius
  const std::vector<ObstacleSegment>* obstacles = nullptr;
  double dt = 0.1;  ///< the (sub)step being taken (s)
  /// Optional per-agent output (count entries, zeroed by the caller): a model sets 1 where it could
  /// not keep agent i collision-free this step (infeasible constraints, or already overlapping), so
  /// that the simulation's overlap projection (resolve_disc_overlaps.hpp) looks there. May be null.
  unsigned char* needs_contact_check = nullptr;
};

/// Scales (vx, vy) down to length max_speed when it is longer (m/s): every model's speed limit.
inline void clamp_speed(double& vx, double& vy, double max_speed) {
  const double speed2 = vx * vx + vy * vy;
  if (speed2 > max_speed * max_speed) {
    const double s = max_speed / std::sqrt(speed2);
    vx *= s, vy *= s;
  }
}

class NavigationModel {
 public:
  virtual ~NavigationModel() = default;
  virtual std::string_view name() const = 0;
  /// Largest step (s) the model integrates stably; the simulation subdivides its dt below this.
  virtual double max_step_s() const { return std::numeric_limits<double>::infinity(); }
  /// True when the simulation should project residual overlaps after each step, starting from the
  /// agents the model flags in CrowdWorld::needs_contact_check (ORCA; see orca_model.hpp).
  virtual bool resolves_overlaps() const { return false; }
  /// Radius (m) of the neighbourhood the model queries; the grid's cell is at least this.
  virtual double neighbor_radius_m() const = 0;
  /// Phase 1: new velocities of the agents at grid-order positions [begin, end) of world.grid (agent
  /// i = grid->order(k)), written to new_vx/new_vy[k], i.e. in grid order: each parallel task then
  /// writes one contiguous block, and no two cores write the same cache line.
  /// Must be thread-safe (const, no shared mutable state) and allocation-free.
  virtual void compute_velocities(const CrowdWorld& world, std::size_t begin, std::size_t end, double* new_vx,
                                  double* new_vy) const = 0;
};

}  // namespace crowdlab
