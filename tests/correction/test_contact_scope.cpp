// The free-joint contact scope's inter-body part (stage_free_joints.cpp, stage_contact_scope): a bone is
// touched when a capsule of another character comes within free_joint_margin_m of it. Since session 20
// the narrow phase tests the near capsule pairs against the margin (pair_touched) while it computes
// their distances for the contacts; this checks its masks against a direct test of every near pair.
#include <catch2/catch.hpp>

#include "tests/correction/dense_crowd_after_narrow_phase.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_contact_scope {

using namespace crowdlab;

TEST_CASE("correction: the narrow phase marks the bones within the free-joint margin of another body",
          "[correction]") {
  const test::CorrectorAtNarrowPhase in = test::dense_crowd_after_narrow_phase();
  const CorrectorState& s = in.state;
  const double margin = in.model.params.free_joint_margin_m;
  REQUIRE(in.model.params.release_free_joints);
  REQUIRE(s.body_pairs.size() > 10);
  REQUIRE(s.pair_touched.size() >= s.body_pairs.size());
  int touched_pairs = 0, untouched_near = 0;
  for (size_t k = 0; k < s.body_pairs.size(); ++k) {
    const auto [ci, cj] = s.body_pairs[k];
    std::array<BoneMask, 2> expected{0, 0};
    for (const auto& [a, b] : s.per_pair_near[k]) {
      const CapsuleContact cc = capsule_contact(s.world_capsule[static_cast<size_t>(ci * kJointCount + a)],
                                                s.world_capsule[static_cast<size_t>(cj * kJointCount + b)]);
      if (cc.depth_m > -margin) {
        expected[0] |= BoneMask{1} << a;
        expected[1] |= BoneMask{1} << b;
      } else {
        ++untouched_near;
      }
    }
    INFO("body pair " << ci << "-" << cj);
    CHECK(s.pair_touched[k] == expected);
    touched_pairs += expected[0] != 0 ? 1 : 0;
  }
  // The crowd is dense enough that both cases occur: pairs within the margin and near pairs beyond it.
  CHECK(touched_pairs > 5);
  CHECK(untouched_near > 0);
}

}  // namespace test_contact_scope
