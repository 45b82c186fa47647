#pragma once
// Measures of a surface crowd (seed 002 §4), accumulated frame by frame.
//
// Ground truth for "could these two agents touch?" is exact: the straight segment between their body
// centres must not pass through the mesh (TriangleBvh). Against it:
//   collision percent  = 100 * (agent-frames whose three-sphere body overlaps a reachable agent's)
//                        / (agent-frames). Seed 002 §4 reports "collision percentages" and "median
//                        collision rates" (.05 %, .009 %; 1,000 agents) without a formula, denominator,
//                        time step or density; per agent-frame is our reading (the usual crowd-simulation
//                        convention). Bodies stand along body_up (the simulator's body), so ground truth
//                        and simulation agree on where each body is.
//   false positive     = an agent the Relevant function kept (so the avoidance model steers around it,
//                        at whatever distance) that is NOT reachable (e.g. the agent on the other side
//                        of a floor, or on the storey above);
//   false negative     = an agent within the interaction range (clearance below it), reachable, that
//                        Relevant dropped.
// Pairs are counted per agent per frame (ordered pairs).
#include "framework/surface/surface_crowd.hpp"
#include "framework/surface/triangle_bvh.hpp"

namespace crowdlab {

struct SurfaceCrowdMeasures {
  long agent_frames = 0;
  long colliding_agent_frames = 0;
  long false_positives = 0;
  long false_negatives = 0;
  double max_distance_to_surface_m = 0.0;  ///< how far any agent has been from its triangle
  double collision_percent() const {
    return agent_frames
               ? 100.0 * static_cast<double>(colliding_agent_frames) / static_cast<double>(agent_frames)
               : 0.0;
  }
};

/// Adds the current frame of `state` (after a step: uses its neighbour lists) to `m`.
/// interaction_range_m: clearance below which a pair counts for FP/FN (default 0.5 m).
void accumulate_surface_measures(const SurfaceCrowdModel& model, const SurfaceCrowdState& state,
                                 const TriangleBvh& bvh, SurfaceCrowdMeasures& m,
                                 double interaction_range_m = 0.5);

/// Distance (metres) from a point to the triangle `face` (0 when on it).
double distance_to_face(const SurfaceMesh& mesh, int face, const Vec3& point_m);

}  // namespace crowdlab
