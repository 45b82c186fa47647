// The fast stimulus path (issue 17): levels of detail for dense skinned meshes, one sample per pixel, and
// the quality measure that holds the fast path to a reference.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <opencv2/quality/qualityssim.hpp>
#include <set>

#include "framework/core/error.hpp"
#include "stimuli/character_mesh.hpp"
#include "stimuli/decode_luma.hpp"
#include "stimuli/level_of_detail.hpp"
#include "stimuli/render_quality.hpp"
#include "stimuli/simplify_character_mesh.hpp"
#include "stimuli/synthetic_crowd.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_fast_path {

using namespace crowdlab;
using namespace crowdlab::stimuli;

namespace {

CrowdAnimation crowd_of(int characters, int frames) {
  SyntheticCrowdOptions co;
  co.characters = characters;
  co.spacing_m = 0.7;
  co.frames = frames;
  co.stage = false;
  return make_synthetic_crowd(co);
}

RenderOptions options_at(int width, int height) {
  RenderOptions o;
  o.width = width;
  o.height = height;
  return o;
}

Renderer& renderer() {
  static Renderer r([] {
    MannequinOptions o;
    o.voxel_m = 0.035;
    return o;
  }());
  return r;
}

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

}  // namespace

TEST_CASE(
    "simplified levels keep a subset of the full mesh's vertices, with fewer triangles and growing error",
    "[stimuli][lod]") {
  const CrowdAnimation crowd = crowd_of(1, 1);
  const MannequinMesh full = build_mannequin_mesh(crowd.characters[0].shape, {});
  const std::vector<CharacterLod> levels = simplify_character_mesh(full, 5, 2.5);
  REQUIRE(levels.size() >= 3);
  CHECK(levels[0].error_m == 0.0);
  CHECK(levels[0].mesh.indices == full.indices);
  auto bytes = [](const MannequinVertex& v) {
    return std::string(reinterpret_cast<const char*>(&v), sizeof v);
  };
  std::set<std::string> originals;
  for (const MannequinVertex& v : full.vertices) originals.insert(bytes(v));
  for (size_t l = 1; l < levels.size(); ++l) {
    const MannequinMesh& m = levels[l].mesh;
    CHECK(m.indices.size() < levels[l - 1].mesh.indices.size());
    CHECK(m.indices.size() % 3 == 0);
    CHECK(levels[l].error_m >= levels[l - 1].error_m);
    CHECK(levels[l].error_m < 0.05);  // metres: a simplified body stays within 5 cm of the full one
    for (std::uint32_t i : m.indices) REQUIRE(i < m.vertices.size());
    // Weights, regions and normals are the full mesh's own: every vertex is one of its vertices.
    size_t foreign = 0;
    for (const MannequinVertex& v : m.vertices) foreign += originals.count(bytes(v)) == 0;
    CHECK(foreign == 0);
  }
  CHECK(simplify_character_mesh(full, 5, 2.5)[2].mesh.indices == levels[2].mesh.indices);  // deterministic
}

TEST_CASE("select_lod picks the coarsest level within the error bound", "[stimuli][lod]") {
  const std::vector<LodLevel> levels = {
      {1, 0.0, 300, {}}, {2, 0.002, 120, {}}, {3, 0.005, 48, {}}, {4, 0.01, 18, {}}};
  CHECK(select_lod(levels, 0.0).key == 1);
  CHECK(select_lod(levels, 0.003).key == 2);
  CHECK(select_lod(levels, 0.006).key == 3);
  CHECK(select_lod(levels, 1.0).key == 4);
  CHECK_THROWS(select_lod({}, 1.0));
}

TEST_CASE("one sample per pixel: characters shade the ground and the frame stays near the 4x reference",
          "[stimuli][fast]") {
  const CrowdAnimation crowd = crowd_of(6, 2);
  RenderOptions fast = options_at(480, 270);
  fast.scene.msaa_samples = 1;
  const RenderOptions reference = reference_render_options(fast);
  for (const char* name : {"V2", "V4"}) {
    const Camera cam = Viewpoint(*find_viewpoint(name), crowd, 480, 270).at(1);
    const cv::Mat la = luma_of(render_frame(renderer(), crowd, fast, cam, 1));
    const cv::Mat lb = luma_of(render_frame(renderer(), crowd, reference, cam, 1));
    INFO(name);
    CHECK(cv::quality::QualitySSIM::compute(la, lb, cv::noArray())[0] > 0.97);
    // Only edges differ: far from every character (the top corners) the two are the same.
    CHECK(cv::norm(la(cv::Rect(0, 0, 40, 30)), lb(cv::Rect(0, 0, 40, 30)), cv::NORM_INF) <= 1.0);
    // The characters cast shadows on the ground: it is darker than the bare ground somewhere.
    RenderOptions empty = fast;
    empty.scene.characters = false;
    const cv::Mat bare = luma_of(render_frame(renderer(), crowd, empty, cam, 1));
    CHECK(cv::countNonZero(bare - la > 8) > 50);
  }
}

TEST_CASE("render quality: the measure sees what encoding costs", "[stimuli][fast]") {
  const CrowdAnimation crowd = crowd_of(4, 6);
  const auto dir = test::scratch_dir("render_quality");
  RenderOptions lossless = options_at(320, 180);
  lossless.crf = 0;
  lossless.x264_preset = "ultrafast";
  const RenderOptions reference = reference_render_options(lossless);
  // The reference path itself, encoded losslessly: only yuv420p rounding separates the two.
  RenderOptions same = reference;
  const QualityReport exact =
      measure_render_quality(renderer(), crowd, same, reference, {ViewpointId::V3}, 6, {0, 5}, dir.string());
  REQUIRE(exact.samples.size() == 2);
  CHECK(exact.ssim_min > 0.995);
  CHECK(exact.psnr_min_db > 40.0);
  // A starved encoder is caught.
  RenderOptions starved = reference;
  starved.crf = 51;
  const QualityReport poor = measure_render_quality(renderer(), crowd, starved, reference, {ViewpointId::V3},
                                                    6, {0, 5}, dir.string());
  CHECK(poor.ssim_min < exact.ssim_min - 0.01);
  CHECK_THROWS_AS(
      measure_render_quality(renderer(), crowd, same, reference, {ViewpointId::V3}, 6, {6}, dir.string()),
      InputError);
}

}  // namespace test_fast_path
