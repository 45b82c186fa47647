#include "framework/crowd/collision_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "framework/core/csv.hpp"

namespace crowdlab {

std::vector<CollisionTableCell> collision_table(const std::vector<CollisionCount>& counts) {
  std::vector<std::string> order;
  std::map<std::pair<std::string, double>, std::vector<double>> groups, events;
  for (const CollisionCount& c : counts) {
    if (std::find(order.begin(), order.end(), c.scenario) == order.end()) order.push_back(c.scenario);
    groups[{c.scenario, c.density}].push_back(static_cast<double>(c.collisions));
    events[{c.scenario, c.density}].push_back(static_cast<double>(c.events));
  }
  std::vector<CollisionTableCell> cells;
  for (const std::string& sc : order) {
    for (const auto& [key, values] : groups) {
      if (key.first != sc) continue;
      CollisionTableCell cell{sc, key.second, static_cast<int>(values.size()), 0.0, 0.0, 0.0};
      for (double v : values) cell.mean += v;
      cell.mean /= static_cast<double>(values.size());
      for (double v : events[key]) cell.mean_events += v / static_cast<double>(values.size());
      if (values.size() > 1) {
        double ss = 0.0;
        for (double v : values) ss += (v - cell.mean) * (v - cell.mean);
        cell.sd = std::sqrt(ss / static_cast<double>(values.size() - 1));
      }
      cells.push_back(cell);
    }
  }
  return cells;
}

std::string collision_table_csv(const std::vector<CollisionTableCell>& cells) {
  std::string s =
      csv_line({"scenario", "density", "repetitions", "mean_collisions", "sd_collisions", "mean_events"});
  for (const CollisionTableCell& c : cells)
    s += csv_line({c.scenario, csv_number(c.density), std::to_string(c.repetitions), csv_number(c.mean),
                   csv_number(c.sd), csv_number(c.mean_events)});
  return s;
}

std::string collision_table_markdown(const std::vector<CollisionTableCell>& cells) {
  std::vector<double> densities;
  std::vector<std::string> scenarios;
  for (const CollisionTableCell& c : cells) {
    if (std::find(densities.begin(), densities.end(), c.density) == densities.end())
      densities.push_back(c.density);
    if (std::find(scenarios.begin(), scenarios.end(), c.scenario) == scenarios.end())
      scenarios.push_back(c.scenario);
  }
  std::sort(densities.begin(), densities.end());
  char buf[64];
  std::string s = "| Density |";
  for (double d : densities) std::snprintf(buf, sizeof buf, " %g |", d), s += buf;
  s += "\n|---|";
  for (std::size_t k = 0; k < densities.size(); ++k) s += "---|";
  s += "\n";
  for (const std::string& sc : scenarios) {
    s += "| Scenario " + sc + " |";
    for (double d : densities) {
      auto it = std::find_if(cells.begin(), cells.end(),
                             [&](const CollisionTableCell& c) { return c.scenario == sc && c.density == d; });
      if (it == cells.end()) {
        s += " |";
      } else {
        std::snprintf(buf, sizeof buf, " %.0f \u00b1 %.0f |", it->mean, it->sd);
        s += buf;
      }
    }
    s += "\n";
  }
  return s;
}

}  // namespace crowdlab
