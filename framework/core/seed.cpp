#include "framework/core/seed.hpp"

#include <bit>
#include <cmath>
#include <numbers>

namespace crowdlab {

std::uint64_t stable_hash(std::string_view text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

std::uint64_t stable_hash_words(std::span<const double> data) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const double d : data) {
    h ^= std::bit_cast<std::uint64_t>(d);
    h *= 0x100000001b3ULL;
    h ^= h >> 29;  // the multiply carries low bits up only: fold the high bits back down
  }
  return mix64(h ^ data.size());
}

std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::uint64_t derive_seed(std::uint64_t parent, std::string_view key) {
  return mix64(parent ^ stable_hash(key));
}

double uniform01(Rng& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

double standard_normal(Rng& rng) {
  double u1 = uniform01(rng);
  while (u1 <= 0.0) u1 = uniform01(rng);
  const double u2 = uniform01(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

std::uint64_t uniform_index(Rng& rng, std::uint64_t n) {
  const std::uint64_t limit = UINT64_MAX - UINT64_MAX % n;
  std::uint64_t x = rng();
  while (x >= limit) x = rng();
  return x % n;
}

}  // namespace crowdlab
