// Issue 28 items 2-4 on the renderer side: dressed bodies (surface labels -> regions, two-sided sheets), the
// set dressing per scenario, and the clean image (FXAA, soft shadows, contact darkening).
#include <catch2/catch.hpp>
#include <opencv2/core.hpp>
#include <set>

#include "framework/body/sample_mpfb2_bodies.hpp"
#include "framework/core/mpfb2_asset_dir.hpp"
#include "stimuli/decode_luma.hpp"
#include "stimuli/render_clip.hpp"
#include "stimuli/render_quality.hpp"
#include "stimuli/scene_set.hpp"
#include "stimuli/skinned_body_mesh.hpp"
#include "stimuli/synthetic_crowd.hpp"

using namespace crowdlab;
using namespace crowdlab::stimuli;

namespace {

cv::Mat luma_of(const BgrImage& img) {
  std::vector<std::uint8_t> rgba(static_cast<size_t>(img.width) * img.height * 4);
  for (size_t p = 0, q = 0; p < img.bgr.size(); p += 3, q += 4) {
    rgba[q] = img.bgr[p + 2];
    rgba[q + 1] = img.bgr[p + 1];
    rgba[q + 2] = img.bgr[p];
    rgba[q + 3] = 255;
  }
  return rgba_to_luma_bt709(rgba.data(), img.width, img.height, false);
}

Renderer& renderer() {
  static Renderer r([] {
    MannequinOptions o;
    o.voxel_m = 0.035;
    return o;
  }());
  return r;
}

bool overlaps(const Box& a, const Vec3& lo, const Vec3& hi) {  // axis-aligned bound of a rotated box
  const Eigen::Matrix3d r = a.rotation.normalized().toRotationMatrix();
  const Vec3 half = r.cwiseAbs() * a.half_extents_m;
  return (a.center_m - half).x() < hi.x() && (a.center_m + half).x() > lo.x() &&
         (a.center_m - half).z() < hi.z() && (a.center_m + half).z() > lo.z();
}

}  // namespace

TEST_CASE("a dressed MPFB2 body renders eyes, lips, brows, hair, garments and shoes as two-sided regions",
          "[stimuli]") {
  const auto model = Mpfb2Model::load(shipped_mpfb2_dir());
  const auto wardrobe =
      Mpfb2Wardrobe::load(default_makehuman_dir(), static_cast<int>(model->base().vertices.size()));
  const auto bodies =
      sample_mpfb2_bodies(*model, 2, 11, 0.5, kWorldFemaleHeight, kWorldMaleHeight, wardrobe.get());
  for (const Mpfb2Sample& s : bodies) {
    const MannequinMesh r = skinned_body_mesh(s.body.mesh);
    CHECK(r.two_sided);
    int lips = 0;
    for (const std::uint8_t k : s.body.mesh.surface)
      lips += k == static_cast<std::uint8_t>(SurfaceKind::kLips);
    INFO("lips vertices " << lips);
    std::set<int> regions;
    for (const MannequinVertex& v : r.vertices) regions.insert(v.region);
    for (SkinRegion k :
         {SkinRegion::kSkin, SkinRegion::kLips, SkinRegion::kEyeWhite, SkinRegion::kIris, SkinRegion::kBrow,
          SkinRegion::kHair, SkinRegion::kShirt, SkinRegion::kTrousers, SkinRegion::kShoes}) {
      INFO("region " << static_cast<int>(k));
      CHECK(regions.count(static_cast<int>(k)) == 1);
    }
    CHECK(regions.count(static_cast<int>(SkinRegion::kSleeve)) == 0);  // no painted-on clothing
    CHECK(!skinned_body_mesh(bodies.front().body.mesh).indices.empty());
  }
  // The palette colours the new regions: dark iris on a light sclera, brows darker than the hair.
  const Palette p = palette(0);
  const auto lum = [](const Rgb& c) { return c[0] + c[1] + c[2]; };
  CHECK(lum(p.colour(SkinRegion::kIris)) < 0.5f * lum(p.colour(SkinRegion::kEyeWhite)));
  CHECK(lum(p.colour(SkinRegion::kBrow)) < lum(p.colour(SkinRegion::kHair)));
  CHECK(lum(p.colour(SkinRegion::kLips)) < lum(p.colour(SkinRegion::kSkin)));
}

