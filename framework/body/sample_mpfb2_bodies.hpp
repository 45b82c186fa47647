#pragma once
// Sampling a crowd of MPFB2 bodies whose heights follow Gaussian distributions by sex (seed 000
// §4.1: "beta parameters were selected randomly following a Gaussian distribution that matched men
// and women height distributions around the world ... half of them belonging to each gender").
//
// Distributions: core/population.hpp (per-sex Gaussian heights, with their source: NCD-RisC 2016,
// eLife 5:e13410, world means men 1.71 m, women 1.59 m, SD 0.07 m); sexes from sample_sexes() (exactly
// round(female_fraction * n) women at seeded indices, as the procedural bodies).
//
// Per body i (its own stream derive_seed(seed, "mpfb2-body/<i>"), draws in this order):
//   gender       0 (woman) or 1 (man)
//   age          uniform in [0.5, 0.75] (25 to ~58 years in MakeHuman's mapping)
//   muscle       0.5 + 0.15 N(0,1) clamped to [0.1, 0.9]
//   weight       0.5 + 0.15 N(0,1) clamped to [0.1, 0.9]
//   height       a target stature from the sex's Gaussian, clamped to [1.40, 2.05] m; the macro `height`
//                is then solved by bisection so that the shaped mesh's measured height (lowest to
//                highest body vertex) equals the target within 1 mm; if the target lies outside what
//                the height targets can reach for that body, the nearest end is used (target_reached)
//   proportions  uniform in [0.5, 1] (neutral .. MakeHuman's "ideal"; the "uncommon" half is left out so
//                that the shipped assets need half the proportion targets)
//   ethnicity    a dominant group (African, Asian, Caucasian: MakeHuman's three ethnic targets) drawn
//                uniformly, with a share uniform in [0.7, 1]; the other two split the rest equally
//   skin_tone    an index into the renderer's six-step skin scale (0 lightest .. 5 darkest,
//                core/appearance.hpp) matching the dominant group: Caucasian 0-2, Asian 1-3,
//                African 3-5, uniform within the range, so that face and body shape agree with the skin
// The assets shipped in framework/body/assets/mpfb2 hold exactly the macro targets these ranges reach
// (scripts/make_mpfb2_subset.py; tests/body/test_mpfb2_assets.cpp checks it).
#include <cstdint>
#include <utility>
#include <vector>

#include "framework/body/mpfb2_body.hpp"
#include "framework/core/population.hpp"

namespace crowdlab {

/// One sampled shape, before the body is built (cheap: a few shaped meshes for the height solve).
struct Mpfb2ShapeDraw {
  Mpfb2ShapeParams params;  ///< params.height solved so that the shaped body measures target_height_m
  double target_height_m = 0.0;
  bool target_reached = true;
  int skin_tone = 0;  ///< 0 lightest .. kSkinToneCount - 1 darkest (see above)
};

struct Mpfb2Sample : Mpfb2ShapeDraw {
  /// The body of `params`; body.shape.params holds the sex and the MEASURED stature (body.height_m,
  /// equal to target_height_m within 1 mm when target_reached), so crowd files record the real values.
  Mpfb2Body body;
};

/// The skin-tone range [first, last] that matches a body's dominant ethnic group (see above).
std::pair<int, int> skin_tone_range(const Mpfb2ShapeParams& params);

/// The macro `height` in [0, 1] whose shaped body measures target_height_m (others from `params`);
/// `reached` is false when the target is outside the reachable range (the nearest end is returned).
double solve_height_param(const Mpfb2Model& model, Mpfb2ShapeParams params, double target_height_m,
                          bool& reached);

/// Measured height (m) of the body group for the given params (lowest to highest vertex).
double measure_mpfb2_height(const Mpfb2Model& model, const Mpfb2ShapeParams& params);

/// The shapes of `count` bodies as described above, in parallel (TBB) into per-index slots: identical
/// for any thread count. Throws InputError for count < 0 or implausible height distributions.
std::vector<Mpfb2ShapeDraw> sample_mpfb2_shapes(const Mpfb2Model& model, int count, std::uint64_t seed,
                                                double female_fraction = 0.5,
                                                HeightDistribution female = kWorldFemaleHeight,
                                                HeightDistribution male = kWorldMaleHeight);

/// sample_mpfb2_shapes() and each shape's body (make_mpfb2_body), built in parallel. With a wardrobe,
/// body i is dressed in sample_mpfb2_outfit(wardrobe, its sex, derive_seed(seed, "mpfb2-outfit/<i>")): a
/// stream of its own, so the shapes are the same dressed or not.
std::vector<Mpfb2Sample> sample_mpfb2_bodies(const Mpfb2Model& model, int count, std::uint64_t seed,
                                             double female_fraction = 0.5,
                                             HeightDistribution female = kWorldFemaleHeight,
                                             HeightDistribution male = kWorldMaleHeight,
                                             const Mpfb2Wardrobe* wardrobe = nullptr);

}  // namespace crowdlab
