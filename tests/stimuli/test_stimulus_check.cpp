// The stimulus check (issue 28 item 7) and the cameras it judges (item 1): crowd in frame, character
// height, loop seam and overlap measures; a travelling crowd stays in frame with a camera outside it.
#include <catch2/catch.hpp>

#include "framework/core/error.hpp"
#include "stimuli/crowd_extent.hpp"
#include "stimuli/stimulus_check.hpp"
#include "stimuli/synthetic_crowd.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_stimulus_check {

using namespace crowdlab;
using namespace crowdlab::stimuli;

namespace {

CrowdAnimation synthetic(int characters, int frames, double walk_mps = 0.0) {
  SyntheticCrowdOptions o;
  o.characters = characters;
  o.spacing_m = 0.8;
  o.frames = frames;
  o.stage = false;
  o.walk_speed_mps = walk_mps;
  o.corridor_walls = walk_mps > 0.0;
  return make_synthetic_crowd(o);
}

}  // namespace

TEST_CASE("stimulus check: crowd in frame, character height and the loop seam of a looping crowd",
          "[stimuli]") {
  const CrowdAnimation crowd = synthetic(9, 40);  // the idle motion's period is the clip: it loops
  const CrowdExtent extent = crowd_extent(character_tracks(crowd), crowd.meta.fps);
  const Viewpoint v1(ViewpointId::V1, extent, 640, 360);
  const StimulusCheck c = measure_stimulus_geometry(crowd, v1, crowd.frame_count());
  CHECK(c.crowd_in_frame_min == 1.0);
  CHECK(c.character_height_px > 60.0);   // 9 people fill 92 % of a 360 px high image ...
  CHECK(c.character_height_px < 360.0);  // ... each one less than all of it
  CHECK(c.seam_step_ratio < 1.5);
  CHECK(c.overlap_frame_share == -1.0);  // not measured here
  // One character moved far to the side leaves the frame: 8 of 9 remain.
  CrowdAnimation strayed = crowd;
  for (Pose& p : strayed.characters[4].frames) p.root_position_m.x() += 40.0;
  CHECK(measure_stimulus_geometry(strayed, v1, crowd.frame_count()).crowd_in_frame_min == Approx(8.0 / 9.0));
  // Cut the clip short of its period: the seam now jumps.
  CHECK(measure_stimulus_geometry(crowd, v1, 25).seam_step_ratio > 3.0);
  CHECK_THROWS_AS(measure_stimulus_geometry(crowd, v1, 0), InputError);
  CHECK_THROWS_AS(measure_stimulus_geometry(crowd, v1, 41), InputError);
}

