#pragma once
// A crowd walking on a SurfaceMesh (seed 002). Immutable model (mesh, parameters, goal distance
// fields) + mutable state (agents, scratch). One step, in named stages:
//   1. bin      agents into a 3D hash grid of body centres (cell = neighbour distance), by the same
//               counting sort as the 2D neighbour grid (framework/core/bucket_sort.hpp)
//   2. relevant per agent, candidates from the 27 surrounding cells filtered by RelevantMode, the
//               max_neighbors with the smallest body clearance (stacked_clearance) kept (relevance.hpp).
//               Ranking by body clearance, not by centre distance: two agents on perpendicular surfaces
//               whose heads touch have centres 1.3 m apart, and in a crowd ten coplanar agents with
//               nearer centres pushed them out of the list (measured: most social-force collisions on
//               the floor-wall corner were such pairs, dropped with a full list of 10).
//   3. steer    preferred velocity down the goal's geodesic field + avoidance in the tangent plane from
//               the Offset tuples (three stacked spheres) of each relevant neighbour
//   4. move     every agent along the surface (surface_walk.hpp), all from the old state (two-phase)
// Stages 2-3 run in parallel over agents and write per-agent slots only, so results do not depend on
// the thread count.
//
// Avoidance (social forces, Helbing & Molnar 1995 with the constants of Helbing, Farkas & Vicsek 2000,
// Nature 407:487: A = 2000 N, B = 0.08 m, k = 1.2e5 kg/s^2, tau = 0.5 s, m = 80 kg):
//   acc = (v_pref - v) / tau + sum_neighbours [A exp(-c/B) + k max(0, -c)] (-u) / m
// where (u, c) is the neighbour's Offset tuple with the smallest clearance c (the union of the three
// sphere tuples acts through its most threatening member, so coplanar agents feel exactly the classic
// force and agents on perpendicular walls feel their heads' proximity).
//
// Avoidance (ORCA / RVO, van den Berg et al. 2011; tangent_orca.hpp): every Offset tuple of every
// relevant neighbour (the union of seed 002's OffsetImproved) becomes one reciprocal half-plane in a's
// tangent plane (disc of combined radius 2 * sphere radius at the tuple's angle and 3D distance);
// near-duplicate tuples (coplanar agents give three equal ones) are merged. The new velocity is the
// one closest to v_pref within max_speed satisfying them (lp2, lp3 when infeasible).
// ORCA is collision-free only for motion exactly as planned; on a surface the motion deviates from
// the plan (crossing a crease rotates the velocity, a boundary clips it, the visibility filter and the
// projection change between steps) and, planning to the contact distance, agents then touch or
// overlap. So ORCA plans with each sphere grown by orca_margin_m = 10 cm (our choice, of the order of
// the social-force range B = 8 cm). Measured (200 agents, two-storey building, 300 steps): agent-frames
// with an overlap 25 % at 0 cm, 1.2 % at 5 cm, 0.8 % at 10 cm, 0.4 % at 20 cm.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "framework/crowd/social_force_model.hpp"
#include "framework/surface/relevance.hpp"
#include "framework/surface/surface_walk.hpp"

