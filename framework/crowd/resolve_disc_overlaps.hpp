#pragma once
// resolve_disc_overlaps: a position-level non-penetration projection for disc agents and wall
// segments, run after a navigation step whose velocity constraints could not all be met.
//
// Why: ORCA is collision-free only while every agent's linear program is feasible (van den Berg et
// al. 2011, Sec. 5.2: in dense crowds the 3D program merely minimises the largest violation, "so
// collisions may occur"). In a jam (e.g. 250 agents meeting at the centre of the antipodal circle)
// the violations accumulate to overlaps of decimetres. This pass restores the hard non-penetration
// constraint |p_i - p_j| >= r_i + r_j and dist(p_i, wall) >= r_i by projecting positions, the
// constraint projection of position-based dynamics (Mueller et al. 2007, "Position Based Dynamics",
// Sec. 3.3, equal masses) that position-based crowds use for the same purpose (Weiss et al. 2017,
// "Position-based Multi-Agent Dynamics for Real-Time Crowd Simulation", Sec. 4).
//
// Algorithm: candidates are the agents with check[i] != 0 (the model's flag: "my constraints were
// infeasible or I already overlap") or every agent when check is null. Overlapping pairs/walls
// within reach of a candidate are collected, then projected Gauss-Seidel in a fixed order (pairs in
// order of (i, j), each pushed apart symmetrically to exact contact plus `separation_slack_m`; an
// agent is pushed fully out of a wall). Agents moved by the projection become candidates of the
// next round, so contacts created by a push are found too. Rounds stop when no overlap deeper than
// `tolerance_m` remains or after `max_rounds`. Sequential and ordered, so the result does not depend
// on the number of threads. Velocities are left to the model (this only corrects positions).
//
// Inputs: px/py (n) positions in m, updated in place; radius (n) m; grid built over positions that
// differ from the current ones by at most `max_stale_m` (the query radius is widened by it);
// walls (segments, m). `pairs` is scratch kept by the caller so steady state allocates nothing.
// Returns the deepest overlap left (m; <= 0 when none) and counts for reporting.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "framework/crowd/navigation_model.hpp"
#include "framework/crowd/neighbor_grid.hpp"

namespace crowdlab {

struct OverlapResolutionOptions {
  double tolerance_m = 1e-5;         ///< overlaps at most this deep are left alone (m)
  double separation_slack_m = 1e-6;  ///< pushes go this far past exact contact (m)
  double contact_margin_m = 0.05;    ///< pairs this close (gap, m) join the projection: pushes can close them
  int max_rounds = 8;                ///< detection rounds (each followed by Gauss-Seidel sweeps)
  int sweeps_per_round = 16;         ///< Gauss-Seidel sweeps over the collected contacts
};

struct OverlapResolutionResult {
  double deepest_overlap_m = 0.0;  ///< deepest overlap left after the projection (m)
  std::size_t contacts = 0;        ///< agent-agent and agent-wall contacts projected
  int rounds = 0;
};

struct OverlapContact {
  std::uint32_t i = 0, j = 0;  ///< agents; j == kWall: wall segment `wall` against agent i
  std::uint32_t wall = 0;
  static constexpr std::uint32_t kWall = 0xffffffffu;
};

/// scratch: contacts buffer and per-agent "moved" marks (resized on first use only).
struct OverlapResolutionScratch {
  std::vector<OverlapContact> contacts;
  std::vector<unsigned char> moved, candidate;
  std::vector<double> shift;  ///< (n) distance each agent has been pushed this call (m)
};

OverlapResolutionResult resolve_disc_overlaps(double* px, double* py, const double* radius, std::size_t n,
                                              const unsigned char* check, const NeighborGrid& grid,
                                              double max_stale_m, const std::vector<ObstacleSegment>& walls,
                                              const OverlapResolutionOptions& options,
                                              OverlapResolutionScratch& scratch);

}  // namespace crowdlab
