// One camera per condition (issue 17): the framing comes from a CrowdExtent that the methods of a
// condition share, it follows the framing rule of viewpoint.hpp, and with it the two clips of a pair
// differ only where the bodies differ.
#include <catch2/catch.hpp>
#include <cmath>

#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "stimuli/crowd_extent.hpp"
#include "stimuli/render_clip.hpp"
#include "stimuli/synthetic_crowd.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_shared_camera {

using namespace crowdlab;
using namespace crowdlab::stimuli;

namespace {

/// Screen rectangle (pixels; x0 > x1 when empty).
struct Rect {
  double x0 = 1e30, y0 = 1e30, x1 = -1e30, y1 = -1e30;
  void add(const Eigen::Vector2d& p) {
    x0 = std::min(x0, p.x());
    y0 = std::min(y0, p.y());
    x1 = std::max(x1, p.x());
    y1 = std::max(y1, p.y());
  }
  bool contains(double x, double y, double margin) const {
    return x >= x0 - margin && x <= x1 + margin && y >= y0 - margin && y <= y1 + margin;
  }
};

/// Projected bounds of the eight corners of the box [lo, hi].
Rect project_box(const Camera& cam, const Vec3& lo, const Vec3& hi) {
  Rect r;
  for (int c = 0; c < 8; ++c) {
    const auto p =
        cam.project(Vec3((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z()));
    REQUIRE(p);
    r.add(*p);
  }
  return r;
}

/// Projected bounds of a character's posed capsules at `frame` (the world box of each capsule).
Rect project_body(const Camera& cam, const CharacterAnimation& c, int frame) {
  const BoneTransforms bones = forward_kinematics(c.shape, c.frames[static_cast<size_t>(frame)]);
  Rect r;
  for (size_t j = 0; j < bones.size(); ++j) {
    const Capsule cap = c.shape.capsules[j].transformed(bones[j]);
    const Rect b = project_box(cam, cap.a.cwiseMin(cap.b) - Vec3::Constant(cap.radius_m),
                               cap.a.cwiseMax(cap.b) + Vec3::Constant(cap.radius_m));
    r.add({b.x0, b.y0});
    r.add({b.x1, b.y1});
  }
  return r;
}

CrowdAnimation synthetic(int characters, double spacing_m, int frames, double walk_mps = 0.0) {
  SyntheticCrowdOptions o;
  o.characters = characters;
  o.spacing_m = spacing_m;
  o.frames = frames;
  o.stage = false;
  o.walk_speed_mps = walk_mps;
  return make_synthetic_crowd(o);
}

/// A flat crowd's trajectories: `agents` standing still on a rows x columns grid facing +Z.
CrowdTrajectories standing_grid(int rows, int columns, double pitch_m, int frames) {
  CrowdTrajectories t;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      AgentTrajectory a;
      a.position_m.assign(static_cast<size_t>(frames), Vec2(c * pitch_m, -r * pitch_m));
      a.heading_rad.assign(static_cast<size_t>(frames), 0.0);
      t.agents.push_back(a);
    }
  return t;
}

}  // namespace

TEST_CASE("framing rule: at V1-V4 the crowd's box is centred and fills 92 % of the binding dimension",
          "[stimuli]") {
  const CrowdTrajectories band = standing_grid(3, 12, 0.9, 2);  // a 10 m wide, 2 m deep audience
  std::vector<CrowdExtent> extents = {
      crowd_extent(character_tracks(synthetic(9, 0.8, 2)), 30.0),
      crowd_extent(character_tracks(synthetic(12, 3.0, 2)), 30.0),
      crowd_extent(character_tracks(synthetic(8, 0.9, 30, 1.2)), 30.0),  // walking
      crowd_extent(character_tracks(band, std::vector<double>(band.agents.size(), 1.7)), 30.0)};
  const int w = 320, h = 180;
  for (size_t k = 0; k < extents.size(); ++k)
    for (const char* name : {"V1", "V2", "V3", "V4"}) {
      INFO("crowd " << k << ", viewpoint " << name);
      const Camera cam = Viewpoint(*find_viewpoint(name), extents[k], w, h).at(0);
      // A travelling crowd (the walkers) is framed by its box relative to the follow path.
      const CrowdExtent& e = extents[k];
      const bool follows = !e.follow_path_m.empty();
      const Rect box =
          follows ? project_box(cam, e.follow_lo_m + e.follow_path_m[0], e.follow_hi_m + e.follow_path_m[0])
                  : project_box(cam, e.lo_m, e.hi_m);
      CHECK(box.x0 >= 0.0);
      CHECK(box.y0 >= 0.0);
      CHECK(box.x1 <= w);
      CHECK(box.y1 <= h);
      CHECK(std::max((box.x1 - box.x0) / w, (box.y1 - box.y0) / h) == Approx(0.92).margin(0.002));
      CHECK(0.5 * (box.x0 + box.x1) == Approx(0.5 * w).margin(0.5));
      CHECK(0.5 * (box.y0 + box.y1) == Approx(0.5 * h).margin(0.5));
    }
  // The bodies themselves (not only their box, which adds 0.4 m around each body axis) fill most of the
  // frame of a small 3 x 3 m crowd: >= 70 % of the width or height.
  const CrowdAnimation crowd = synthetic(16, 0.8, 2);
  const CrowdExtent extent = crowd_extent(character_tracks(crowd), 30.0);
  for (const char* name : {"V1", "V2", "V3", "V4"}) {
    INFO("viewpoint " << name);
    const Camera cam = Viewpoint(*find_viewpoint(name), extent, w, h).at(0);
    Rect bodies;
    for (const CharacterAnimation& c : crowd.characters) {
      const Rect b = project_body(cam, c, 0);
      bodies.add({b.x0, b.y0});
      bodies.add({b.x1, b.y1});
    }
    CHECK(std::max((bodies.x1 - bodies.x0) / w, (bodies.y1 - bodies.y0) / h) >= 0.7);
  }
}

