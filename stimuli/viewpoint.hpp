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
// "tracking": follows the focal character (the first, "c000") of seed 001's flow A from behind and
//   above (25 deg down, 6 m, 30 deg off its walking axis), on its path (CrowdExtent::focal_feet_m)
//   smoothed over +-0.5 s so that the gait's sway does not shake the image.
//
// "front" is the crowd's mean facing direction (CrowdExtent::front); the camera sits in front of the
// crowd looking back at it.
//
// Framing rule (V1-V4, pair): the camera looks along the preset's direction; its target and distance
// are chosen so that the crowd's box (CrowdExtent: every body cylinder over the whole clip) projects
// CENTRED in the image and fills kFrameFill = 92 % of the image width or height, whichever binds
// (4 % margin on each side of that dimension), with all eight box corners inside the image. A 3 x 3 m
// concert and a long corridor both fill the view.
//
// Following (V1-V4, pair stays fixed): when the crowd travels (CrowdExtent::follow_path_m, a walking
// crowd), the same rule frames the bodies' box RELATIVE to the crowd's smoothed centroid, and the
// camera rides along that path at a fixed offset: the crowd stays in frame at any clip length, the
// camera never enters the crowd (the fit keeps every box corner in front of it), and the ground and
// walls slide past as they would for a camera dolly. V4 then also turns a quarter about the vertical
// (still 80 deg down, seen from the crowd's side) when that frames the box closer: a corridor's crowd,
// long along its walk, then runs along the image's long side (issue 28, session 24).
//
// One camera per condition: build the Viewpoint from a CrowdExtent computed from the data that the
// methods of a condition share (see crowd_extent.hpp), so `baseline` and `ours` get the same camera.
#include <map>
#include <string>
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "framework/core/viewpoint_catalogue.hpp"
#include "stimuli/camera.hpp"
#include "stimuli/crowd_extent.hpp"

namespace crowdlab::stimuli {

/// Explicit cameras replacing presets (the spec's render.viewpoints, checked there with
/// camera_placement_problem()).
using ViewpointOverrides = std::map<ViewpointId, CameraPlacement>;

class Viewpoint {
 public:
  /// The catalogue's preset `id` framed on `extent`, or overrides[id] when given. The spec loader has
  /// checked the overrides: a placement camera_placement_problem() refuses is a programming error here
  /// (std::logic_error).
  Viewpoint(ViewpointId id, const CrowdExtent& extent, int width, int height,
            const ViewpointOverrides& overrides = {});
  /// Frames a lone crowd file from its own root motion (crowd_extent(character_tracks(crowd))).
  Viewpoint(ViewpointId id, const CrowdAnimation& crowd, int width, int height,
            const ViewpointOverrides& overrides = {});
  /// An explicit camera named `name` (the render command's --viewpoint-override with a name outside the
  /// catalogue); `placement` as above.
  static Viewpoint placed(std::string name, const CameraPlacement& placement, int width, int height);

  /// The camera for frame `frame` (only "tracking" moves).
  Camera at(int frame) const;
  const std::string& name() const { return name_; }
  /// True when the camera moves with the frame ("tracking", or following a travelling crowd); otherwise
  /// at(f) == at(0) for every f.
  bool moves() const { return tracking_ || !follow_path_.empty(); }

 private:
  Viewpoint() = default;
  void place(const CameraPlacement& placement, int width, int height);
  std::string name_;
  Camera fixed_;
  bool tracking_ = false;
  std::vector<Vec3> focal_path_;  ///< smoothed focal root per frame (tracking only)
  Vec3 tracking_offset_ = Vec3::Zero();
  std::vector<Vec3> follow_path_;  ///< per frame, added to fixed_'s eye and target (following only)
};

}  // namespace crowdlab::stimuli
