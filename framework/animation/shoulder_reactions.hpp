#pragma once
// Shoulder reactions of walking characters (seed 001 §4.1).
//
// Trigger (seed 001 Eqs. 2-3 via framework/core/closest_approach.hpp): on frame f, agent i has a
// collision risk with agent j when
//     0 <= ttca_ij < ttca_threshold   and   dtca_ij < dtca_threshold
// (defaults 0.7 s and 0.6 m, the paper's values). The paper writes ttca < ttca_th; a negative ttca
// means the closest approach is already past (the agents separate), which is no risk, so it is
// excluded. Velocities are the trajectories' central differences.
// Decision: a risk event starts on the first frame the condition holds for a pair (a rising edge);
// the agent reacts to it with probability p (its trigger level, e.g. 0, 0.33, 0.66, 1), drawn once
// per event from derive_seed(seed, "shoulder/<i>/<j>/<frame>"). With risks from several agents on
// the same frame (e.g. one on each side) the agent reacts to the earliest closest approach; while a
// reaction is still rising toward its peak, new risks are ignored.
// Side: the partner's position relative to the agent at the time of closest approach, in the agent's
// heading frame: on the left (+X) -> weight > 0 (torso presented to the left, reaction_pose.hpp).
// Envelope: rises from the current weight to +-1 over ttca (clamped to [0.25, 0.7] s, so the peak
// falls at the closest approach), holds 0.1 s and returns to 0 over 0.4 s: 1.2 s in all for a
// trigger at ttca = 0.7 s (0.75 s at the shortest), about one gait cycle at 1.3 m/s (110 steps/min
// = 1.09 s per cycle), i.e. one shoulder turn per passing, as in the paper's mocap clips where the
// reaction fits within the interaction. Raised-cosine blends keep the weight C1-continuous.
// Forced mode (pair experiment, seed 001 §3: "shoulder" factor 0/1/2): exactly `forced_count` agents
// (a seeded choice, preferring agents that meet any risk) react to every risk, the others never do; because
// that experiment's passing distances go up to 0.70 m, the dtca threshold is raised to max(dtca_threshold,
// 0.75 m) there.
#include <cstdint>
#include <vector>

#include "framework/core/trajectories.hpp"

namespace crowdlab {

struct ShoulderReactionParams {
  double ttca_threshold_s = 0.7;
  double dtca_threshold_m = 0.6;
  double trigger_probability = 1.0;  ///< per-event reaction probability in [0, 1]
  int forced_count = -1;             ///< >= 0: exactly this many agents react (probability ignored)
};

struct ShoulderEvent {
  int agent = 0;
  int partner = 0;
  int frame = 0;  ///< frame of the trigger (rising edge)
  double ttca_s = 0;
  double dtca_m = 0;
  int side = 0;  ///< +1 partner passes on the agent's left, -1 on its right
  bool reacted = false;
};

struct ShoulderReactions {
  std::vector<std::vector<double>> weight;  ///< (agents x frames) signed reaction weight in [-1, 1]
  std::vector<ShoulderEvent> events;        ///< every risk event, in (agent, frame) order
};

/// Throws InputError for bad parameters (negative thresholds, probability outside [0, 1]).
ShoulderReactions compute_shoulder_reactions(const CrowdTrajectories& trajectories,
                                             const ShoulderReactionParams& params, std::uint64_t seed);

}  // namespace crowdlab
