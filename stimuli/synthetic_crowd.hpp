#pragma once
// A small procedural crowd built in code, for renderer tests, benchmarks and quick looks without a
// crowd file: characters on a jittered grid facing +Z, procedural bodies (half women, half men,
// heights and girths varied), arms lowered from the T-pose and a looping idle motion (sway, arm
// swing, head turn) whose period equals the clip length, so the clip loops seamlessly. Optionally a
// walking crowd (a plain sinusoidal gait, not the animation stage's) between corridor walls.
#include <cstdint>

#include "framework/core/crowd_animation.hpp"

namespace crowdlab::stimuli {

struct SyntheticCrowdOptions {
  int characters = 20;
  int frames = 30;
  double fps = 30.0;
  double spacing_m = 0.7;  ///< grid pitch; below ~0.45 m neighbours interpenetrate
  std::uint64_t seed = 1;
  bool stage = true;            ///< add a low stage box in front of the crowd
  int columns = 0;              ///< characters per row (0: a square grid)
  double walk_speed_mps = 0.0;  ///< > 0: everyone walks toward +Z with a simple procedural gait
  bool corridor_walls = false;  ///< add two long walls on both sides of the crowd path
};

CrowdAnimation make_synthetic_crowd(const SyntheticCrowdOptions& options);

}  // namespace crowdlab::stimuli
