#pragma once
// Garment and hair colours for dressed bodies (MPFB2 with MakeHuman's outfits, body/mpfb2_outfit.hpp),
// drawn per character instead of picked from the 16 fixed palettes (palette.hpp), which a crowd of 20-60
// repeats visibly (issue 28: "16 flat colour palettes").
//
// Input: the character's clothing index (core/appearance.hpp; animate_crowd gives every character of a
// crowd its own, a permutation seeded per condition and shifted by a seeded offset, so each crowd wears
// other colours; the corrected crowd keeps it, so `baseline` and
// `ours` of a condition wear the same colours) and its skin tone (0 lightest .. 5 darkest). Output: sRGB
// colours in [0, 1]. Each index draws from its own stream, derive_seed(kFabricSeed, "fabric/<index>").
//
// Colour families (facts of everyday wear, not measured data): tops are neutrals (white, grey, black,
// navy, beige; 40 %), muted colours of any hue (45 %; HSV saturation 0.2-0.5) or brighter ones (15 %;
// 0.5-0.7); bottoms are denim blue (40 %), black or charcoal (25 %), khaki, beige or brown (20 %), grey
// (10 %) or a muted colour (5 %); shoes black, dark brown, white, grey or tan; hair black, dark brown,
// brown, light brown, blond or auburn, with black and dark brown more likely for darker skin tones
// (as in the world's population), or grey at its own, small share (grey_hair_share). Every colour is jittered
// a little in value and saturation, so no two characters share exactly a colour. Saturated reds (hue within
// 20 degrees of red, saturation > 0.55) are desaturated: overlap mode paints pure red.
#include <cstdint>

#include "stimuli/palette.hpp"

namespace crowdlab::stimuli {

inline constexpr std::uint64_t kFabricSeed = 0x6661627269637331ull;  // "fabrics1"

/// The share of dressed characters with grey hair, by skin tone: 3 % for the three lighter tones, 1.5 %
/// for the darker ones. Why: the bodies are 25-58 years old (body/sample_mpfb2_bodies.hpp), and a head
/// that reads as grey from a distance (mostly grey hair) is uncommon before 50: Panhard, Lozano and
/// Loussouarn (2012, "Greying of the human hair: a worldwide survey, revisiting the '50' rule of thumb",
/// Br J Dermatol 167:865-873) found 6-23 % of 50-year-olds with half their hair grey, fewer among people
/// of Asian and African descent, who grey later. Before issue 28's review grey was one family among seven
/// by weight: 6-10 % of the lighter tones, about one head in ten of a concert crowd (session 11's
/// close-ups), too many for a crowd whose mean age is about 41 and for a concert's younger audience.
double grey_hair_share(int skin_tone);

/// The palette of a dressed character: drawn colours for shirt, trousers, shoes and hair; skin from the
/// tone (skin_tone_colour); sleeve and trouser lengths of palette(clothing) (used only on bare bodies).
/// Deterministic. Throws InputError for a tone outside [0, kSkinToneCount).
Palette fabric_palette(int clothing, int skin_tone);

}  // namespace crowdlab::stimuli
