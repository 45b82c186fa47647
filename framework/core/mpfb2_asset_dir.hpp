#pragma once
// Where the MPFB2 / MakeHuman body assets (CC0) are when a spec's `animation.body_model` names no path.
// crowdlab ships the subset it needs in framework/body/assets/mpfb2 (docs/animation.md says what it holds
// and weighs); the binary finds it by the source tree's path fixed at configure time, so a fresh checkout
// renders realistic people with no download. $CROWDLAB_MPFB2 overrides it (e.g. a full MPFB2 folder, or
// an installed copy when the source tree has moved), and a spec's `body_model.path` overrides both.
#include <filesystem>

namespace crowdlab {

/// The shipped subset's folder (the source tree's framework/body/assets/mpfb2 as configured).
std::filesystem::path shipped_mpfb2_dir();

/// $CROWDLAB_MPFB2 when set and non-empty, else shipped_mpfb2_dir().
std::filesystem::path default_mpfb2_dir();

/// The MakeHuman wardrobe (eyebrows, hair, clothes, shoes; body/mpfb2_outfit.hpp): $CROWDLAB_MAKEHUMAN when
/// set and non-empty, else the shipped framework/body/assets/makehuman as configured.
std::filesystem::path default_makehuman_dir();

}  // namespace crowdlab
