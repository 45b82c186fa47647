#pragma once
// `--shard K/N`: a disjoint, deterministic slice of the work. `crowdlab run` numbers its crowd groups
// (the conditions that show one crowd) in enumeration order; group i belongs to shard (i mod N) + 1, so
// every condition is in exactly one shard and no two shards write the same files.
#include <string>

namespace crowdlab {

struct Shard {
  int index = 1;  ///< K, 1-based
  int count = 1;  ///< N
  bool contains(std::size_t item_index) const {
    return static_cast<int>(item_index % static_cast<std::size_t>(count)) + 1 == index;
  }
};

/// Parses "K/N" with 1 <= K <= N; throws InputError otherwise.
Shard parse_shard(const std::string& text);

}  // namespace crowdlab
