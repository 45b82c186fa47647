#pragma once
// Deepest interpenetration (m, >= 0) among a set of posed bodies (their world capsules): the maximum of
// max_penetration_depth (penetration_depth.hpp) over the pairs whose body boxes overlap. Broad phase:
// sweep and prune on x (bodies sorted by their box's lower x; a pair is tested only while the second
// body's box starts before the first one's ends), then seed 000 §3.4's body-box test. A crowd of n
// bodies costs O(n log n) plus the neighbouring pairs instead of all n (n - 1) / 2 pairs.
// Used by the correction's loop closure (correct_crowd.cpp), which compares several closures by it and,
// per body, decides which characters it closes.
#include <span>
#include <vector>

#include "framework/core/forward_kinematics.hpp"

namespace crowdlab {

double deepest_crowd_penetration(std::span<const WorldCapsules> bodies);

/// Per body, its deepest interpenetration (m, >= 0) with any other body of the set (same broad phase).
std::vector<double> deepest_penetration_per_body(std::span<const WorldCapsules> bodies);

}  // namespace crowdlab
