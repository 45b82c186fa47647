#pragma once
// Sampling a crowd of MPFB2 bodies whose heights follow Gaussian distributions by sex (seed 000
// §4.1: "beta parameters were selected randomly following a Gaussian distribution that matched men
// and women height distributions around the world ... half of them belonging to each gender").
//
// Distributions: core/population.hpp (NCD-RisC 2016 world means, SD 7 cm); sexes from sample_sexes()
// (exactly round(female_fraction * n) women at seeded indices, as the procedural bodies).
//
// Per body i (its own stream derive_seed(seed, "mpfb2-body/<i>")): gender = 0 (woman) or 1 (man); age uniform
// in [0.5, 0.75] (25 to ~58 years); muscle and weight 0.5 + 0.15 N(0,1) clamped to [0.1, 0.9]; a target
// height from the sex's Gaussian, clamped to [1.40, 2.05] m. The macro `height` is then solved by bisection
// so that the shaped mesh's measured height (lowest to highest body vertex) equals the target within 1 mm; if
// the target lies outside what the height targets can reach for that body, the nearest end is used
// (Mpfb2Sample::target_reached says which).
#include <cstdint>
#include <vector>

#include "framework/body/mpfb2_body.hpp"
#include "framework/core/population.hpp"

namespace crowdlab {

struct Mpfb2Sample {
  Mpfb2Body body;
  double target_height_m = 0.0;
  bool target_reached = true;
};

/// The macro `height` in [0, 1] whose shaped body measures target_height_m (others from `params`);
/// `reached` is false when the target is outside the reachable range (the nearest end is returned).
double solve_height_param(const Mpfb2Model& model, Mpfb2ShapeParams params, double target_height_m,
                          bool& reached);

/// Measured height (m) of the body group for the given params (lowest to highest vertex).
double measure_mpfb2_height(const Mpfb2Model& model, const Mpfb2ShapeParams& params);

/// Bodies are built in parallel (TBB) into per-index slots: identical for any thread count.
std::vector<Mpfb2Sample> sample_mpfb2_bodies(const Mpfb2Model& model, int count, std::uint64_t seed,
                                             double female_fraction = 0.5,
                                             HeightDistribution female = kWorldFemaleHeight,
                                             HeightDistribution male = kWorldMaleHeight);

}  // namespace crowdlab
