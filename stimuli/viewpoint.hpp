#pragma once
// Named camera viewpoints that frame a crowd automatically.
//
// Seed 000 §4.4.1 names four viewpoints for its stimuli: front (V1), upper-front (V2), front-side (V3)
// and overhead (V4); Fig. 8 shows them. The paper gives no numbers, so the presets are chosen to
// match the figure: V1 near eye level (6 deg above the horizontal), V2 30 deg down, V3 45 deg to the
// side and 15 deg down (it shows full foreground bodies and the upper bodies behind them, §4.4.4),
// V4 a bird's-eye view 80 deg down. All use a 40 deg vertical field of view.
// "pair": seed 001 §3.1.4's canonical three-quarter view of two characters passing: 45 deg from the
//   walking axis, 30 deg down, so that one character starts top right and the other bottom left.
// "tracking": follows the focal character (named "c000", else the first) of seed 001's flow A
//   from behind and above (25 deg down, 6 m, 30 deg off its walking axis), on its root position
//   smoothed over +-0.5 s so that the gait's sway does not shake the image.
//
// "front" is the crowd's mean facing direction (unit forward vectors of the roots averaged over all
// characters and frames); when they cancel out (|mean| < 0.25, e.g. bidirectional flows) it is +Z.
// The camera sits in front of the crowd looking back at it. Presets put the crowd's bounding box
// (all root positions over the clip, +-0.4 m, from the ground to the tallest head) inside the
// frame with an 8 % margin, so a 3 x 3 m concert and a long corridor both fill the view.
#include <map>
#include <string>
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "stimuli/camera.hpp"

namespace crowdlab::stimuli {

/// The names accepted by Viewpoint: V1, V2, V3, V4, pair, tracking.
const std::vector<std::string>& viewpoint_names();

/// Overrides from the spec's render.viewpoint_overrides: name -> [px,py,pz, tx,ty,tz, fov_deg].
using ViewpointOverrides = std::map<std::string, std::vector<double>>;

class Viewpoint {
 public:
  /// Throws InputError for an unknown name or a malformed override (not 7 finite numbers, fov
  /// outside (1, 170) degrees, eye == target).
  Viewpoint(const std::string& name, const CrowdAnimation& crowd, int width, int height,
            const ViewpointOverrides& overrides = {});

  /// The camera for frame `frame` (only "tracking" moves).
  Camera at(int frame) const;
  const std::string& name() const { return name_; }

 private:
  std::string name_;
  Camera fixed_;
  bool tracking_ = false;
  std::vector<Vec3> focal_path_;  ///< smoothed focal root per frame (tracking only)
  Vec3 tracking_offset_ = Vec3::Zero();
};

}  // namespace crowdlab::stimuli
