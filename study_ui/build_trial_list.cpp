#include "study_ui/build_trial_list.hpp"

#include <algorithm>
#include <cctype>

#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"

namespace crowdlab::study {
namespace {

template <class T>
void shuffle_in_place(std::vector<T>& items, Rng& rng) {
  for (size_t i = items.size(); i > 1; --i) std::swap(items[i - 1], items[uniform_index(rng, i)]);
}

std::string level_of(const StimulusEntry& e, const std::string& factor) {
  auto it = e.factors.find(factor);
  return it == e.factors.end() ? std::string() : it->second;
}

}  // namespace

std::uint64_t participant_seed(std::uint64_t spec_seed, const std::string& participant) {
  return derive_seed(spec_seed, "participant:" + participant);
}

std::uint64_t participant_number(const std::string& participant) {
  size_t start = participant.size();
  while (start > 0 && std::isdigit(static_cast<unsigned char>(participant[start - 1]))) --start;
  if (start == participant.size() || participant.size() - start > 18) return stable_hash(participant);
  return std::stoull(participant.substr(start));
}

std::vector<int> williams_row(int n, std::uint64_t row) {
  // First row 0, 1, n-1, 2, n-2, ...; row r adds r (mod n) to every entry (Williams 1949).
  std::vector<int> out(static_cast<size_t>(n));
  for (int j = 0; j < n; ++j) {
    const int base = (j % 2 == 1) ? (j + 1) / 2 : (j == 0 ? 0 : n - j / 2);
    out[static_cast<size_t>(j)] =
        static_cast<int>((static_cast<std::uint64_t>(base) + row) % static_cast<std::uint64_t>(n));
  }
  return out;
}

std::vector<Trial> build_trial_list(const ProtocolSpec& protocol, const StimulusManifest& manifest,
                                    std::uint64_t spec_seed, const std::string& participant) {
  const std::string& block_by = protocol.block_by;
  if (!block_by.empty() && std::find(manifest.factor_names.begin(), manifest.factor_names.end(), block_by) ==
                               manifest.factor_names.end())
    throw InputError(SourceLocation{"", 0, 0, "protocol.blocks"},
                     "block factor '" + block_by + "' is not a column of the stimulus manifest");

  // Blocks in order of first appearance; practice split into global and per-block.
  std::vector<std::string> block_names;
  std::vector<std::vector<StimulusEntry>> block_trials, block_practice;
  std::vector<StimulusEntry> global_practice;
  auto block_slot = [&](const std::string& name) {
    auto it = std::find(block_names.begin(), block_names.end(), name);
    if (it != block_names.end()) return static_cast<size_t>(it - block_names.begin());
    block_names.push_back(name);
    block_trials.emplace_back();
    block_practice.emplace_back();
    return block_names.size() - 1;
  };
  for (const StimulusEntry& e : manifest.entries)
    if (!e.practice) block_trials[block_slot(block_by.empty() ? "all" : level_of(e, block_by))].push_back(e);
  if (block_names.empty()) throw InputError("the stimulus manifest lists no test (non-practice) stimuli");
  for (const StimulusEntry& e : manifest.entries) {
    if (!e.practice) continue;
    const std::string level = block_by.empty() ? std::string() : level_of(e, block_by);
    auto it = std::find(block_names.begin(), block_names.end(), level);
    if (it == block_names.end())
      global_practice.push_back(e);
    else
      block_practice[static_cast<size_t>(it - block_names.begin())].push_back(e);
  }

  const std::uint64_t seed = participant_seed(spec_seed, participant);
  std::vector<int> order(block_names.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  if (protocol.block_order == BlockOrder::random) {
    Rng rng(derive_seed(seed, "block-order"));
    shuffle_in_place(order, rng);
  } else if (protocol.block_order == BlockOrder::latin_square) {
    order = williams_row(static_cast<int>(block_names.size()), participant_number(participant));
  }

  std::vector<Trial> trials;
  auto append = [&](std::vector<StimulusEntry> entries, const std::string& block, int block_number,
                    bool practice, const std::string& stream) {
    Rng rng(derive_seed(seed, stream));
    shuffle_in_place(entries, rng);
    for (StimulusEntry& e : entries) {
      Trial t;
      t.index = static_cast<int>(trials.size()) + 1;
      t.block = block;
      t.block_number = block_number;
      t.practice = practice;
      t.stimulus = std::move(e);
      trials.push_back(std::move(t));
    }
  };
  append(global_practice, "practice", 0, true, "practice");
  for (size_t k = 0; k < order.size(); ++k) {
    const auto b = static_cast<size_t>(order[k]);
    append(block_practice[b], block_names[b], 0, true, "practice:" + block_names[b]);
    append(block_trials[b], block_names[b], static_cast<int>(k) + 1, false, "block:" + block_names[b]);
  }
  return trials;
}

}  // namespace crowdlab::study
