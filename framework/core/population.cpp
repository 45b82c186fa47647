#include "framework/core/population.hpp"

#include <cmath>
#include <numeric>
#include <string>

#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"

namespace crowdlab {

std::vector<Sex> sample_sexes(int n, double female_fraction, std::uint64_t seed) {
  if (n < 0) throw InputError("sample_sexes: n must be >= 0, got " + std::to_string(n));
  if (!std::isfinite(female_fraction) || female_fraction < 0.0 || female_fraction > 1.0)
    throw InputError("female_fraction must be in [0, 1], got " + std::to_string(female_fraction));
  const auto count = static_cast<size_t>(n);
  const auto women = static_cast<size_t>(std::lround(female_fraction * n));
  std::vector<size_t> order(count);
  std::iota(order.begin(), order.end(), size_t{0});
  Rng rng(derive_seed(seed, "bodies/sex"));
  for (size_t i = count; i > 1; --i) std::swap(order[i - 1], order[uniform_index(rng, i)]);
  std::vector<Sex> sex(count, Sex::kMale);
  for (size_t k = 0; k < women; ++k) sex[order[k]] = Sex::kFemale;
  return sex;
}

}  // namespace crowdlab
