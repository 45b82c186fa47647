#pragma once
// Deterministic seeds. Every random stream in crowdlab is derived from the spec seed and a stable
// string key (condition id, character index, participant id...), never from the order things are
// processed in, so adding a factor level or running with more threads changes no other stream.
#include <cstdint>
#include <random>
#include <span>
#include <string_view>

namespace crowdlab {

/// 64-bit FNV-1a hash of a string: stable across platforms and runs.
std::uint64_t stable_hash(std::string_view text);

/// A 64-bit hash of a block of doubles' bit patterns, eight bytes per step: FNV-1a's xor-multiply on
/// whole words, then mix64. For in-memory cache keys of meshes (a body's ~15,000 vertices are 1.5 MB of
/// data, which byte-wise FNV-1a took ~3 ms to hash twice per character per crowd load; issue 31). Stable
/// across runs; two blocks that differ in one element always differ here (each step is a bijection of the
/// running value), and 0.0 and -0.0 differ. Not equal to stable_hash of the same bytes.
std::uint64_t stable_hash_words(std::span<const double> data);

/// SplitMix64 finaliser: a well-mixed 64-bit value from any 64-bit input (Steele et al. 2014).
std::uint64_t mix64(std::uint64_t x);

/// The seed of a named sub-stream: mix64(parent ^ stable_hash(key)).
std::uint64_t derive_seed(std::uint64_t parent, std::string_view key);

/// The generator every crowdlab component uses (fully specified by the C++ standard, so sequences
/// are identical on every platform). Note: std::*_distribution are NOT specified bit-exactly across
/// standard libraries; use the helpers below for portable draws.
using Rng = std::mt19937_64;

/// Uniform double in [0, 1) from the top 53 bits.
double uniform01(Rng& rng);
/// Standard normal by Box-Muller on uniform01 (portable, unlike std::normal_distribution).
double standard_normal(Rng& rng);
/// Uniform integer in [0, n) (n > 0), by rejection (unbiased).
std::uint64_t uniform_index(Rng& rng, std::uint64_t n);

}  // namespace crowdlab
