#pragma once
// clip_sidecar: the JSON that travels next to a stimulus clip (clip.mp4 -> clip.json) and says how it
// was made: the camera of every frame and who is in it. Format (docs/stimuli.md, "Clip sidecar"):
//   {"format": "crowdlab-clip/1", "viewpoint": "V3", "frames": N, "fps": 30,
//    "camera": {"moves": false, "eye": [x,y,z], "target": [x,y,z], "up": [x,y,z], "fov_y_deg": 40,
//               "near_m": .., "far_m": .., "width": 1920, "height": 1080},
//    "camera_per_frame": [{"eye": .., "target": .., "up": ..}, ...],   // "tracking" only (moves: true)
//    "characters": [{"name": "c000", "sex": "female", "height_m": 1.62}, ...]}
// Positions in metres (world frame, +Y up), angles in degrees; "camera" holds frame 0.
// Sex and height come from each character's BodyShape params (shape.params.sex, .height_m).
#include <filesystem>
#include <nlohmann/json.hpp>

#include "framework/core/crowd_animation.hpp"
#include "stimuli/viewpoint.hpp"

namespace crowdlab::stimuli {

/// The sidecar of a clip of `frames` frames of `crowd` seen from `view`.
nlohmann::json clip_sidecar(const Viewpoint& view, int frames, const CrowdAnimation& crowd);

/// Where the sidecar of `clip` lives: the same path with the extension ".json".
std::filesystem::path clip_sidecar_path(const std::filesystem::path& clip);

/// A camera as the sidecar's "camera" object records it (eye, target, up, fov, near/far, size).
nlohmann::json camera_json(const Camera& camera);

}  // namespace crowdlab::stimuli
