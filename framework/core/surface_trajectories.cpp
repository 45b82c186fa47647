#include "framework/core/surface_trajectories.hpp"

#include "framework/core/csv.hpp"

namespace crowdlab {

std::string surface_trajectories_csv(const SurfaceTrajectories& t, double fps) {
  std::string s = csv_line({"character", "frame", "time_s", "x", "y", "z", "up_x", "up_y", "up_z",
                            "forward_x", "forward_y", "forward_z"});
  for (std::size_t i = 0; i < t.agents.size(); ++i) {
    const SurfaceAgentTrajectory& a = t.agents[i];
    for (std::size_t f = 0; f < a.feet_m.size(); ++f) {
      std::vector<std::string> row{std::to_string(i), std::to_string(f),
                                   csv_number(static_cast<double>(f) / fps)};
      for (const Vec3* v : {&a.feet_m[f], &a.up[f], &a.forward[f]})
        for (int k = 0; k < 3; ++k) row.push_back(csv_number((*v)[k]));
      s += csv_line(row);
    }
  }
  return s;
}

}  // namespace crowdlab
