#pragma once
// Helpers shared by the crowd tests: run a simulation while tracking the deepest disc overlap, and a
// hash of trajectories for determinism checks.
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "framework/core/sha256.hpp"
#include "framework/core/trajectories.hpp"
#include "framework/crowd/crowd_simulation.hpp"

namespace crowdlab::test {

/// Deepest overlap r_i + r_j - |p_i - p_j| over all pairs (negative when all apart), brute force.
inline double deepest_overlap(const CrowdSimulation& sim) {
  double worst = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < sim.size(); ++i)
    for (std::size_t j = i + 1; j < sim.size(); ++j)
      worst = std::max(worst, sim.radius(i) + sim.radius(j) - (sim.position(i) - sim.position(j)).norm());
  return worst;
}

/// SHA-256 over every position and heading bit pattern of the trajectories.
inline std::string trajectories_hash(const CrowdTrajectories& t) {
  std::string bytes;
  for (const AgentTrajectory& a : t.agents) {
    for (const Vec2& p : a.position_m)
      bytes.append(reinterpret_cast<const char*>(p.data()), 2 * sizeof(double));
    for (double h : a.heading_rad) bytes.append(reinterpret_cast<const char*>(&h), sizeof(double));
  }
  return sha256_hex(bytes);
}

/// Agents evenly spaced on a circle, each heading to its antipode.
inline std::vector<AgentInit> antipodal_circle(int n, double spacing_m, double radius_m) {
  const double R = n * spacing_m / (2.0 * 3.14159265358979323846);
  std::vector<AgentInit> agents(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * 3.14159265358979323846 * i / n;
    auto& g = agents[static_cast<std::size_t>(i)];
    g.position = R * Vec2(std::cos(a), std::sin(a));
    g.goal = -g.position;
    g.radius_m = radius_m;
    g.preferred_speed_mps = 1.5;
    g.max_speed_mps = 1.5;
  }
  return agents;
}

}  // namespace crowdlab::test
