#pragma once
// Sampling a crowd of MPFB2 bodies whose heights follow Gaussian distributions by sex (seed 000
// §4.1: "beta parameters were selected randomly following a Gaussian distribution that matched men
// and women height distributions around the world ... half of them belonging to each gender").
//
// Default distributions: world adult means from NCD Risk Factor Collaboration, "A century of trends
// in adult human height", eLife 5:e13410 (2016): 1996-born cohort, men ~171 cm, women ~159 cm
// (global averages of the country means). The within-population SD of adult height is ~7 cm for men
// and ~6.5 cm for women (e.g. Jelenkovic et al., eLife 5:e17364, 2016, twin cohorts, ~6-7 cm);
// we use 7.0 and 6.5 cm.
//
// Per body i (its own stream derive_seed(seed, "mpfb2-body/<i>")): sex alternates female, male,
// female ... (half and half); gender = 0 or 1; age uniform in [0.5, 0.75] (25 to ~58 years);
// muscle and weight 0.5 + 0.15 N(0,1) clamped to [0.1, 0.9]; a target height from the sex's
// Gaussian, clamped to [1.40, 2.05] m. The macro `height` is then solved by bisection so that the
// shaped mesh's measured height (lowest to highest body vertex) equals the target within 1 mm; if
// the target lies outside what the height targets can reach for that body, the nearest end is used
// (Mpfb2Sample::target_reached says which).
#include <cstdint>
#include <vector>

#include "framework/body/mpfb2_body.hpp"

namespace crowdlab {

struct HeightDistribution {
  double mean_m = 1.71;
  double sd_m = 0.07;
};
inline constexpr HeightDistribution kWorldMaleHeight{1.71, 0.070};
inline constexpr HeightDistribution kWorldFemaleHeight{1.59, 0.065};

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

std::vector<Mpfb2Sample> sample_mpfb2_bodies(const Mpfb2Model& model, int count, std::uint64_t seed,
                                             HeightDistribution female = kWorldFemaleHeight,
                                             HeightDistribution male = kWorldMaleHeight);

}  // namespace crowdlab
