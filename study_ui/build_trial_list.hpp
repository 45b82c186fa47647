#pragma once
// build_trial_list: the ordered trials one participant sees, from the stimulus manifest.
//
// Order (seed 001 §3.1.5 and §4.2.2; seed 000 §4.4.1):
//  1. Practice stimuli (manifest column practice = 1) come first and are never analysed. A practice
//     stimulus whose level of the blocking factor names a block is shown at the start of that block
//     instead (seed 001 §4.2.2 showed six practice examples "at the beginning of each block").
//     Practice trials are shuffled among themselves.
//  2. Blocks are the levels of protocol.block_by (one block "all" when empty). Block order per
//     protocol.block_order: "fixed" (levels in order of first appearance in the manifest), "random"
//     (a permutation drawn from the participant seed), or "latin_square" (row p mod n of a
//     Williams-design Latin square, Williams 1949, where p is the participant number: the trailing
//     digits of the id, e.g. P07 -> 7, or a stable hash of the id when it has none). For an odd
//     number of blocks a single Williams square balances first-order carry-over only over 2n
//     participants; the row rule is the same.
//  3. Trials are shuffled within each block (Fisher-Yates on Rng).
// Every random stream derives from participant_seed(spec_seed, participant) with derive_seed, so the
// same participant always sees the same order and different participants different ones.
#include <cstdint>
#include <string>
#include <vector>

#include "framework/core/stimulus_manifest.hpp"
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab::study {

struct Trial {
  int index = 0;         ///< 1-based position in the participant's sequence
  std::string block;     ///< block name (level of block_by, "all", or "practice")
  int block_number = 0;  ///< 1-based position of the block in this participant's order (0 = practice)
  StimulusEntry stimulus;
  bool practice = false;
};

/// The seed of everything one participant sees: derive_seed(spec_seed, "participant:" + id).
std::uint64_t participant_seed(std::uint64_t spec_seed, const std::string& participant);

/// Participant number used by the Latin square: trailing digits of the id, else a stable hash.
std::uint64_t participant_number(const std::string& participant);

/// Row `row` of a Williams-design Latin square of order n: a permutation of 0..n-1.
std::vector<int> williams_row(int n, std::uint64_t row);

/// Throws InputError when block_by names no manifest column or block_order is unknown, or when the
/// manifest has no test stimuli.
std::vector<Trial> build_trial_list(const ProtocolSpec& protocol, const StimulusManifest& manifest,
                                    std::uint64_t spec_seed, const std::string& participant);

}  // namespace crowdlab::study
