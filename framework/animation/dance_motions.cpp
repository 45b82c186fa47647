#include "framework/animation/dance_motions.hpp"

#include <cmath>

#include "framework/animation/rotation_helpers.hpp"

namespace crowdlab {

namespace {
using anim::kPi;
constexpr double k2Pi = 2.0 * kPi;

using anim::frac;
// 1 on the beat, 0 half-way between beats, smooth (a "dip" envelope).
double on_beat(double b) {
  return 0.5 + 0.5 * std::cos(k2Pi * b);
}
// Sine with a period of `beats`.
double wave(double b, double beats, double phase = 0.0) {
  return std::sin(k2Pi * (b / beats + phase));
}

// A step of one foot during the first half of a beat: moves from `from` to `to` while lifted.
struct Step {
  double offset, lift;
};
Step step_move(double u, double from, double to, double height) {
  if (u >= 0.5) return {to, 0.0};
  const double s = u / 0.5;
  return {from + (to - from) * anim::cosine_ease(s), height * std::sin(kPi * s)};
}

void relaxed_arms(DancePose& p, double b, double a, double swing) {
  for (int s = 0; s < 2; ++s) {
    p.arm[static_cast<size_t>(s)] = {0.15 + swing * a * wave(b, 2.0, 0.5 * s), kPi / 2 - 0.4, 0.5, 0.0};
  }
}

DancePose bounce(double b, double a) {
  DancePose p;
  p.pelvis_offset.y() = -0.045 * a * on_beat(b);
  p.spine_pitch = 0.06 * a * on_beat(b);
  p.head_pitch = 0.10 * a * on_beat(b - 0.1);
  relaxed_arms(p, b, a, 0.08);
  for (auto& arm : p.arm) arm.elbow = 0.6 + 0.2 * on_beat(b);
  return p;
}

DancePose sway(double b, double a) {
  DancePose p;
  const double s = wave(b, 2.0);
  p.pelvis_offset.x() = 0.05 * a * s;
  p.pelvis_offset.y() = -0.02 * a * std::abs(s);
  p.pelvis_roll = -0.06 * a * s;
  p.spine_roll = 0.10 * a * s;
  p.head_roll = -0.06 * a * s;
  relaxed_arms(p, b, a, 0.1);
  p.arm[0].raise += 0.15 * a * (0.5 + 0.5 * s);
  p.arm[1].raise += 0.15 * a * (0.5 - 0.5 * s);
  return p;
}

DancePose wave_overhead(double b, double a) {
  DancePose p;
  const double s = wave(b, 4.0);
  p.pelvis_offset.y() = -0.02 * a * on_beat(b);
  p.spine_roll = 0.12 * a * s;
  p.head_pitch = -0.1;
  p.arm[0] = {2.55 + 0.25 * a * s, 0.35, 0.25, 0.1};
  p.arm[1] = {2.55 - 0.25 * a * s, 0.35, 0.25, 0.1};
  return p;
}

DancePose fist_pump(double b, double a) {
  DancePose p = bounce(b, 0.6 * a);
  const double pump = on_beat(b + 0.15);
  p.arm[1] = {1.7 + 1.0 * a * pump, 0.9, 1.7 - 1.3 * pump, 0.05 * pump};
  p.head_pitch = -0.05 - 0.08 * a * pump;
  return p;
}

DancePose jump(double b, double a) {
  DancePose p;
  // Jumps at the start of beats 0 and 2 (airborne for the first 35 % of the beat); a landing crouch
  // after each and a preparatory crouch before it (position c in the 2-beat cycle, wrapped).
  const double c = std::fmod(b, 2.0);
  const double u = frac(b);
  const bool jump_beat = c < 1.0;
  const double air = jump_beat && u < 0.35 ? std::sin(kPi * u / 0.35) : 0.0;
  const double lift = 0.10 * a * air;
  auto bump = [&](double centre) {
    double d = c - centre;
    d -= 2.0 * std::round(d / 2.0);
    return std::exp(-d * d / (0.12 * 0.12));
  };
  const double crouch = 0.06 * a * (bump(0.5) + bump(1.85));
  p.pelvis_offset.y() = lift - crouch;
  for (auto& f : p.foot) f.lift = lift;
  p.spine_pitch = 0.1 * crouch / 0.06;
  const double arms = 0.5 + 0.5 * std::cos(kPi * (b - 0.15));  // up around each take-off, period 2 beats
  p.arm[0] = {0.4 + 1.6 * a * arms, 0.5, 0.5, 0.0};
  p.arm[1] = p.arm[0];
  return p;
}

DancePose head_nod(double b, double a) {
  DancePose p;
  p.pelvis_offset.y() = -0.02 * a * on_beat(b);
  p.spine_pitch = 0.12 * a * on_beat(b);
  p.head_pitch = 0.30 * a * on_beat(b - 0.05);
  relaxed_arms(p, b, a, 0.05);
  for (auto& arm : p.arm) arm.elbow = 0.8;
  return p;
}

DancePose clap(double b, double a) {
  DancePose p = bounce(b, 0.5 * a);
  const double open = 1.0 - on_beat(b);  // hands together on the beat
  for (auto& arm : p.arm) arm = {1.05, kPi / 2 + 0.35 - 0.45 * open * a, 1.25, 0.0};
  p.head_pitch += 0.05;
  return p;
}

DancePose step_touch(double b, double a) {
  DancePose p;
  // Beat 0: right foot steps out; 1: right foot back; 2: left out; 3: left back.
  const int beat = static_cast<int>(std::floor(b)) % 4;
  const double u = frac(b);
  const double w = 0.16 * a, h = 0.06 * a;
  double out_right = 0, out_left = 0;
  if (beat == 0) {
    const Step st = step_move(u, 0, w, h);
    p.foot[1] = {st.offset, 0, st.lift, 0};
    out_right = st.offset;
  } else if (beat == 1) {
    const Step st = step_move(u, w, 0, h);
    p.foot[1] = {st.offset, 0, st.lift, 0};
    out_right = st.offset;
  } else if (beat == 2) {
    const Step st = step_move(u, 0, w, h);
    p.foot[0] = {st.offset, 0, st.lift, 0};
    out_left = st.offset;
  } else {
    const Step st = step_move(u, w, 0, h);
    p.foot[0] = {st.offset, 0, st.lift, 0};
    out_left = st.offset;
  }
  p.pelvis_offset.x() = 0.5 * (out_left - out_right);
  p.pelvis_offset.y() = -0.03 * a * on_beat(b);
  p.pelvis_roll = 0.8 * (out_right - out_left);
  p.spine_roll = -0.6 * (out_right - out_left);
  relaxed_arms(p, b, a, 0.25);
  for (auto& arm : p.arm) arm.elbow = 1.0;
  return p;
}

DancePose twist(double b, double a) {
  DancePose p;
  const double s = wave(b, 2.0);
  p.pelvis_yaw = 0.25 * a * s;
  p.spine_yaw = -0.35 * a * s;
  p.pelvis_offset.y() = -0.05 * a;
  p.foot[0].heel = 0.25 * a * (0.5 + 0.5 * s);
  p.foot[1].heel = 0.25 * a * (0.5 - 0.5 * s);
  p.arm[0] = {0.7 - 0.25 * a * s, kPi / 2 - 0.6, 1.5, 0.0};
  p.arm[1] = {0.7 + 0.25 * a * s, kPi / 2 - 0.6, 1.5, 0.0};
  return p;
}

DancePose shoulder_shimmy(double b, double a) {
  DancePose p = bounce(b, 0.4 * a);
  const double s = std::sin(k2Pi * 2.0 * b);
  p.arm[0] = {0.35, kPi / 2 - 0.5, 1.4, 0.12 * a * (0.5 + 0.5 * s)};
  p.arm[1] = {0.35, kPi / 2 - 0.5, 1.4, 0.12 * a * (0.5 - 0.5 * s)};
  p.spine_yaw = 0.12 * a * s;
  p.spine_pitch = 0.08;
  return p;
}

DancePose hands_up_sway(double b, double a) {
  DancePose p;
  const double s = wave(b, 8.0);
  p.pelvis_offset.x() = 0.06 * a * s;
  p.pelvis_offset.y() = -0.015 * a * on_beat(b);
  p.pelvis_roll = -0.05 * a * s;
  p.spine_roll = 0.09 * a * s;
  p.head_pitch = -0.15;
  p.arm[0] = {2.45 + 0.1 * a * s, 0.15, 0.15, 0.1};
  p.arm[1] = {2.45 - 0.1 * a * s, 0.15, 0.15, 0.1};
  return p;
}

DancePose point_up(double b, double a) {
  DancePose p = bounce(b, 0.6 * a);
  // Right arm points on beats 0 and 2, left on 1 and 3, each a smooth rise and fall.
  const double r = 0.5 - 0.5 * std::cos(kPi * b);  // 1 on odd... period 2 beats
  const double right = 1.0 - r, left = r;
  p.arm[1] = {0.3 + 2.2 * a * right, 1.1, 1.2 * (1 - right) + 0.1, 0.0};
  p.arm[0] = {0.3 + 2.2 * a * left, 1.1, 1.2 * (1 - left) + 0.1, 0.0};
  p.head_pitch = -0.1 * a;
  return p;
}

DancePose knee_pop(double b, double a) {
  DancePose p;
  const double s = wave(b, 2.0);
  p.foot[0].heel = 0.35 * a * std::max(0.0, s);
  p.foot[1].heel = 0.35 * a * std::max(0.0, -s);
  p.pelvis_offset.y() = -0.04 * a * std::abs(s);
  p.pelvis_roll = 0.06 * a * s;
  p.pelvis_offset.x() = -0.025 * a * s;
  p.spine_roll = -0.08 * a * s;
  relaxed_arms(p, b, a, 0.15);
  for (auto& arm : p.arm) arm.elbow = 0.9;
  return p;
}

DancePose idle_weight_shift(double b, double a) {
  DancePose p;
  const double s = wave(b, 8.0);
  p.pelvis_offset.x() = 0.03 * a * s;
  p.pelvis_roll = -0.03 * a * s;
  p.spine_roll = 0.04 * a * s;
  p.spine_pitch = 0.015 * wave(b, 4.0);  // breathing
  p.head_yaw = 0.35 * a * wave(b, 8.0, 0.25) * wave(b, 8.0 / 3.0);
  p.foot[0].heel = 0.12 * std::max(0.0, -s);  // the unloaded knee relaxes
  p.foot[1].heel = 0.12 * std::max(0.0, s);
  relaxed_arms(p, b, a, 0.03);
  return p;
}

DancePose idle_hands_together(double b, double a) {
  DancePose p;
  const double s = wave(b, 8.0);
  p.pelvis_offset.x() = 0.02 * a * s;
  p.spine_pitch = 0.02 + 0.015 * wave(b, 4.0);
  p.head_yaw = 0.3 * a * wave(b, 8.0, 0.6);
  p.head_pitch = 0.05 * wave(b, 4.0, 0.3);
  for (auto& arm : p.arm) arm = {0.45, kPi / 2 + 0.25, 1.35, 0.0};
  return p;
}

DancePose clap_overhead(double b, double a) {
  DancePose p = bounce(b, 0.5 * a);
  const double open = 1.0 - on_beat(b);
  for (auto& arm : p.arm) arm = {2.75 - 0.15 * open, 0.9 + 0.6 * open * a, 0.35, 0.08};
  p.head_pitch = -0.12;
  return p;
}

}  // namespace

const std::array<DanceMotion, 16>& dance_motions() {
  static const std::array<DanceMotion, 16> motions = {{
      {"bounce", 4, false, bounce},
      {"sway", 4, false, sway},
      {"wave_overhead", 4, false, wave_overhead},
      {"fist_pump", 4, false, fist_pump},
      {"jump", 4, false, jump},
      {"head_nod", 4, false, head_nod},
      {"clap", 4, false, clap},
      {"step_touch", 4, false, step_touch},
      {"twist", 4, false, twist},
      {"shoulder_shimmy", 4, false, shoulder_shimmy},
      {"hands_up_sway", 8, false, hands_up_sway},
      {"point_up", 4, false, point_up},
      {"knee_pop", 4, false, knee_pop},
      {"idle_weight_shift", 8, true, idle_weight_shift},
      {"idle_hands_together", 8, true, idle_hands_together},
      {"clap_overhead", 4, false, clap_overhead},
  }};
  return motions;
}

}  // namespace crowdlab
