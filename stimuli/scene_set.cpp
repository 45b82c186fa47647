#include "stimuli/scene_set.hpp"

#include <cmath>

namespace crowdlab::stimuli {
namespace {

/// A box centred at `c` (x, z on the floor plan; y is its centre height) with half extents `h` in the frame
/// whose +z axis is `forward` (unit, horizontal).
DecorBox box_in(const Vec3& c, const Vec3& h, const Vec3& forward, const Rgb& colour, float emission = 0.0f) {
  DecorBox d;
  d.box.center_m = c;
  d.box.half_extents_m = h;
  d.box.rotation = Quat(Eigen::AngleAxisd(std::atan2(forward.x(), forward.z()), Vec3::UnitY()));
  d.colour = colour;
  d.emission = emission;
  return d;
}

std::vector<DecorBox> concert_hall(const CrowdAnimation& crowd, const Vec3& lo, const Vec3& hi) {
  std::vector<DecorBox> out;
  const Box& stage = crowd.environment.boxes.front();
  const Vec3 centre(0.5 * (lo.x() + hi.x()), 0.0, 0.5 * (lo.z() + hi.z()));
  Vec3 forward = stage.center_m - centre;  // toward the stage
  forward.y() = 0.0;
  if (forward.norm() < 1e-6) return out;
  forward.normalize();
  const Vec3 side = Vec3::UnitY().cross(forward);  // horizontal, perpendicular
  const Vec3 stage_floor(stage.center_m.x(), 0.0, stage.center_m.z());
  const double stage_top = stage.center_m.y() + stage.half_extents_m.y();
  const double stage_back = stage.half_extents_m.z();
  // Behind the stage: back wall and backdrop.
  const Vec3 back = stage_floor + forward * (stage_back + 0.3);
  out.push_back(box_in(back + Vec3(0, 3.0, 0), {8.0, 3.0, 0.15}, forward, rgb(58, 56, 64)));
  out.push_back(
      box_in(back - forward * 0.2 + Vec3(0, stage_top + 2.0, 0), {4.5, 2.0, 0.03}, forward, rgb(34, 30, 52)));
  // The truss above the stage front and its lamps (warm white, amber, magenta, cyan).
  const Vec3 truss = stage_floor - forward * (stage_back - 0.3) + Vec3(0, 4.6, 0);
  out.push_back(box_in(truss, {5.0, 0.12, 0.12}, forward, rgb(40, 40, 44)));
  const Rgb lamps[6] = {rgb(255, 236, 200), rgb(255, 176, 80), rgb(240, 90, 200),
                        rgb(90, 210, 255),  rgb(255, 176, 80), rgb(255, 236, 200)};
  for (int k = 0; k < 6; ++k)
    out.push_back(box_in(truss + side * (-3.75 + 1.5 * k) - Vec3(0, 0.3, 0), {0.16, 0.18, 0.16}, forward,
                         lamps[k], 1.0f));
  // The hall around the crowd: back wall, side walls, wall lamps, an exit sign.
  const double half_depth = 0.5 * std::max(hi.x() - lo.x(), hi.z() - lo.z());
  const Vec3 rear = centre - forward * (half_depth + 5.0);
  const double hall_len = (stage_floor - rear).norm() + stage_back + 0.6;
  const Vec3 hall_mid = rear + forward * (0.5 * hall_len);
  const Rgb wall = rgb(86, 80, 92);
  out.push_back(box_in(rear + Vec3(0, 3.0, 0), {9.0, 3.0, 0.15}, forward, wall));
  for (int s = -1; s <= 1; s += 2)
    out.push_back(
        box_in(hall_mid + side * (9.0 * s) + Vec3(0, 3.0, 0), {0.15, 3.0, 0.5 * hall_len}, forward, wall));
  for (int k = -2; k <= 2; ++k)
    out.push_back(box_in(rear + forward * 0.2 + side * (3.2 * k) + Vec3(0, 3.2, 0), {0.2, 0.12, 0.05},
                         forward, rgb(255, 214, 150), 1.0f));
  out.push_back(box_in(rear + forward * 0.2 + side * 7.0 + Vec3(0, 2.4, 0), {0.3, 0.12, 0.04}, forward,
                       rgb(60, 220, 110), 1.0f));
  return out;
}

std::vector<DecorBox> corridor_walls(const CrowdAnimation& crowd) {
  std::vector<DecorBox> out;
  const Rgb plaster = rgb(196, 188, 176), skirting = rgb(70, 66, 62), pilaster = rgb(172, 164, 152);
  for (const Box& barrier : crowd.environment.boxes) {
    const double x = barrier.center_m.x(), outward = x < 0 ? -1.0 : 1.0;
    const double half_len = barrier.half_extents_m.z(), z = barrier.center_m.z();
    const double face = x + outward * (barrier.half_extents_m.x() + 0.15);
    const Vec3 along = Vec3::UnitZ();
    out.push_back(box_in({face + outward * 0.1, 1.3, z}, {0.1, 1.3, half_len}, along, plaster));
    out.push_back(box_in({face - outward * 0.01, 0.06, z}, {0.02, 0.06, half_len}, along, skirting));
    for (double p = z - half_len + 1.5; p < z + half_len; p += 3.0) {
      out.push_back(box_in({face - outward * 0.06, 1.3, p}, {0.07, 1.3, 0.2}, along, pilaster));
      out.push_back(
          box_in({face - outward * 0.15, 2.35, p + 1.5}, {0.1, 0.05, 0.3}, along, rgb(255, 240, 214), 1.0f));
    }
  }
  return out;
}

}  // namespace

std::vector<DecorBox> make_scene_set(const CrowdAnimation& crowd, const Vec3& bounds_lo,
                                     const Vec3& bounds_hi) {
  if (crowd.environment.boxes.empty()) return {};
  if (crowd.meta.scenario == "stationary") return concert_hall(crowd, bounds_lo, bounds_hi);
  if (crowd.meta.scenario == "corridor") return corridor_walls(crowd);
  return {};
}

}  // namespace crowdlab::stimuli
