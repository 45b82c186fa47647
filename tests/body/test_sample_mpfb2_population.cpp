// The population sample_mpfb2_shapes() draws (seed 000 §4.1): half of each sex, per-sex Gaussian heights
// (core/population.hpp) measured on the shaped meshes, and varied shape, ethnicity and skin tone.
#include <catch2/catch.hpp>
#include <cmath>
#include <set>

#include "framework/body/sample_mpfb2_bodies.hpp"
#include "framework/core/appearance.hpp"
#include "framework/core/mpfb2_asset_dir.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_sample_mpfb2_population {

using namespace crowdlab;

namespace {

const Mpfb2Model& shipped_model() {
  static const std::shared_ptr<const Mpfb2Model> model = Mpfb2Model::load(shipped_mpfb2_dir());
  return *model;
}

struct Moments {
  int n = 0;
  double sum = 0.0, sum2 = 0.0;
  void add(double x) { ++n, sum += x, sum2 += x * x; }
  double mean() const { return sum / n; }
  double sd() const { return std::sqrt(std::max(0.0, sum2 / n - mean() * mean())); }
};

int dominant_group(const Mpfb2ShapeParams& p) {
  if (p.african >= p.asian && p.african >= p.caucasian) return 0;
  return p.asian >= p.caucasian ? 1 : 2;
}

}  // namespace

TEST_CASE("200 sampled MPFB2 shapes: half of each sex, per-sex height distributions, varied looks") {
  const int n = 200;  // also under the sanitizers: with 40 the sex difference check has too little power
  const std::vector<Mpfb2ShapeDraw> draws = sample_mpfb2_shapes(shipped_model(), n, 2024);
  std::array<Moments, 2> height;  // women, men: the stature measured on the shaped mesh
  Moments muscle, weight, proportions;
  std::set<int> tones;
  std::array<int, 3> groups{};
  for (const Mpfb2ShapeDraw& d : draws) {
    const Mpfb2ShapeParams& p = d.params;
    REQUIRE((p.gender == 0.0 || p.gender == 1.0));
    REQUIRE(d.target_reached);
    const double measured = measure_mpfb2_height(shipped_model(), p);
    CHECK(measured == Approx(d.target_height_m).margin(0.001));
    height[p.gender == 0.0 ? 0 : 1].add(measured);
    muscle.add(p.muscle), weight.add(p.weight), proportions.add(p.proportions);
    CHECK(p.age >= 0.5);
    CHECK(p.age <= 0.75);
    CHECK(p.proportions >= 0.5);
    const int group = dominant_group(p);
    ++groups[static_cast<size_t>(group)];
    CHECK(p.african + p.asian + p.caucasian == Approx(1.0));
    const auto [first, last] = skin_tone_range(p);
    CHECK(d.skin_tone >= first);
    CHECK(d.skin_tone <= last);
    CHECK(last < kSkinToneCount);
    tones.insert(d.skin_tone);
  }
  // Exactly half women, half men.
  CHECK(height[0].n == n / 2);
  CHECK(height[1].n == n / 2);
  // Heights: means within 4 standard errors, SDs within 30 % (and the clamp to [1.40, 2.05] m is rare).
  for (int s = 0; s < 2; ++s) {
    const HeightDistribution d = s == 0 ? kWorldFemaleHeight : kWorldMaleHeight;
    INFO((s == 0 ? "women" : "men") << ": mean " << height[static_cast<size_t>(s)].mean() << " sd "
                                    << height[static_cast<size_t>(s)].sd());
    CHECK(std::abs(height[static_cast<size_t>(s)].mean() - d.mean_m) <
          4 * d.sd_m / std::sqrt(height[static_cast<size_t>(s)].n));
    CHECK(height[static_cast<size_t>(s)].sd() == Approx(d.sd_m).epsilon(0.3));
  }
  CHECK(height[1].mean() > height[0].mean() + 0.08);
  // Shape varies (muscle and weight SD 0.15 before clamping; proportions uniform on [0.5, 1]).
  CHECK(muscle.sd() > 0.1);
  CHECK(weight.sd() > 0.1);
  CHECK(proportions.sd() > 0.1);
  // Every ethnic group and (nearly) every skin tone occurs.
  for (int g : groups) CHECK(g > n / 6);
  CHECK(tones.size() >= (test::kSanitized ? 5u : 6u));
  // Deterministic: the same seed gives the same draws (built in parallel again).
  const std::vector<Mpfb2ShapeDraw> again = sample_mpfb2_shapes(shipped_model(), n, 2024);
  for (size_t i = 0; i < draws.size(); ++i) {
    CHECK(again[i].params.height == draws[i].params.height);
    CHECK(again[i].skin_tone == draws[i].skin_tone);
  }
}

TEST_CASE("sampled MPFB2 bodies record their sex and their measured stature in the BodyShape") {
  const int n = test::kSanitized ? 2 : 4;
  const std::vector<Mpfb2Sample> bodies = sample_mpfb2_bodies(shipped_model(), n, 77);
  const std::vector<Mpfb2ShapeDraw> draws = sample_mpfb2_shapes(shipped_model(), n, 77);
  for (int i = 0; i < n; ++i) {
    const Mpfb2Sample& s = bodies[static_cast<size_t>(i)];
    CHECK(s.params.height == draws[static_cast<size_t>(i)].params.height);
    CHECK(s.skin_tone == draws[static_cast<size_t>(i)].skin_tone);
    CHECK(s.body.shape.params.sex == (s.params.gender == 0.0 ? Sex::kFemale : Sex::kMale));
    CHECK(s.body.shape.params.height_m == s.body.height_m);
    CHECK(s.body.height_m == Approx(measure_mpfb2_height(shipped_model(), s.params)).margin(1e-12));
    CHECK(s.body.height_m == Approx(s.target_height_m).margin(0.001));
  }
}

}  // namespace test_sample_mpfb2_population
