#pragma once
// A character's appearance index (CharacterAnimation::palette) packs two choices, so that crowd files
// carry both with no format change and older files keep their meaning:
//   palette = clothing + kAppearanceStride * (skin_tone + 1)
//   clothing   the clothing palette (renderers take it modulo their palette count), in [0, kAppearanceStride)
//   skin_tone  -1: the clothing palette's own skin (what every procedural body uses, so a plain index
//              0..N-1 means what it always did); 0 lightest .. kSkinToneCount - 1 darkest: a six-step,
//              Fitzpatrick-like scale (renderers map it to colours), set by body models whose shape carries
//              an ethnicity (MPFB2, body/sample_mpfb2_bodies.hpp) so that skin and body shape agree.
// Indices below 0 are taken as plain clothing indices (renderers wrap them).

namespace crowdlab {

inline constexpr int kSkinToneCount = 6;
inline constexpr int kAppearanceStride = 1 << 16;

/// The appearance index for a clothing palette in [0, kAppearanceStride) and a skin tone in
/// [-1, kSkinToneCount). Out-of-range arguments are the caller's bug (checked in debug builds by tests).
constexpr int pack_appearance(int clothing, int skin_tone) {
  return clothing + kAppearanceStride * (skin_tone + 1);
}

/// The clothing palette of an appearance index.
constexpr int clothing_of(int appearance) {
  return appearance < 0 ? appearance : appearance % kAppearanceStride;
}

/// The skin tone of an appearance index: -1 (the clothing palette's own skin) or 0..kSkinToneCount - 1.
constexpr int skin_tone_of(int appearance) {
  return appearance < 0 ? -1 : appearance / kAppearanceStride - 1;
}

}  // namespace crowdlab
