#pragma once
// BENCHMARK / TEST FIXTURE, not a crowd generator: a stationary crowd of idly swaying characters for
// `crowdlab bench correct`, the correction tests and the damping experiment, so that this stage can be
// exercised without the crowd and animation stages.
//
// Placement: a jittered square grid at the requested density D (characters per m^2): spacing 1/sqrt(D),
// each position jittered by up to +-10 % of the spacing (minimum spacing ~0.8 of the grid spacing, close to a
// Poisson-disk sample at the same density), headings toward +Z +- 0.4 rad. Bodies: core make_procedural_body,
// alternately female/male, heights drawn from normal distributions with the world adult means of NCD-RisC
// 2016 (eLife 5:e13410: women 1.59 m, men 1.71 m; SD 0.065 / 0.07 m, clamped to [1.45, 1.95] m), girth
// uniform in [0.9, 1.1]. Motion: the pelvis and legs stand still (feet planted), arms hang at ~55 deg below
// horizontal; the spine, neck, shoulders and elbows follow slow sinusoids (0.3-0.6 Hz, per-character phase),
// a few degrees to ~15 degrees in amplitude. Target poses are free of self-collision by construction.
#include <cstdint>

#include "framework/core/crowd_animation.hpp"

namespace crowdlab {

struct SwayingCrowdOptions {
  int characters = 20;
  double density_per_m2 = 2.22;
  int frames = 60;
  double fps = 30.0;
  std::uint64_t seed = 1;
  double sway_amplitude = 1.0;  ///< multiplies every sinusoid amplitude (0 = a frozen crowd)
};

/// Throws InputError for characters < 1, density <= 0, frames < 1 or fps <= 0.
CrowdAnimation make_swaying_crowd_fixture(const SwayingCrowdOptions& options);

/// The swaying pose of one character at time t (seconds): used by the fixture, exposed for tests.
Pose swaying_pose(const BodyShape& shape, const Vec3& floor_position_m, double heading_rad, double phase_rad,
                  double frequency_hz, double amplitude, double t_s);

}  // namespace crowdlab