TEST_CASE("set dressing: a hall around the concert and walls along the corridor, never inside the crowd",
          "[stimuli]") {
  CrowdAnimation concert;
  concert.meta.scenario = "stationary";
  Box stage;
  stage.center_m = Vec3(0, 0.5, 6.0);
  stage.half_extents_m = Vec3(4, 0.5, 1.5);
  concert.environment.boxes = {stage};
  const Vec3 lo(-2, 0, -2), hi(2, 2.4, 2);
  const std::vector<DecorBox> hall = make_scene_set(concert, lo, hi);
  REQUIRE(hall.size() > 8);
  int lamps = 0, behind_stage = 0, behind_crowd = 0;
  for (const DecorBox& d : hall) {
    CHECK(!overlaps(d.box, lo, hi));
    lamps += d.emission > 0.5f;
    behind_stage += d.box.center_m.z() > stage.center_m.z() + 1.0;
    behind_crowd += d.box.center_m.z() < lo.z() - 2.0;
  }
  CHECK(lamps >= 6);
  CHECK(behind_stage >= 2);  // back wall and backdrop
  CHECK(behind_crowd >= 1);  // the hall's back wall, seen from the front (V1)

  CrowdAnimation corridor;
  corridor.meta.scenario = "corridor";
  Box left, right;
  left.center_m = Vec3(-1.55, 0.6, 10);
  right.center_m = Vec3(1.55, 0.6, 10);
  left.half_extents_m = right.half_extents_m = Vec3(0.05, 0.6, 15);
  corridor.environment.boxes = {left, right};
  const std::vector<DecorBox> walls = make_scene_set(corridor, Vec3(-1.5, 0, -5), Vec3(1.5, 2, 25));
  REQUIRE(walls.size() > 4);
  int both_sides[2] = {0, 0};
  for (const DecorBox& d : walls) {
    CHECK(std::abs(d.box.center_m.x()) > 1.5);  // outside the walkway
    ++both_sides[d.box.center_m.x() < 0 ? 0 : 1];
  }
  CHECK(both_sides[0] == both_sides[1]);
  corridor.meta.scenario = "flow_a";
  CHECK(make_scene_set(corridor, lo, hi).empty());
}

TEST_CASE("clean image: FXAA brings one sample per pixel closer to 4x MSAA, and feet darken the floor",
          "[stimuli][fast]") {
  SyntheticCrowdOptions co;
  co.characters = 6;
  co.spacing_m = 0.8;
  co.frames = 2;
  co.stage = false;
  const CrowdAnimation crowd = make_synthetic_crowd(co);
  RenderOptions clean;
  clean.width = 480;
  clean.height = 270;
  RenderOptions raw = clean;
  raw.scene.clean_image = false;
  const Camera cam = Viewpoint(ViewpointId::V2, crowd, 480, 270).at(1);
  const cv::Mat c = luma_of(render_frame(renderer(), crowd, clean, cam, 1));
  const cv::Mat r = luma_of(render_frame(renderer(), crowd, raw, cam, 1));
  const cv::Mat c_ref = luma_of(render_frame(renderer(), crowd, reference_render_options(clean), cam, 1));
  const cv::Mat r_ref = luma_of(render_frame(renderer(), crowd, reference_render_options(raw), cam, 1));
  // Edge pixels far from the 4x reference: fewer after FXAA.
  const int clean_far = cv::countNonZero(cv::abs(c - c_ref) > 20);
  const int raw_far = cv::countNonZero(cv::abs(r - r_ref) > 20);
  INFO("pixels > 20 levels from the reference: clean " << clean_far << ", raw " << raw_far);
  CHECK(clean_far < 0.8 * raw_far);
  // Contact darkening: the clean frame is darker than the raw one on a patch of floor around each character.
  CHECK(cv::countNonZero(r - c > 6) > 300);
  CHECK(cv::countNonZero(c - r > 6) < cv::countNonZero(r - c > 6) / 4);
}
