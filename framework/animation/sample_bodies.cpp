#include "framework/animation/sample_bodies.hpp"

#include <algorithm>
#include <cmath>
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
  const std::vector<Sex> sex = sample_sexes(n, female_fraction, seed);
  std::vector<BodyParams> out(count);
  for (size_t i = 0; i < count; ++i) {
    Rng rng(derive_seed(seed, "bodies/" + std::to_string(i)));
    const HeightDistribution d = sex[i] == Sex::kFemale ? kWorldFemaleHeight : kWorldMaleHeight;
    out[i].sex = sex[i];
    out[i].height_m = d.mean_m + d.sd_m * truncated_normal(rng, 3.0);
    out[i].girth = std::clamp(kGirthMean + kGirthSd * truncated_normal(rng, 3.0), kGirthMin, kGirthMax);
  }
  return out;
}

}  // namespace crowdlab
