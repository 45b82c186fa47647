#pragma once
// The named camera viewpoints: one catalogue, indexed by a typed id (ViewpointId). The spec layer turns a
// viewpoint's name into its id once (the `viewpoint` factor's levels, the keys of render.viewpoints;
// framework/spec/type_condition.cpp chooses the default of conditions without a `viewpoint` factor); from
// there the id travels in the condition's typed settings and the render recipe to the camera
// (stimuli/viewpoint.hpp: the framing presets), which reads its preset by index, never by name (issue 30).
//   V1-V4     seed 000 §4.4.1 (Fig. 8): front, upper-front, front-side and overhead. The paper gives no
//             numbers; the angles are chosen to match the figure (see stimuli/viewpoint.hpp).
//   pair      seed 001 §3.1.4's three-quarter view of two characters passing.
//   tracking  follows seed 001's focal character of flow A from behind and above.
// Angles in degrees: azimuth about +Y from the crowd's front, elevation above the horizontal, and the
// vertical field of view.
//
// A camera placement (render.viewpoints, `render --viewpoint-override`) replaces a preset by an explicit
// camera: [px, py, pz, tx, ty, tz, fov_deg], metres and degrees; camera_placement_problem() is its one
// check, made where the placement is read (the spec loader, the render command).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace crowdlab {

enum class ViewpointId : std::uint8_t { V1, V2, V3, V4, pair, tracking };

struct ViewpointPreset {
  ViewpointId id;
  std::string_view name;
  double azimuth_deg = 0.0;
  double elevation_deg = 0.0;
  double fov_deg = 40.0;
};

/// Indexed by ViewpointId (kViewpointCatalogue[i].id == ViewpointId(i)).
inline constexpr std::array<ViewpointPreset, 6> kViewpointCatalogue = {{
    {ViewpointId::V1, "V1", 0.0, 6.0, 40.0},
    {ViewpointId::V2, "V2", 0.0, 30.0, 40.0},
    {ViewpointId::V3, "V3", 45.0, 15.0, 40.0},
    {ViewpointId::V4, "V4", 0.0, 80.0, 40.0},
    {ViewpointId::pair, "pair", 45.0, 30.0, 35.0},
    {ViewpointId::tracking, "tracking", 30.0, 25.0, 45.0},
}};

/// The preset of `id` (by index: no name lookup).
constexpr const ViewpointPreset& viewpoint_preset(ViewpointId id) {
  return kViewpointCatalogue[static_cast<std::size_t>(id)];
}
/// The name of `id` (V1, ..., tracking): for file names, messages and tables.
constexpr std::string_view viewpoint_name(ViewpointId id) {
  return viewpoint_preset(id).name;
}

/// The catalogue's names in order: V1, V2, V3, V4, pair, tracking.
const std::vector<std::string>& viewpoint_names();

/// The id named `name`, or nullopt when the catalogue has none. The one name lookup: made by the spec
/// layer (and by the commands that take a viewpoint's name as an argument).
std::optional<ViewpointId> find_viewpoint(std::string_view name);

/// [px, py, pz, tx, ty, tz, fov_deg]: an explicit camera (eye, target, vertical field of view).
using CameraPlacement = std::array<double, 7>;

/// Why `p` cannot place a camera (a value not finite, fov_deg outside (1, 170) degrees, the eye on the
/// target), or an empty string when it can.
std::string camera_placement_problem(const CameraPlacement& p);

}  // namespace crowdlab