namespace crowdlab {

/// The ObstacleAvoidance function fed by Relevant/Offset (seed 002 §1 evaluates both).
enum class SurfaceAvoidance { kSocialForces, kOrca };

struct SurfaceCrowdParams {
  SurfaceAvoidance avoidance = SurfaceAvoidance::kSocialForces;
  StackedBody body;                  ///< height, sphere radius and spacing (metres)
  double neighbor_distance_m = 3.0;  ///< candidate radius between body centres; (0, 10]
  int max_neighbors = 10;            ///< [1, 32]
  double preferred_speed_mps = 1.3;  ///< (0, 3]
  double max_speed_mps = 1.8;        ///< >= preferred speed
  double dt_s = 1.0 / 30.0;          ///< (0, 0.2]
  RelevantMode relevant = RelevantMode::kVisibility;
  /// The 2D crowd model's social-force constants (A_n, B_m, k_body, relaxation_s, mass_kg), one source for
  /// both (framework/crowd/social_force_model.hpp); the surface model uses no wall or friction terms.
  SocialForceParams social;
  double orca_time_horizon_s = 2.0;  ///< ORCA tau (s), as the 2D crowd model's default; (0, 10]
  double orca_margin_m = 0.1;        ///< ORCA plans with each sphere radius + margin (m); [0, 1]; see header
  double goal_reached_m = 0.75;      ///< a new goal is chosen within this geodesic distance
  /// The body's up (sphere stack, body centre, feet disk, tangent plane of the avoidance): true =
  /// smooth_surface_up (vertex normals blended across the face, so a body tilts over the triangles
  /// next to a crease, as the pipeline renders it); false = the face normal, which snaps by the crease
  /// angle when an agent crosses an edge. Measured (200 agents, 300 steps, 3 seeds): on the 20 cm slab
  /// and the floor-wall corner most colliding pairs had an agent that had just crossed a sharp crease:
  /// the head swept ~1.3 m in one step into an agent the avoidance could not anticipate (docs/surfaces.md).
  bool smooth_body_up = true;
};

struct SurfaceCrowdModel {
  std::shared_ptr<const SurfaceMesh> mesh;
  SurfaceCrowdParams params;
  std::vector<int> goal_vertices;                ///< (G)
  std::vector<std::vector<double>> goal_fields;  ///< (G x V) geodesic distance to each goal, metres
  std::shared_ptr<const TriangleBvh> bvh;        ///< kVisibilityMesh only (over *mesh)
};

/// Validates params (InputError naming the parameter) and computes `goal_count` goal fields at vertices
/// drawn from `seed` (area-uniform).
SurfaceCrowdModel make_surface_crowd_model(std::shared_ptr<const SurfaceMesh> mesh,
                                           const SurfaceCrowdParams& params, int goal_count,
                                           std::uint64_t seed);

struct SurfaceCrowdState {
  std::vector<SurfacePoint> points;  ///< (N) where each agent stands
  std::vector<Vec3> velocity_mps;    ///< (N) tangent velocity, world frame
  std::vector<int> goal;             ///< (N) index into model.goal_fields
  std::vector<int> neighbors;        ///< (N x max_neighbors) relevant neighbours of the last step
  std::vector<int> neighbor_count;   ///< (N)
  long step_index = 0;
  // Scratch, sized once (no allocation per step after the first).
  std::vector<std::uint32_t> cell_slot, slot_start, slot_agents;
  std::vector<Vec3> center_m, up;  ///< (N) body centres and up vectors of the old state
  struct SortedAgent {             ///< what a neighbour scan reads, in one cache-friendly record
    Vec3 center_m, feet_m, up;
    int index;
  };
  std::vector<SortedAgent> sorted;  ///< (N) agents in slot (cell) order
  std::vector<Vec3> next_velocity;
  std::vector<int> next_goal;
  std::vector<std::vector<int>> face_agents;  ///< kSurface mode only
};

/// Places n agents on random faces (area-weighted), at least two sphere radii apart (same side), each
/// with a goal. Throws InputError when n < 1 or they do not fit after many attempts.
SurfaceCrowdState spawn_surface_agents(const SurfaceCrowdModel& model, int n, std::uint64_t seed);

/// "social" | "orca" -> SurfaceAvoidance; InputError naming `key` otherwise.
SurfaceAvoidance parse_surface_avoidance(const std::string& text, const std::string& key);
const char* surface_avoidance_name(SurfaceAvoidance a);

/// One simulation step (see header). Deterministic for any TBB thread count.
void step_surface_crowd(const SurfaceCrowdModel& model, SurfaceCrowdState& state);

/// The body's up at p (see SurfaceCrowdParams::smooth_body_up); unit, world frame.
Vec3 body_up(const SurfaceCrowdModel& model, const SurfacePoint& p);

/// Body centre (feet + body_up * height / 2), world frame.
Vec3 body_center(const SurfaceCrowdModel& model, const SurfacePoint& p);

}  // namespace crowdlab