TEST_CASE("crowd extent: trajectories and heights, surface frames and errors", "[stimuli]") {
  const CrowdTrajectories grid = standing_grid(2, 3, 1.0, 3);
  std::vector<double> heights = {1.6, 1.7, 1.8, 1.9, 1.65, 1.75};
  const CrowdExtent e = crowd_extent(character_tracks(grid, heights), 15.0);
  CHECK(e.lo_m.isApprox(Vec3(-kBodyRadiusM, 0.0, -1.0 - kBodyRadiusM)));
  CHECK(e.hi_m.isApprox(Vec3(2.0 + kBodyRadiusM, 1.9, kBodyRadiusM)));
  CHECK(e.front.isApprox(Vec3::UnitZ()));
  REQUIRE(e.focal_feet_m.size() == 3);
  CHECK(e.focal_feet_m[2].isApprox(Vec3::Zero()));
  CHECK_THROWS_AS(character_tracks(grid, {1.7}), InputError);
  CHECK_THROWS_AS(crowd_extent({}, 30.0), InputError);
  // A body standing on a wall (up = +X) extends along +X by its height.
  SurfaceTrajectories wall;
  wall.agents.push_back({{Vec3(0, 2, 0)}, {Vec3::UnitX()}, {Vec3::UnitZ()}});
  const CrowdExtent w = crowd_extent(character_tracks(wall, {1.8}), 30.0);
  CHECK(w.hi_m.x() == Approx(1.8));
  CHECK(w.lo_m.x() == Approx(0.0).margin(1e-12));
  CHECK(w.hi_m.y() == Approx(2.0 + kBodyRadiusM));
}

TEST_CASE("with the shared camera, frame 0 of a pair differs only where the bodies differ", "[stimuli]") {
  // `baseline` and a corrected copy: character 0 (at the crowd's edge) is moved 8 cm at every frame
  // and raises its left arm, as a correction would do; the others are unchanged.
  CrowdAnimation baseline = synthetic(6, 1.3, 2);
  baseline.environment.ground_plane = false;  // a moved body's shadow on the ground would differ too
  CrowdAnimation ours = baseline;
  for (Pose& p : ours.characters[0].frames) {
    p.root_position_m += Vec3(-0.08, 0.0, 0.05);
    p.local_rotations[kLeftShoulder] =
        Quat(Eigen::AngleAxisd(0.6, Vec3::UnitX())) * p.local_rotations[kLeftShoulder];
  }
  // The shared framing data: here the baseline's motion stands for the trajectories both share.
  const CrowdExtent extent = crowd_extent(character_tracks(baseline), baseline.meta.fps);
  RenderOptions options;
  options.width = 320;
  options.height = 180;
  const Camera cam = Viewpoint(ViewpointId::V3, extent, options.width, options.height).at(0);
  MannequinOptions mesh;
  mesh.voxel_m = 0.035;
  Renderer renderer(mesh);
  const BgrImage a = render_frame(renderer, baseline, options, cam, 0);
  const BgrImage b = render_frame(renderer, ours, options, cam, 0);
  REQUIRE(a.bgr.size() == b.bgr.size());

  Rect changed = project_body(cam, baseline.characters[0], 0);
  const Rect moved = project_body(cam, ours.characters[0], 0);
  changed.add({moved.x0, moved.y0});
  changed.add({moved.x1, moved.y1});
  std::vector<Rect> everyone;
  for (const CharacterAnimation& c : baseline.characters) everyone.push_back(project_body(cam, c, 0));
  everyone.push_back(moved);
  const double margin_px = 2.0;  // antialiasing
  int differing = 0, outside = 0, far_pixels = 0, far_differing = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const size_t at = 3 * (static_cast<size_t>(y) * static_cast<size_t>(a.width) + static_cast<size_t>(x));
      const bool same =
          a.bgr[at] == b.bgr[at] && a.bgr[at + 1] == b.bgr[at + 1] && a.bgr[at + 2] == b.bgr[at + 2];
      const double cx = x + 0.5, cy = y + 0.5;
      if (!same) ++differing;
      if (!same && !changed.contains(cx, cy, margin_px)) ++outside;
      bool near_someone = false;
      for (const Rect& r : everyone) near_someone = near_someone || r.contains(cx, cy, 10.0);
      if (!near_someone) {
        ++far_pixels;
        if (!same) ++far_differing;
      }
    }
  CHECK(differing > 50);      // the pair does differ ...
  CHECK(outside == 0);        // ... only around the body that differs
  CHECK(far_pixels > 10000);  // much of the image is far from every character ...
  CHECK(far_differing == 0);  // ... and identical there
}

}  // namespace test_shared_camera
