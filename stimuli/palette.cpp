#include "stimuli/palette.hpp"

#include <string>
#include <vector>

#include "framework/core/error.hpp"
#include "stimuli/fabric_palette.hpp"

namespace crowdlab::stimuli {
namespace {

// Skin tones, light to dark (the skin tone of an appearance index, core/appearance.hpp, indexes them).
constexpr std::array<Rgb, kSkinToneCount> kSkin = {rgb(241, 205, 180), rgb(226, 184, 150), rgb(198, 150, 112),
                                                   rgb(160, 112, 80),  rgb(120, 80, 56),   rgb(86, 58, 42)};
constexpr Rgb kHairBlack = rgb(30, 26, 24), kHairBrown = rgb(78, 52, 34), kHairBlond = rgb(186, 150, 96),
              kHairAuburn = rgb(120, 58, 34), kHairGrey = rgb(150, 146, 140);

const std::vector<Palette>& table() {
  static const std::vector<Palette> palettes = {
      {kSkin[0], kHairBrown, rgb(52, 84, 140), rgb(48, 52, 62), rgb(40, 36, 34), true, true},
      {kSkin[2], kHairBlack, rgb(214, 210, 198), rgb(70, 88, 120), rgb(230, 230, 226), false, true},
      {kSkin[4], kHairBlack, rgb(176, 70, 56), rgb(58, 58, 58), rgb(34, 32, 30), true, true},
      {kSkin[1], kHairBlond, rgb(84, 124, 84), rgb(156, 132, 100), rgb(96, 64, 44), false, true},
      {kSkin[3], kHairBlack, rgb(230, 186, 70), rgb(40, 48, 72), rgb(220, 220, 214), false, false},
      {kSkin[0], kHairAuburn, rgb(120, 60, 110), rgb(40, 40, 46), rgb(30, 30, 30), true, true},
      {kSkin[5], kHairBlack, rgb(236, 236, 232), rgb(92, 76, 60), rgb(60, 40, 30), false, true},
      {kSkin[1], kHairGrey, rgb(96, 108, 120), rgb(150, 150, 140), rgb(70, 60, 52), true, true},
      {kSkin[2], kHairBrown, rgb(40, 120, 130), rgb(200, 190, 160), rgb(200, 196, 188), false, false},
      {kSkin[3], kHairBlack, rgb(150, 40, 60), rgb(34, 44, 70), rgb(240, 240, 236), true, true},
      {kSkin[0], kHairBlond, rgb(244, 150, 120), rgb(80, 110, 150), rgb(230, 228, 222), false, true},
      {kSkin[4], kHairBrown, rgb(60, 60, 66), rgb(110, 100, 80), rgb(40, 30, 26), true, true},
      {kSkin[2], kHairAuburn, rgb(140, 160, 200), rgb(60, 60, 70), rgb(50, 40, 36), false, true},
      {kSkin[5], kHairGrey, rgb(200, 120, 50), rgb(50, 54, 60), rgb(36, 34, 32), true, true},
      {kSkin[1], kHairBlack, rgb(110, 150, 90), rgb(230, 224, 210), rgb(160, 120, 90), false, false},
      {kSkin[3], kHairBrown, rgb(70, 70, 140), rgb(120, 124, 130), rgb(30, 30, 30), true, true},
  };
  return palettes;
}

}  // namespace

Rgb Palette::colour(SkinRegion region) const {
  switch (region) {
    case SkinRegion::kHair:
      return hair;
    case SkinRegion::kShirt:
      return shirt;
    case SkinRegion::kSleeve:
      return long_sleeves ? shirt : skin;
    case SkinRegion::kTrousers:
      return trousers;
    case SkinRegion::kLowerLeg:
      return long_trousers ? trousers : skin;
    case SkinRegion::kShoes:
      return shoes;
    case SkinRegion::kEyeWhite:
      return rgb(226, 222, 214);  // sclera: off-white, a little darker than paper white
    case SkinRegion::kIris:
      return rgb(58, 40, 30);  // dark brown, the world's most common iris colour
    case SkinRegion::kLips:    // lips: the skin, redder and darker
      return {skin[0] * 0.82f, skin[1] * 0.58f, skin[2] * 0.58f};
    case SkinRegion::kBrow:  // brows: the hair colour, a little darker
      return {hair[0] * 0.75f, hair[1] * 0.75f, hair[2] * 0.75f};
    default:
      return skin;
  }
}

int palette_count() {
  return static_cast<int>(table().size());
}

const Palette& palette(int index) {
  const int n = palette_count();
  return table()[static_cast<size_t>(((index % n) + n) % n)];
}

Rgb skin_tone_colour(int tone) {
  if (tone < 0 || tone >= kSkinToneCount)
    throw InputError("skin tone " + std::to_string(tone) + " is not in [0, " +
                     std::to_string(kSkinToneCount - 1) + "]");
  return kSkin[static_cast<size_t>(tone)];
}

Palette character_palette(int appearance) {
  if (skin_tone_of(appearance) >= 0) return fabric_palette(clothing_of(appearance), skin_tone_of(appearance));
  return palette(clothing_of(appearance));
}

}  // namespace crowdlab::stimuli
