#pragma once
// count_spec_collisions: the collision count of one trajectory set per scenario x density x repetition
// of a spec's conditions, the input of seed 001 Table 2 (collision_table.hpp).
//
// What is counted (seed 001 is terse; this is our reading, with the reasons):
//   collisions = sum over the clip's frames (spec.fps, spec.duration_s; the paper: 10 s at 30 Hz,
//   §4.2.2) of the number of character pairs whose discs overlap (centre distance < r_i + r_j) in
//   that frame, over ALL pairs of the scene (in scenario A the flow's own pairs too).
//   * per frame, not per event: seed 001 treats a collision as a per-frame state (§3.1, eq. 1: "n_i is
//     the number of frames where v_i(f) != 0 ... i.e., when there is a collision"), and Table 2's
//     "number of collisions detected by our system" (§4.3) is what a per-frame detector reports.
//     Event onsets cannot give Table 2's A 0.5/m^2 cell: at 1.4 m spacing the flow walks in step and
//     only the focal character meets anyone, and 50 +- 4 distinct encounters in 10 s is more than it
//     passes (~2.6 m/s x 10 s / 1.4 m ~ 19 rows); 50 frames (1.7 s of contact) is plausible.
//   * all pairs, not only the focal character's in A: A 2.8/m^2 has 4546 +- 76 in 300 frames, i.e.
//     15 simultaneous overlaps per frame on average, more than one disc can have around it (<= 6).
//   The number of distinct events (a pair starting to overlap, disc_collision_events.hpp) is kept
//   beside it for reference. Other factors (trigger, viewpoint, method...) do not change the 2D crowd, so
// each (resolved scenario type, density level, repetition) is generated once, with the seed of the
// first condition that has it.
#include <vector>

#include "framework/crowd/collision_table.hpp"
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

/// One CollisionCount per distinct (scenario, density, repetition), in condition order. The scenario
/// is the condition's `scenario` level (e.g. "A") or else the resolved type; density the `density`
/// level or else the achieved density. Shows a Progress bar per trajectory set.
/// Throws InputError like generate_scenario.
std::vector<CollisionCount> count_spec_collisions(const ExperimentSpec& spec,
                                                  const std::vector<Condition>& conditions);

}  // namespace crowdlab
