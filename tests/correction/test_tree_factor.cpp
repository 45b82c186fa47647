// The tree factorisation's reuse (tree_factor.hpp): refactor_character, which keeps stage_predict's
// blocks for the bones whose subtree has no contact block, must give exactly factor_character's
// preconditioner, bit for bit (the corrector's outputs are pinned, tests/determinism).
#include <bit>
#include <catch2/catch.hpp>
#include <cstring>
#include <utility>

#include "framework/correction/corrector_step.hpp"
#include "framework/correction/tree_factor.hpp"
#include "tests/correction/dense_crowd_after_narrow_phase.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_tree_factor {

using namespace crowdlab;

namespace {

/// A dense swaying crowd's corrector state stepped to the point where stage_solve factorises: the tree
/// factorised by stage_predict, contact blocks added by stage_assemble_contacts.
struct SolveInput {
  CorrectorModel model;
  CorrectorState state;
};

SolveInput state_before_solve() {
  test::CorrectorAtNarrowPhase at = test::dense_crowd_after_narrow_phase();
  SolveInput in{std::move(at.model), std::move(at.state)};
  stage_contact_scope(in.model, in.state);
  stage_assemble_contacts(in.model, in.state);
  return in;
}

bool same_bits(const Mat6& a, const Mat6& b) {
  return std::memcmp(a.data(), b.data(), sizeof(Mat6)) == 0;
}

/// Bones of character c whose preconditioner blocks differ bitwise between two states.
int differing_blocks(const CorrectorState& a, const CorrectorState& b, int c) {
  int n = 0;
  for (int j = 0; j < kJointCount; ++j) {
    const auto g = static_cast<size_t>(c * kJointCount + j);
    n += same_bits(a.precond[g], b.precond[g]) ? 0 : 1;
  }
  return n;
}

}  // namespace

TEST_CASE(
    "correction: refactorising only the bones above contact blocks is bit-identical to a full "
    "factorisation",
    "[correction]") {
  const SolveInput in = state_before_solve();
  int characters_with_contacts = 0, partial_masks = 0;
  for (int c = 0; c < in.model.characters(); ++c) {
    if (!in.state.has_contacts[static_cast<size_t>(c)]) continue;
    ++characters_with_contacts;
    const BoneMask blocks = in.state.contact_blocks[static_cast<size_t>(c)];
    partial_masks += blocks != kAllBones ? 1 : 0;
    CorrectorState full = in.state, reused = in.state;
    REQUIRE(factor_character(full, c));
    REQUIRE(refactor_character(reused, c, blocks));
    INFO("character " << c << ", contact blocks " << blocks);
    CHECK(differing_blocks(full, reused, c) == 0);
  }
  CHECK(characters_with_contacts >= 6);  // the crowd is dense enough for the check to mean something
  CHECK(partial_masks >= 1);             // and some bones are reused
}

TEST_CASE("correction: refactorising without a bone's contact block changes the preconditioner",
          "[correction]") {
  // The check above can fail: reusing the contact-free blocks of a bone that has a contact block (here
  // the highest-numbered such bone, which has no descendant with one) gives a different factorisation.
  const SolveInput in = state_before_solve();
  int checked = 0;
  for (int c = 0; c < in.model.characters(); ++c) {
    const BoneMask blocks = in.state.contact_blocks[static_cast<size_t>(c)];
    if (!in.state.has_contacts[static_cast<size_t>(c)] || blocks == 0) continue;
    const BoneMask highest = std::bit_floor(blocks);
    CorrectorState full = in.state, wrong = in.state;
    factor_character(full, c);
    refactor_character(wrong, c, blocks & ~highest);
    CHECK(differing_blocks(full, wrong, c) > 0);
    ++checked;
  }
  CHECK(checked >= 1);
}

}  // namespace test_tree_factor
