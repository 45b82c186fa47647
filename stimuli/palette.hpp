#pragma once
// Clothing and skin palettes for mannequin characters (CharacterAnimation::palette selects one).
// Colours are sRGB in [0, 1]. Skin tones span the range of the Fitzpatrick-scale swatches used in
// graphics practice; clothing is muted everyday wear (no saturated pure red, which overlap mode uses).
// A palette also says whether sleeves and lower legs are clothed (long sleeves / trousers) or skin
// (short sleeves / shorts or skirt), which varies silhouettes as well as colours.
#include <array>

#include "framework/core/appearance.hpp"
#include "stimuli/mannequin_mesh.hpp"

namespace crowdlab::stimuli {

using Rgb = std::array<float, 3>;

/// A colour from its 0-255 sRGB bytes.
constexpr Rgb rgb(int r, int g, int b) {
  return {r / 255.0f, g / 255.0f, b / 255.0f};
}

struct Palette {
  Rgb skin, hair, shirt, trousers, shoes;
  bool long_sleeves = true;
  bool long_trousers = true;

  /// Colour of a mesh region under this palette.
  Rgb colour(SkinRegion region) const;
};

/// Number of distinct built-in palettes (>= 12).
int palette_count();
/// Palette `index` modulo palette_count() (negative indices wrap too).
const Palette& palette(int index);

/// The colour of skin tone `tone` (0 lightest .. kSkinToneCount - 1 darkest, core/appearance.hpp): the
/// same six swatches the palettes use. Throws InputError outside [0, kSkinToneCount).
Rgb skin_tone_colour(int tone);

/// A character's palette from its appearance index (CharacterAnimation::palette, core/appearance.hpp):
/// the clothing palette; when the index carries a skin tone (a body model with an ethnicity: MPFB2), the
/// colours drawn for that clothing index and tone instead (fabric_palette.hpp), skin from the tone.
Palette character_palette(int appearance);

}  // namespace crowdlab::stimuli
