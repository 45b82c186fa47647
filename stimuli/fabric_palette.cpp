#include "stimuli/fabric_palette.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "framework/core/seed.hpp"

namespace crowdlab::stimuli {
namespace {

/// HSV (hue in degrees, saturation and value in [0, 1]) to sRGB.
Rgb hsv(double h, double s, double v) {
  h = std::fmod(std::fmod(h, 360.0) + 360.0, 360.0) / 60.0;
  const double c = v * s, x = c * (1.0 - std::abs(std::fmod(h, 2.0) - 1.0)), m = v - c;
  const int sector = static_cast<int>(h) % 6;
  const std::array<std::array<double, 3>, 6> rgb = {
      {{c, x, 0}, {x, c, 0}, {0, c, x}, {0, x, c}, {x, 0, c}, {c, 0, x}}};
  const auto& p = rgb[static_cast<size_t>(sector)];
  return {static_cast<float>(p[0] + m), static_cast<float>(p[1] + m), static_cast<float>(p[2] + m)};
}

double between(Rng& rng, double lo, double hi) {
  return lo + (hi - lo) * uniform01(rng);
}

/// One of `weights.size()` families, by weight.
template <size_t N>
size_t family(Rng& rng, const std::array<double, N>& weights) {
  double total = 0.0;
  for (double w : weights) total += w;
  double u = uniform01(rng) * total;
  for (size_t k = 0; k < N; ++k) {
    if (u < weights[k]) return k;
    u -= weights[k];
  }
  return N - 1;
}

/// Keeps a colour out of overlap mode's red: a red hue is allowed only muted.
double safe_saturation(double hue, double s) {
  const double from_red = std::min(std::fmod(hue + 360.0, 360.0), 360.0 - std::fmod(hue + 360.0, 360.0));
  return from_red < 20.0 ? std::min(s, 0.55) : s;
}

Rgb neutral(Rng& rng) {
  switch (family(rng, std::array<double, 5>{3, 3, 2, 2, 1})) {
    case 0:  // white, off-white
      return hsv(between(rng, 30, 60), between(rng, 0.0, 0.08), between(rng, 0.86, 0.95));
    case 1:  // grey
      return hsv(between(rng, 180, 240), between(rng, 0.0, 0.06), between(rng, 0.35, 0.7));
    case 2:  // black
      return hsv(between(rng, 200, 240), between(rng, 0.0, 0.1), between(rng, 0.1, 0.18));
    case 3:  // navy
      return hsv(between(rng, 215, 232), between(rng, 0.45, 0.7), between(rng, 0.22, 0.38));
    default:  // beige, camel
      return hsv(between(rng, 30, 42), between(rng, 0.2, 0.4), between(rng, 0.6, 0.82));
  }
}

Rgb colour_of_any_hue(Rng& rng, double s_lo, double s_hi, double v_lo, double v_hi) {
  const double h = between(rng, 0, 360);
  return hsv(h, safe_saturation(h, between(rng, s_lo, s_hi)), between(rng, v_lo, v_hi));
}

Rgb top(Rng& rng) {
  switch (family(rng, std::array<double, 3>{40, 45, 15})) {
    case 0:
      return neutral(rng);
    case 1:
      return colour_of_any_hue(rng, 0.2, 0.5, 0.35, 0.8);
    default:
      return colour_of_any_hue(rng, 0.5, 0.7, 0.5, 0.85);
  }
}

Rgb bottom(Rng& rng) {
  switch (family(rng, std::array<double, 5>{40, 25, 20, 10, 5})) {
    case 0:  // denim
      return hsv(between(rng, 208, 222), between(rng, 0.3, 0.6), between(rng, 0.25, 0.6));
    case 1:  // black, charcoal
      return hsv(between(rng, 200, 240), between(rng, 0.0, 0.12), between(rng, 0.1, 0.25));
    case 2:  // khaki, beige, brown
      return hsv(between(rng, 28, 45), between(rng, 0.25, 0.5), between(rng, 0.3, 0.75));
    case 3:  // grey
      return hsv(between(rng, 180, 240), between(rng, 0.0, 0.06), between(rng, 0.35, 0.6));
    default:
      return colour_of_any_hue(rng, 0.2, 0.45, 0.25, 0.6);
  }
}

Rgb shoes(Rng& rng) {
  switch (family(rng, std::array<double, 5>{35, 20, 25, 10, 10})) {
    case 0:  // black
      return hsv(0, 0, between(rng, 0.08, 0.16));
    case 1:  // dark brown
      return hsv(between(rng, 20, 30), between(rng, 0.45, 0.65), between(rng, 0.2, 0.35));
    case 2:  // white
      return hsv(between(rng, 30, 60), between(rng, 0.0, 0.05), between(rng, 0.85, 0.94));
    case 3:  // grey
      return hsv(0, 0, between(rng, 0.4, 0.6));
    default:  // tan
      return hsv(between(rng, 28, 36), between(rng, 0.4, 0.6), between(rng, 0.5, 0.7));
  }
}

/// Where clothing index `clothing` falls in [0, 1): the fractional part of (clothing + 0.5) times the
/// golden ratio's conjugate (a Weyl sequence). Any run of consecutive indices spreads evenly over [0, 1),
/// so the N consecutive indices of a crowd of N (animate_crowd's shifted permutation) hold share * N of any
/// share, to within about one.
double evenly_spread(int clothing) {
  const double x = (clothing + 0.5) * 0.6180339887498949;
  return x - std::floor(x);
}

Rgb hair(Rng& rng, int clothing, int skin_tone) {
  // Grey first, at its own share (grey_hair_share) and spread evenly over the clothing indices: every crowd
  // used the indices 0..N-1, so a random draw per index fixed the grey heads of every crowd of a size (two
  // in every crowd of 20 before, issue 28).
  if (evenly_spread(clothing) < grey_hair_share(skin_tone))
    return hsv(between(rng, 30, 40), between(rng, 0.02, 0.08), between(rng, 0.55, 0.72));
  // Black and dark brown weigh more the darker the skin; fair hair only on the three lighter tones.
  const double dark = 1.0 + 2.0 * skin_tone;
  const double fair = skin_tone <= 2 ? 3.0 - skin_tone : 0.0;
  switch (family(rng, std::array<double, 6>{dark, dark, 2, 1.5 * fair / 3.0 + 0.2, fair, 0.6 * fair / 3.0})) {
    case 0:  // black
      return hsv(between(rng, 20, 30), between(rng, 0.2, 0.4), between(rng, 0.08, 0.13));
    case 1:  // dark brown
      return hsv(between(rng, 20, 28), between(rng, 0.45, 0.6), between(rng, 0.17, 0.26));
    case 2:  // brown
      return hsv(between(rng, 22, 30), between(rng, 0.5, 0.62), between(rng, 0.28, 0.4));
    case 3:  // light brown
      return hsv(between(rng, 28, 34), between(rng, 0.45, 0.55), between(rng, 0.42, 0.55));
    case 4:  // blond
      return hsv(between(rng, 36, 44), between(rng, 0.4, 0.55), between(rng, 0.62, 0.78));
    default:  // auburn
      return hsv(between(rng, 14, 22), between(rng, 0.6, 0.72), between(rng, 0.35, 0.48));
  }
}

}  // namespace

double grey_hair_share(int skin_tone) {
  return skin_tone <= 2 ? 0.03 : 0.015;
}

Palette fabric_palette(int clothing, int skin_tone) {
  Palette p = palette(clothing);
  p.skin = skin_tone_colour(skin_tone);  // throws outside the scale
  Rng rng(derive_seed(kFabricSeed, "fabric/" + std::to_string(clothing)));
  p.shirt = top(rng);
  p.trousers = bottom(rng);
  p.shoes = shoes(rng);
  p.hair = hair(rng, clothing, skin_tone);
  return p;
}

}  // namespace crowdlab::stimuli
