// docs/embedding.md's game-loop example: it compiles (this file includes it), it corrects the collision
// it creates, and the document shows exactly the code that is compiled here.
#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>

#include "framework/metrics/measure_crowd.hpp"
#include "tests/embedding/game_loop_example.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_embedding {

namespace {

using crowdlab::test::slurp;

crowdlab::CrowdAnimation as_crowd(const game::GameLog& log, bool corrected, double fps) {
  crowdlab::CrowdAnimation crowd;
  crowd.meta.fps = fps;
  const auto& frames = corrected ? log.corrected : log.animated;
  for (size_t c = 0; c < log.bodies.size(); ++c) {
    crowdlab::CharacterAnimation ch;
    ch.name = "c00" + std::to_string(c);
    ch.shape = log.bodies[c];
    for (const auto& frame : frames) ch.frames.push_back(frame[c]);
    crowd.characters.push_back(std::move(ch));
  }
  return crowd;
}

}  // namespace

TEST_CASE("the documented game loop removes the collision its animation creates", "[embedding]") {
  const double fps = 30;
  const int frames = crowdlab::test::kSanitized ? 45 : 90;
  const game::GameLog log = game::run_game_loop(frames, fps);
  REQUIRE(log.corrected.size() == static_cast<size_t>(frames));
  const auto animated = crowdlab::measure_crowd(as_crowd(log, false, fps));
  const auto corrected = crowdlab::measure_crowd(as_crowd(log, true, fps));
  INFO("mean overlap per character: animated " << animated.mean_character_overlap_l << " L, corrected "
                                               << corrected.mean_character_overlap_l << " L");
  CHECK(animated.mean_character_overlap_l > 1.0);  // the animation really pushes the bodies into each other
  CHECK(corrected.mean_character_overlap_l < 0.1 * animated.mean_character_overlap_l);
}

TEST_CASE("docs/embedding.md shows the compiled example verbatim", "[embedding]") {
  const std::string doc = slurp(crowdlab::test::source_dir() / "docs/embedding.md");
  std::string code = slurp(crowdlab::test::source_dir() / "tests/embedding/game_loop_example.hpp");
  REQUIRE(!code.empty());
  INFO("docs/embedding.md must contain tests/embedding/game_loop_example.hpp exactly, in a ```cpp block");
  CHECK(doc.find("```cpp\n" + code + "```") != std::string::npos);
}

}  // namespace test_embedding
