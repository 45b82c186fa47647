#pragma once
// The manifest row of one rendered clip (framework/core/stimulus_manifest.hpp): file, duration, frame
// count, resolution and the SHA-256 of the MP4, from render_clip()'s result. Metric columns (overlap
// volume, V_i, collisions) come from the animation layer and are left for the caller to fill.
#include <map>
#include <string>

#include "framework/core/stimulus_manifest.hpp"
#include "stimuli/render_clip.hpp"

namespace crowdlab::stimuli {

/// `mp4_path` is the file on disk (hashed); `file_in_manifest` the path written into the manifest
/// (relative to the manifest's folder). Throws RuntimeError when the file cannot be read.
StimulusEntry make_stimulus_entry(const std::string& id, const std::map<std::string, std::string>& factors,
                                  const std::string& mp4_path, const std::string& file_in_manifest,
                                  const RenderResult& result);

}  // namespace crowdlab::stimuli
