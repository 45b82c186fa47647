#include "framework/crowd/pair_closest_approaches.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/closest_approach.hpp"
#include "framework/core/csv.hpp"
#include "framework/core/error.hpp"
#include "framework/crowd/neighbor_grid.hpp"

namespace crowdlab {

void for_each_close_pair(const CrowdTrajectories& t, int frame, double max_distance_m,
                         const std::function<void(int, int, double)>& visit) {
  if (!(max_distance_m > 0.0) || !std::isfinite(max_distance_m))
    throw InputError("measures: the pair distance limit must be > 0 m");
  const std::size_t n = t.agents.size();
  std::vector<double> x(n), y(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& p = t.agents[i].position_m.at(static_cast<std::size_t>(frame));
    x[i] = p.x(), y[i] = p.y();
  }
  NeighborGrid grid(max_distance_m);
  grid.rebuild(x.data(), y.data(), n);
  std::vector<std::pair<std::uint32_t, double>> near;
  for (std::size_t i = 0; i < n; ++i) {
    near.clear();
    grid.for_each_within(x[i], y[i], max_distance_m,
                         [&](std::uint32_t j, double, double, double d2, double r2) {
                           if (j > i && d2 < max_distance_m * max_distance_m)
                             near.emplace_back(j, std::sqrt(d2));
                           return r2;
                         });
    std::sort(near.begin(), near.end());
    for (const auto& [j, d] : near) visit(static_cast<int>(i), static_cast<int>(j), d);
  }
}

std::vector<PairApproach> pair_closest_approaches(const CrowdTrajectories& t, double max_distance_m) {
  std::vector<PairApproach> out;
  for (int f = 0; f < t.frame_count(); ++f) {
    for_each_close_pair(t, f, max_distance_m, [&](int i, int j, double d) {
      const auto fi = static_cast<std::size_t>(f);
      const Vec2 vi = trajectory_velocity(t, static_cast<std::size_t>(i), fi);
      const Vec2 vj = trajectory_velocity(t, static_cast<std::size_t>(j), fi);
      const ClosestApproach ca = closest_approach(t.agents[static_cast<std::size_t>(i)].position_m[fi], vi,
                                                  t.agents[static_cast<std::size_t>(j)].position_m[fi], vj);
      out.push_back({f, i, j, d, ca.ttca_s, ca.dtca_m});
    });
  }
  return out;
}

std::string pair_closest_approaches_csv(const std::vector<PairApproach>& rows, double fps) {
  std::string s = csv_line({"frame", "time_s", "i", "j", "distance_m", "ttca_s", "dtca_m"});
  for (const PairApproach& r : rows)
    s +=
        csv_line({std::to_string(r.frame), csv_number(r.frame / fps), std::to_string(r.i),
                  std::to_string(r.j), csv_number(r.distance_m), csv_number(r.ttca_s), csv_number(r.dtca_m)});
  return s;
}

}  // namespace crowdlab
