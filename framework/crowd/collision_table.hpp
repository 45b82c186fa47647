#pragma once
// Collision counts per scenario x density across repetitions, in the form of seed 001 Table 2
// ("Average (+-SD) number of collisions detected by our system for each Scenario x Density
// condition across repetitions"). SD is the sample standard deviation (n - 1); 0 for one repetition.
#include <string>
#include <vector>

namespace crowdlab {

struct CollisionCount {
  std::string scenario;  ///< e.g. "A" / "B" / "flow_a"
  double density = 0.0;  ///< characters per m^2
  int repetition = 1;
  long long collisions = 0;  ///< colliding pair-frames (count_spec_collisions.hpp says why)
  long long events = 0;      ///< distinct collision events (pairs starting to overlap), for reference
};

struct CollisionTableCell {
  std::string scenario;
  double density = 0.0;
  int repetitions = 0;
  double mean = 0.0;
  double sd = 0.0;
  double mean_events = 0.0;  ///< mean of CollisionCount::events
};

/// One cell per (scenario, density), scenarios in first-seen order, densities ascending.
std::vector<CollisionTableCell> collision_table(const std::vector<CollisionCount>& counts);

/// CSV: scenario,density,repetitions,mean_collisions,sd_collisions,mean_events.
std::string collision_table_csv(const std::vector<CollisionTableCell>& cells);

/// Markdown like Table 2: a Density header row, one row per scenario with "mean ± sd" cells.
std::string collision_table_markdown(const std::vector<CollisionTableCell>& cells);

}  // namespace crowdlab
