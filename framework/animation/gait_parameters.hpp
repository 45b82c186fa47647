#pragma once
// Speed-dependent gait parameters of the procedural walk.
//
// Cadence and step length follow the "walk ratio" relation: step length / step rate is nearly
// constant across walking speeds for a given adult (Sekiya, Nagasaki et al. 1996; Sekiya & Nagasaki,
// Gait & Posture 7:225-227, 1998: ~0.0064-0.0066 m per step/min in young adults, scaling with
// stature). With WR = 0.0065 * (H / 1.70 m) m·min/step and v = L * c / 60:
//   cadence c(v) = sqrt(60 v / WR)   [steps/min]
//   step length L(v) = WR * c(v)     [m]
// At v = 1.3 m/s and H = 1.70 m this gives c = 110 steps/min and L = 0.71 m, the free-speed values of
// Grieve & Gear (Ergonomics 9:379, 1966) and Murray, Drought & Kory (JBJS 46A, 1964).
//
// Stance phase: 62 % of the gait cycle (Murray et al. 1964 at free speed), so double support takes
// 2 x 12 % of the cycle. Kept constant over 0.5-1.8 m/s so the contact schedule is a pure function of
// the phase.
//
// Angular amplitudes (radians) grow linearly with speed from their slow-walk to fast-walk values
// (Inman, Ralston & Todd, "Human Walking", 1981; Murray, Sepic & Barnard, Phys Ther 47:272, 1967):
//   pelvic rotation +-3..+-6 deg, pelvic list (obliquity) +-3..+-5 deg, thorax counter-rotation
//   50 % of the pelvic rotation, shoulder flexion/extension +-8..+-25 deg, elbow flexion 15..30 deg
//   mean with +-5..+-15 deg swing.
namespace crowdlab {

inline constexpr double kWalkRatioAt170 = 0.0065;  ///< m·min/step at stature 1.70 m
inline constexpr double kStanceFraction = 0.62;
inline constexpr double kMinGaitSpeed = 0.5;  ///< the procedural gait's speed range (m/s)
inline constexpr double kMaxGaitSpeed = 1.8;

struct GaitParameters {
  double speed_mps = 0;
  double cadence_steps_per_min = 0;
  double step_length_m = 0;
  double stride_frequency_hz = 0;  ///< full cycles (two steps) per second
  double pelvic_rotation_rad = 0;  ///< amplitude about the vertical
  double pelvic_list_rad = 0;      ///< amplitude of the frontal-plane drop of the swing side
  double lateral_sway_m = 0;       ///< amplitude of the pelvis shift toward the stance foot
  double arm_swing_rad = 0;        ///< shoulder flexion/extension amplitude
  double elbow_mean_rad = 0;
  double elbow_swing_rad = 0;
  double trunk_lean_rad = 0;     ///< forward lean of the trunk
  double foot_lift_m = 0;        ///< peak ankle rise during swing
  double toe_off_pitch_rad = 0;  ///< heel-rise angle reached at toe-off
};

/// Parameters at `speed_mps` (clamped to [0.5, 1.8]) for a person of stature `height_m`.
GaitParameters gait_parameters(double speed_mps, double height_m);

}  // namespace crowdlab
