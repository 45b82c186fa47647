#pragma once
// Local avoidance of a surface crowd (seed 002 §3; the "steer" stage of surface_crowd.hpp): agent i's
// new velocity from its preferred velocity and its relevant neighbours of this step
// (s.neighbors[i * max_neighbors + k], k < keep), in its tangent plane. One object per model, chosen
// once from SurfaceCrowdParams::avoidance, as the 2D crowd's NavigationModel is:
//   social forces  one explicit step of Helbing & Molnar's model with Helbing, Farkas & Vicsek's
//                  constants (the sf_* parameters), on each neighbour's Offset tuple of least clearance
//   orca           ORCA (van den Berg et al. 2011) in the tangent plane over the union of each
//                  neighbour's Offset tuples (tangent_orca.hpp)
// Inputs in metres, seconds and m/s, world frame; the result is neither projected onto the agent's
// face nor clamped to max_speed_mps (the caller does both). Stateless and thread-safe.
#include <cstddef>

#include "framework/surface/surface_crowd.hpp"

namespace crowdlab {

class SurfaceAvoidanceModel {
 public:
  virtual ~SurfaceAvoidanceModel() = default;
  virtual Vec3 velocity(const SurfaceCrowdModel& model, const SurfaceCrowdState& s, std::size_t i,
                        std::size_t keep, const Vec3& v_pref) const = 0;
};

/// The (shared, immutable) avoidance model of a kind.
const SurfaceAvoidanceModel& surface_avoidance_model(SurfaceAvoidance kind);

}  // namespace crowdlab