TEST_CASE("stimulus check: a walking crowd keeps in frame and in size, and its seam is reported",
          "[stimuli]") {
  // 12 walkers covering 13 m in 10 s: one box over the whole clip would make them specks.
  const CrowdAnimation crowd = synthetic(12, 300, 1.3);
  const CrowdExtent extent = crowd_extent(character_tracks(crowd), crowd.meta.fps);
  REQUIRE(extent.follow_path_m.size() == 300u);
  for (const char* name : {"V1", "V2", "V3", "V4"}) {
    INFO(name);
    const Viewpoint view(*find_viewpoint(name), extent, 640, 360);
    CHECK(view.moves());
    const StimulusCheck c = measure_stimulus_geometry(crowd, view, crowd.frame_count());
    CHECK(c.crowd_in_frame_min == 1.0);
    CHECK(c.character_height_px > (std::string(name) == "V4" ? 20.0 : 50.0));
    CHECK(c.seam_step_ratio > 3.0);  // they jump back 13 m when the clip restarts
    // The camera never stands inside the crowd: at every frame it is outside the bodies' box.
    for (int f = 0; f < crowd.frame_count(); f += 15) {
      Vec3 lo = Vec3::Constant(1e30), hi = Vec3::Constant(-1e30);
      for (const CharacterAnimation& ch : crowd.characters) {
        lo = lo.cwiseMin(ch.frames[static_cast<size_t>(f)].root_position_m);
        hi = hi.cwiseMax(ch.frames[static_cast<size_t>(f)].root_position_m);
      }
      const Vec3 eye = view.at(f).eye;
      const bool inside = (eye.array() > lo.array() - 0.3).all() && (eye.array() < hi.array() + 0.3).all();
      CHECK_FALSE(inside);
    }
  }
  // From overhead, walkers in a corridor (3 abreast, 8 deep: longer along the walk than across it)
  // cross the image along its long side, the camera's right axis along the walk; seen from their front
  // they were half as tall on screen.
  SyntheticCrowdOptions o;
  o.characters = 24;
  o.columns = 3;
  o.frames = 120;
  o.stage = false;
  o.walk_speed_mps = 1.3;
  o.corridor_walls = true;
  const CrowdAnimation corridor = make_synthetic_crowd(o);
  const CrowdExtent along = crowd_extent(character_tracks(corridor), corridor.meta.fps);
  const Vec3 size = along.follow_hi_m - along.follow_lo_m, walk = along.front;
  REQUIRE(std::abs(size.dot(walk)) > 1.5 * std::abs(size.dot(Vec3::UnitY().cross(walk).normalized())));
  const Viewpoint v4(ViewpointId::V4, along, 640, 360);
  const Vec3 right = (v4.at(0).target - v4.at(0).eye).cross(Vec3::UnitY()).normalized();
  CHECK(std::abs(right.dot(walk)) > 0.98);
  const StimulusCheck overhead = measure_stimulus_geometry(corridor, v4, corridor.frame_count());
  CHECK(overhead.crowd_in_frame_min == 1.0);
  CHECK(overhead.character_height_px > 20.0);
  // A crowd that stays put keeps a fixed camera.
  const CrowdAnimation still = synthetic(4, 30);
  CHECK(crowd_extent(character_tracks(still), 30.0).follow_path_m.empty());
  CHECK_FALSE(Viewpoint(ViewpointId::V3, crowd_extent(character_tracks(still), 30.0), 64, 36).moves());
}

TEST_CASE("stimulus check: overlap measures, thresholds and the sidecar form", "[stimuli]") {
  StimulusCheck c;
  add_overlap_measures(c, {0.0, 0.002, 0.0, 0.006});
  CHECK(c.overlap_frame_share == 0.5);
  CHECK(c.overlap_pixel_fraction == Approx(0.002));
  c.crowd_in_frame_min = 0.9;
  c.character_height_px = 70.0;
  c.seam_step_ratio = 4.0;
  StimulusCheckSpec limits;
  limits.baseline_overlap_frames_min = 0.6;
  // V1 at 1080p: out of frame, too small, seam, and too little baseline overlap.
  CHECK(stimulus_check_failures(c, limits, {ViewpointId::V1, true, true, 1080}).size() == 4);
  // V4's own height limit (60 px) passes; a clip that does not loop has no seam to judge; ours is
  // not held to the baseline's overlap.
  CHECK(stimulus_check_failures(c, limits, {ViewpointId::V4, false, false, 1080}).size() == 1);
  // Pixel limits scale with the image height: 70 px is plenty at 270 px high.
  CHECK(stimulus_check_failures(c, limits, {ViewpointId::V1, false, false, 270}).size() == 1);
  StimulusCheck unknown;
  CHECK(stimulus_check_failures(unknown, limits, {ViewpointId::V1, true, true, 1080}).empty());
  const StimulusCheck back = stimulus_check_from_json(stimulus_check_json(c));
  CHECK(back.crowd_in_frame_min == 0.9);
  CHECK(back.overlap_pixel_fraction == Approx(0.002));
  CHECK(stimulus_check_from_json(stimulus_check_json(unknown)).seam_step_ratio == -1.0);
}

}  // namespace test_stimulus_check
