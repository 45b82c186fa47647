#pragma once
// Body sampling for a crowd (seed 000 §4.1: "beta parameters were selected randomly following a
// Gaussian distribution that matched men and women height distributions around the world ... half of
// them belonging to each gender").
//
// Heights: Gaussian per sex (core/population.hpp: men 1.71 +- 0.07 m, women 1.59 +- 0.07 m, NCD-RisC
// 2016), truncated at +-3 SD by resampling; sexes from sample_sexes().
// Girth (radius multiplier of the procedural body) ~ N(1.0, 0.08), truncated to [0.8, 1.3]:
// a +-8 % spread of limb circumference matches the coefficient of variation of ANSUR II (2012) thigh
// and arm circumferences (~7-9 %).
#include <cstdint>
#include <vector>

#include "framework/core/body_shape.hpp"
#include "framework/core/population.hpp"

namespace crowdlab {

inline constexpr double kGirthMean = 1.0, kGirthSd = 0.08, kGirthMin = 0.8, kGirthMax = 1.3;

/// n bodies; exactly round(female_fraction * n) are women, placed at seeded random indices.
/// Deterministic in (n, female_fraction, seed); body i depends only on (seed, i, its sex).
/// Throws InputError for n < 0 or female_fraction outside [0, 1].
std::vector<BodyParams> sample_bodies(int n, double female_fraction, std::uint64_t seed);

}  // namespace crowdlab
