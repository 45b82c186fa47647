// A game loop that corrects its characters' collisions online, one frame at a time. docs/embedding.md
// shows this file verbatim; tests/embedding/test_embedding.cpp compiles it, runs it and checks the result.
#pragma once
#include <algorithm>
#include <vector>

#include "framework/core/body_shape.hpp"
#include "framework/core/crowd_animation.hpp"
#include "framework/core/pose.hpp"
#include "framework/correction/corrector.hpp"

namespace game {

struct GameLog {
  std::vector<crowdlab::BodyShape> bodies;
  std::vector<std::vector<crowdlab::Pose>> animated;   // per frame: what the animation system wanted
  std::vector<std::vector<crowdlab::Pose>> corrected;  // per frame: what the game shows
};

// Two characters face the stage (+Z); the second one's animation slides it 0.5 m into the first one
// over two seconds, as a crowd animation system that ignores bodies would.
inline GameLog run_game_loop(int frames, double fps) {
  GameLog log;
  // 1. Once, when the characters spawn: their bodies and the corrector.
  log.bodies = {crowdlab::make_procedural_body({crowdlab::Sex::kFemale, 1.65, 1.0}),
                crowdlab::make_procedural_body({crowdlab::Sex::kMale, 1.80, 1.1})};
  crowdlab::CorrectorParams params;   // seed 000 defaults (damping d = 0.006)
  crowdlab::Environment environment;  // the ground plane y = 0
  crowdlab::Corrector corrector(log.bodies, params, environment, fps);

  // 2. Every frame: animate as usual, then let the corrector resolve the contacts.
  for (int f = 0; f < frames; ++f) {
    const double t = f / fps;
    std::vector<crowdlab::Pose> poses = {crowdlab::Pose::rest(log.bodies[0]),
                                         crowdlab::Pose::rest(log.bodies[1])};
    poses[1].root_position_m.x() = 0.8 - 0.5 * std::min(t / 2.0, 1.0);  // walks into character 0
    std::vector<crowdlab::Pose> shown = corrector.step(poses);          // same order, one pose per character
    // ... render `shown` instead of `poses`; corrector.last_stats() counts this step's contacts ...
    log.animated.push_back(std::move(poses));
    log.corrected.push_back(std::move(shown));
  }
  return log;
}

}  // namespace game
