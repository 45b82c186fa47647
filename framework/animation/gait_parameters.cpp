#include "framework/animation/gait_parameters.hpp"

#include <algorithm>
#include <cmath>

namespace crowdlab {

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;
double lerp(double a, double b, double t) {
  return a + (b - a) * t;
}
}  // namespace

GaitParameters gait_parameters(double speed_mps, double height_m) {
  const double v = std::clamp(speed_mps, kMinGaitSpeed, kMaxGaitSpeed);
  const double t = (v - kMinGaitSpeed) / (kMaxGaitSpeed - kMinGaitSpeed);
  const double wr = kWalkRatioAt170 * height_m / 1.70;
  GaitParameters g;
  g.speed_mps = v;
  g.cadence_steps_per_min = std::sqrt(60.0 * v / wr);
  g.step_length_m = wr * g.cadence_steps_per_min;
  g.stride_frequency_hz = g.cadence_steps_per_min / 120.0;
  g.pelvic_rotation_rad = lerp(3.0, 6.0, t) * kDeg;
  g.pelvic_list_rad = lerp(3.0, 5.0, t) * kDeg;
  g.lateral_sway_m = lerp(0.025, 0.015, t) * height_m / 1.70;  // slower walks sway more
  g.arm_swing_rad = lerp(8.0, 25.0, t) * kDeg;
  g.elbow_mean_rad = lerp(15.0, 30.0, t) * kDeg;
  g.elbow_swing_rad = lerp(5.0, 15.0, t) * kDeg;
  g.trunk_lean_rad = lerp(1.0, 5.0, t) * kDeg;
  g.foot_lift_m = lerp(0.05, 0.09, t) * height_m / 1.70;
  g.toe_off_pitch_rad = lerp(20.0, 40.0, t) * kDeg;
  return g;
}

}  // namespace crowdlab
