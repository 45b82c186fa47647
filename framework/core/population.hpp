#pragma once
// A crowd's population by sex: the adult height distributions bodies are drawn from, and which
// characters are women (seed 000 §4.1: "beta parameters were selected randomly following a Gaussian
// distribution that matched men and women height distributions around the world ... half of them
// belonging to each gender"). Shared by the procedural bodies (animation/sample_bodies.hpp) and the
// MPFB2 bodies (body/sample_mpfb2_bodies.hpp), so both body models sample the same population.
//
// Heights (stature, metres), Gaussian per sex:
//   men   mean 1.71 m, SD 0.07 m
//   women mean 1.59 m, SD 0.07 m   (kept equal to the men's SD: within-country SDs are ~0.065-0.07 m,
//                                   e.g. Jelenkovic et al., eLife 5:e17364, 2016, and the spread between
//                                   countries widens the world's distribution slightly)
// Source: NCD Risk Factor Collaboration (NCD-RisC), "A century of trends in adult human height",
// eLife 5:e13410 (2016): global mean adult height for the 1996 birth cohort, men ~171 cm, women ~159 cm.
#include <cstdint>
#include <vector>

#include "framework/core/body_shape.hpp"

namespace crowdlab {

struct HeightDistribution {
  double mean_m = 1.71;
  double sd_m = 0.07;
};
inline constexpr HeightDistribution kWorldMaleHeight{1.71, 0.07};
inline constexpr HeightDistribution kWorldFemaleHeight{1.59, 0.07};

/// The sex of each of n characters: exactly round(female_fraction * n) women, at the first indices of
/// a seeded Fisher-Yates shuffle of 0..n-1 (stream derive_seed(seed, "bodies/sex")).
/// Throws InputError for n < 0 or female_fraction outside [0, 1].
std::vector<Sex> sample_sexes(int n, double female_fraction, std::uint64_t seed);

}  // namespace crowdlab
