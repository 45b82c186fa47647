#pragma once
// The named camera viewpoints: one catalogue, used by the spec's validation (the `viewpoint` factor's
// levels, the keys of render.viewpoints; the default of conditions without a `viewpoint` factor is
// chosen with the condition's typed settings, framework/spec/type_condition.cpp) and by the renderer
// (stimuli/viewpoint.hpp: the framing presets).
//   V1-V4     seed 000 §4.4.1 (Fig. 8): front, upper-front, front-side and overhead. The paper gives no
//             numbers; the angles are chosen to match the figure (see stimuli/viewpoint.hpp).
//   pair      seed 001 §3.1.4's three-quarter view of two characters passing.
//   tracking  follows seed 001's focal character of flow A from behind and above.
// Angles in degrees: azimuth about +Y from the crowd's front, elevation above the horizontal, and the
// vertical field of view.
#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace crowdlab {

struct ViewpointPreset {
  std::string_view name;
  double azimuth_deg = 0.0;
  double elevation_deg = 0.0;
  double fov_deg = 40.0;
};

inline constexpr std::array<ViewpointPreset, 6> kViewpointCatalogue = {{
    {"V1", 0.0, 6.0, 40.0},
    {"V2", 0.0, 30.0, 40.0},
    {"V3", 45.0, 15.0, 40.0},
    {"V4", 0.0, 80.0, 40.0},
    {"pair", 45.0, 30.0, 35.0},
    {"tracking", 30.0, 25.0, 45.0},
}};

/// The catalogue's names in order: V1, V2, V3, V4, pair, tracking.
const std::vector<std::string>& viewpoint_names();

/// The preset named `name`, or nullptr when the catalogue has none.
const ViewpointPreset* find_viewpoint(std::string_view name);

}  // namespace crowdlab
