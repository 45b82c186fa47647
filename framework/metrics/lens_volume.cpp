#include "framework/metrics/lens_volume.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "framework/core/error.hpp"

namespace crowdlab {
namespace {
void check_args(double r1, double r2, double d, const char* what) {
  if (!std::isfinite(r1) || !std::isfinite(r2) || !std::isfinite(d) || r1 < 0.0 || r2 < 0.0 || d < 0.0)
    throw InputError(std::string(what) + ": radii and distance must be finite and >= 0");
}
}  // namespace

double lens_volume(double r1, double r2, double d) {
  check_args(r1, r2, d, "lens_volume");
  if (d >= r1 + r2) return 0.0;
  const double rmin = std::min(r1, r2);
  if (d <= std::abs(r1 - r2)) return 4.0 / 3.0 * std::numbers::pi * rmin * rmin * rmin;
  const double s = r1 + r2 - d;
  const double dr = r1 - r2;
  return std::numbers::pi * s * s * (d * d + 2.0 * d * (r1 + r2) - 3.0 * dr * dr) / (12.0 * d);
}

double circle_lens_area(double r1, double r2, double d) {
  check_args(r1, r2, d, "circle_lens_area");
  if (d >= r1 + r2) return 0.0;
  const double rmin = std::min(r1, r2);
  if (d <= std::abs(r1 - r2)) return std::numbers::pi * rmin * rmin;
  const double d1 = (d * d + r1 * r1 - r2 * r2) / (2.0 * d);
  const double d2 = d - d1;
  auto segment = [](double r, double x) {
    const double c = std::clamp(x / r, -1.0, 1.0);
    return r * r * std::acos(c) - x * std::sqrt(std::max(0.0, r * r - x * x));
  };
  return segment(r1, d1) + segment(r2, d2);
}

}  // namespace crowdlab
