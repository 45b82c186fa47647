#include "stimuli/overlap_samples.hpp"

#include <algorithm>

#include "framework/core/error.hpp"

namespace crowdlab::stimuli {

std::vector<double> sample_overlap_fractions(Renderer& renderer, const CrowdAnimation& crowd,
                                             const RenderOptions& options, const Viewpoint& view, int frames,
                                             int every) {
  if (every < 1) throw InputError("overlap samples: the frame step must be at least 1");
  prepare_renderer(renderer, crowd, options);
  SceneOptions scene = options.scene;
  scene.overlap = true;
  std::vector<double> fractions;
  for (int f = 0; f < std::min(frames, crowd.frame_count()); f += every) {
    renderer.draw(f, view.at(f), scene);
    fractions.push_back(renderer.overlap_fraction());
  }
  return fractions;
}

}  // namespace crowdlab::stimuli
