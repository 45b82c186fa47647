#pragma once
// Overlap-mode samples of a clip for the stimulus check (stimulus_check.hpp): frames 0, every,
// 2 every, ... of the crowd drawn again with SceneOptions::overlap on (seed 000 Fig. 5: pixels whose
// surface lies inside another character), each reduced to its overlap-pixel fraction. Nothing is
// encoded; the clip itself is rendered as the spec asks.
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "stimuli/render_clip.hpp"
#include "stimuli/renderer.hpp"
#include "stimuli/viewpoint.hpp"

namespace crowdlab::stimuli {

/// The overlap-pixel fraction (Renderer::overlap_fraction) of every `every`-th of the first `frames`
/// frames, drawn with `options` (image size, MSAA) plus overlap mode. Throws InputError when every < 1.
std::vector<double> sample_overlap_fractions(Renderer& renderer, const CrowdAnimation& crowd,
                                             const RenderOptions& options, const Viewpoint& view, int frames,
                                             int every);

}  // namespace crowdlab::stimuli
