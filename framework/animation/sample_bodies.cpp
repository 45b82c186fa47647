#include "framework/animation/sample_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"

namespace crowdlab {

namespace {
// A standard normal truncated to [-limit, limit] by resampling.
double truncated_normal(Rng& rng, double limit) {
  for (;;) {
    const double z = standard_normal(rng);
    if (std::abs(z) <= limit) return z;
  }
}
}  // namespace

std::vector<BodyParams> sample_bodies(int n, double female_fraction, std::uint64_t seed) {
  if (n < 0) throw InputError("sample_bodies: n must be >= 0, got " + std::to_string(n));
  if (!std::isfinite(female_fraction) || female_fraction < 0.0 || female_fraction > 1.0)
    throw InputError("sample_bodies: female_fraction must be in [0, 1], got " +
                     std::to_string(female_fraction));
  const auto count = static_cast<size_t>(n);
  const auto women = static_cast<size_t>(std::lround(female_fraction * n));

  // Which indices are women: a seeded Fisher-Yates shuffle of 0..n-1, the first `women` of it.
  std::vector<size_t> order(count);
  std::iota(order.begin(), order.end(), size_t{0});
  Rng shuffle_rng(derive_seed(seed, "bodies/sex"));
  for (size_t i = count; i > 1; --i) std::swap(order[i - 1], order[uniform_index(shuffle_rng, i)]);
  std::vector<bool> is_female(count, false);
  for (size_t k = 0; k < women; ++k) is_female[order[k]] = true;

  std::vector<BodyParams> out(count);
  for (size_t i = 0; i < count; ++i) {
    Rng rng(derive_seed(seed, "bodies/" + std::to_string(i)));
    const HeightDistribution d = is_female[i] ? kWorldFemaleHeight : kWorldMaleHeight;
    out[i].sex = is_female[i] ? Sex::kFemale : Sex::kMale;
    out[i].height_m = d.mean_m + d.sd_m * truncated_normal(rng, 3.0);
    out[i].girth = std::clamp(kGirthMean + kGirthSd * truncated_normal(rng, 3.0), kGirthMin, kGirthMax);
  }
  return out;
}

}  // namespace crowdlab
