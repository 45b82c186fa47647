#include "framework/crowd/disc_collision_events.hpp"

#include <algorithm>
#include <map>
#include <tuple>

#include "framework/core/csv.hpp"
#include "framework/crowd/pair_closest_approaches.hpp"

namespace crowdlab {

std::vector<CollisionEvent> disc_collision_events(const CrowdTrajectories& t) {
  double max_r = 0.0;
  for (const AgentTrajectory& a : t.agents) max_r = std::max(max_r, a.radius_m);
  std::vector<CollisionEvent> done;
  if (max_r <= 0.0) return done;
  std::map<std::pair<int, int>, CollisionEvent> open;  // ordered: deterministic
  const int frames = t.frame_count();
  for (int f = 0; f < frames; ++f) {
    std::map<std::pair<int, int>, double> now;
    for_each_close_pair(t, f, 2.0 * max_r, [&](int i, int j, double d) {
      const double pen =
          t.agents[static_cast<std::size_t>(i)].radius_m + t.agents[static_cast<std::size_t>(j)].radius_m - d;
      if (pen > 0.0) now[{i, j}] = pen;
    });
    for (auto it = open.begin(); it != open.end();) {
      if (!now.count(it->first)) {
        it->second.end_frame = f;
        done.push_back(it->second);
        it = open.erase(it);
      } else {
        ++it;
      }
    }
    for (const auto& [key, pen] : now) {
      auto [it, inserted] = open.try_emplace(key, CollisionEvent{key.first, key.second, f, frames, pen});
      if (!inserted) it->second.max_penetration_m = std::max(it->second.max_penetration_m, pen);
    }
  }
  for (auto& [key, e] : open) done.push_back(e);
  std::sort(done.begin(), done.end(), [](const CollisionEvent& a, const CollisionEvent& b) {
    return std::tie(a.start_frame, a.i, a.j) < std::tie(b.start_frame, b.i, b.j);
  });
  return done;
}

std::string disc_collision_events_csv(const std::vector<CollisionEvent>& events, double fps) {
  std::string s =
      csv_line({"i", "j", "start_frame", "end_frame", "start_time_s", "duration_s", "max_penetration_m"});
  for (const CollisionEvent& e : events)
    s += csv_line({std::to_string(e.i), std::to_string(e.j), std::to_string(e.start_frame),
                   std::to_string(e.end_frame), csv_number(e.start_frame / fps),
                   csv_number((e.end_frame - e.start_frame) / fps), csv_number(e.max_penetration_m)});
  return s;
}

}  // namespace crowdlab
