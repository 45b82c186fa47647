#include "framework/body/sample_mpfb2_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <tbb/parallel_for.h>

#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"

namespace crowdlab {
namespace {

/// Body-group y values (decimetres) of a shaped mesh; the height is their range.
std::vector<double> body_y_dm(const Mpfb2Model& model, const Mpfb2ShapeParams& p) {
  const std::vector<Vec3> v = shaped_vertices_dm(model, p);
  std::vector<double> y;
  y.reserve(model.body_vertices().size());
  for (int i : model.body_vertices()) y.push_back(v[static_cast<size_t>(i)].y());
  return y;
}

double range_m(const std::vector<double>& y_dm) {
  const auto [lo, hi] = std::minmax_element(y_dm.begin(), y_dm.end());
  return 0.1 * (*hi - *lo);
}

/// A dominant ethnic group drawn uniformly, with a share in [0.7, 1]; the others split the rest.
void sample_ethnicity(Rng& rng, Mpfb2ShapeParams& p) {
  const std::uint64_t dominant = uniform_index(rng, 3);
  const double share = 0.7 + 0.3 * uniform01(rng);
  const double other = 0.5 * (1.0 - share);
  p.african = dominant == 0 ? share : other;
  p.asian = dominant == 1 ? share : other;
  p.caucasian = dominant == 2 ? share : other;
}

}  // namespace

std::pair<int, int> skin_tone_range(const Mpfb2ShapeParams& params) {
  if (params.african >= params.asian && params.african >= params.caucasian) return {3, 5};
  if (params.asian >= params.caucasian) return {1, 3};
  return {0, 2};
}

double measure_mpfb2_height(const Mpfb2Model& model, const Mpfb2ShapeParams& params) {
  return range_m(body_y_dm(model, params));
}

double solve_height_param(const Mpfb2Model& model, Mpfb2ShapeParams params, double target_height_m,
                          bool& reached) {
  if (!std::isfinite(target_height_m) || target_height_m <= 0.0)
    throw InputError("solve_height_param: target height must be a positive number of metres");
  // The shaped mesh is piecewise linear in the height macro (minheight on [0, 0.5], maxheight on
  // [0.5, 1]), so three shapes give every intermediate one exactly: y(h) = y(0.5) + s (y(end) - y(0.5)).
  params.height = 0.0;
  const std::vector<double> y_min = body_y_dm(model, params);
  params.height = 0.5;
  const std::vector<double> y_mid = body_y_dm(model, params);
  params.height = 1.0;
  const std::vector<double> y_max = body_y_dm(model, params);
  std::vector<double> y(y_mid.size());
  auto height_at = [&](double h) {
    const std::vector<double>& end = h < 0.5 ? y_min : y_max;
    const double s = std::abs(2.0 * h - 1.0);
    for (size_t i = 0; i < y.size(); ++i) y[i] = y_mid[i] + s * (end[i] - y_mid[i]);
    return range_m(y);
  };
  double lo = 0.0, hi = 1.0;
  const double h_lo = height_at(lo), h_hi = height_at(hi);
  reached = target_height_m >= h_lo && target_height_m <= h_hi;
  if (target_height_m <= h_lo) return lo;
  if (target_height_m >= h_hi) return hi;
  for (int iter = 0; iter < 40 && hi - lo > 1e-7; ++iter) {
    const double mid = 0.5 * (lo + hi);
    (height_at(mid) < target_height_m ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<Mpfb2ShapeDraw> sample_mpfb2_shapes(const Mpfb2Model& model, int count, std::uint64_t seed,
                                                double female_fraction, HeightDistribution female,
                                                HeightDistribution male) {
  if (count < 0) throw InputError("sample_mpfb2_bodies: count must be >= 0");
  for (const HeightDistribution& d : {female, male})
    if (!(d.mean_m > 1.0 && d.mean_m < 2.5 && d.sd_m >= 0.0 && d.sd_m < 0.3))
      throw InputError(
          "sample_mpfb2_bodies: height distribution needs mean in (1, 2.5) m and sd in [0, 0.3) m");
  const std::vector<Sex> sex = sample_sexes(count, female_fraction, seed);
  std::vector<Mpfb2ShapeDraw> out(static_cast<size_t>(count));
  tbb::parallel_for(0, count, [&](int i) {
    Rng rng(derive_seed(seed, "mpfb2-body/" + std::to_string(i)));
    const bool is_female = sex[static_cast<size_t>(i)] == Sex::kFemale;
    const HeightDistribution& d = is_female ? female : male;
    Mpfb2ShapeDraw& s = out[static_cast<size_t>(i)];
    Mpfb2ShapeParams& p = s.params;
    p.gender = is_female ? 0.0 : 1.0;
    p.age = 0.5 + 0.25 * uniform01(rng);
    p.muscle = std::clamp(0.5 + 0.15 * standard_normal(rng), 0.1, 0.9);
    p.weight = std::clamp(0.5 + 0.15 * standard_normal(rng), 0.1, 0.9);
    s.target_height_m = std::clamp(d.mean_m + d.sd_m * standard_normal(rng), 1.40, 2.05);
    p.proportions = 0.5 + 0.5 * uniform01(rng);
    sample_ethnicity(rng, p);
    const auto [first_tone, last_tone] = skin_tone_range(p);
    s.skin_tone = first_tone + static_cast<int>(uniform_index(
                                   rng, static_cast<std::uint64_t>(last_tone - first_tone + 1)));
    p.height = solve_height_param(model, p, s.target_height_m, s.target_reached);
  });
  return out;
}

std::vector<Mpfb2Sample> sample_mpfb2_bodies(const Mpfb2Model& model, int count, std::uint64_t seed,
                                             double female_fraction, HeightDistribution female,
                                             HeightDistribution male, const Mpfb2Wardrobe* wardrobe) {
  const std::vector<Mpfb2ShapeDraw> shapes =
      sample_mpfb2_shapes(model, count, seed, female_fraction, female, male);
  std::vector<Mpfb2Sample> out(shapes.size());
  tbb::parallel_for(size_t{0}, shapes.size(), [&](size_t i) {
    static_cast<Mpfb2ShapeDraw&>(out[i]) = shapes[i];
    if (wardrobe) {
      const Sex sex = shapes[i].params.gender >= 0.5 ? Sex::kMale : Sex::kFemale;
      const Mpfb2Outfit outfit =
          sample_mpfb2_outfit(*wardrobe, sex, derive_seed(seed, "mpfb2-outfit/" + std::to_string(i)));
      out[i].body = make_mpfb2_body(model, shapes[i].params, &outfit);
    } else {
      out[i].body = make_mpfb2_body(model, shapes[i].params);
    }
  });
  return out;
}

}  // namespace crowdlab
