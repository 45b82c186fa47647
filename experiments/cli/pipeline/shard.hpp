#pragma once
// `--shard K/N`: a disjoint, deterministic slice of the conditions. Condition i (in enumeration order)
// belongs to shard (i mod N) + 1, so every condition is in exactly one shard and shards are balanced
// to within one condition.
#include <string>

namespace crowdlab::cli {

struct Shard {
  int index = 1;  ///< K, 1-based
  int count = 1;  ///< N
  bool contains(std::size_t condition_index) const {
    return static_cast<int>(condition_index % static_cast<std::size_t>(count)) + 1 == index;
  }
};

/// Parses "K/N" with 1 <= K <= N; throws InputError otherwise.
Shard parse_shard(const std::string& text);

}  // namespace crowdlab::cli
