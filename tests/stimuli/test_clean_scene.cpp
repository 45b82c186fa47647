// Issue 28 items 2-4 on the renderer side: dressed bodies (surface labels -> regions, two-sided sheets), the
// set dressing per scenario, and the clean image (FXAA, soft shadows, contact darkening).
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <utility>
#include <vector>

#include "framework/body/sample_mpfb2_bodies.hpp"
#include "framework/core/mpfb2_asset_dir.hpp"
#include "stimuli/decode_luma.hpp"
#include "stimuli/render_clip.hpp"
#include "stimuli/render_quality.hpp"
#include "stimuli/scene_set.hpp"
#include "stimuli/simplify_character_mesh.hpp"
#include "stimuli/skinned_body_mesh.hpp"
#include "stimuli/synthetic_crowd.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_clean_scene {

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

/// Distance (m) from p to triangle abc (closest point by regions, Ericson 2005, "Real-Time Collision
/// Detection", 5.1.5).
double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

/// `count` dressed MPFB2 bodies sampled from `seed` (half women, world heights), from the shipped assets.
std::vector<Mpfb2Sample> dressed_bodies(int count, std::uint64_t seed) {
  const auto model = Mpfb2Model::load(shipped_mpfb2_dir());
  const auto wardrobe =
      Mpfb2Wardrobe::load(default_makehuman_dir(), static_cast<int>(model->base().vertices.size()));
  return sample_mpfb2_bodies(*model, count, seed, 0.5, kWorldFemaleHeight, kWorldMaleHeight, wardrobe.get());
}

}  // namespace

TEST_CASE("a dressed MPFB2 body renders eyes, lips, brows, hair, garments and shoes as two-sided regions",
          "[stimuli]") {
  const auto bodies = dressed_bodies(2, 11);
  for (const Mpfb2Sample& s : bodies) {
    const MannequinMesh r = skinned_body_mesh(s.body.mesh);
    CHECK(r.two_sided);
    int lips = 0;
    for (const std::uint8_t k : s.body.mesh.surface)
      lips += k == static_cast<std::uint8_t>(SurfaceKind::kLips);
    INFO("lips vertices " << lips);
    std::set<int> regions;
    int lip_coloured = 0;  // the lips are skin with a lip weight (drawn in the lip colour above 0.5)
    for (const MannequinVertex& v : r.vertices) {
      regions.insert(v.region);
      lip_coloured += v.lips > 127 && v.region == static_cast<std::uint8_t>(SkinRegion::kSkin);
    }
    CHECK(lip_coloured > lips / 3);
    for (SkinRegion k : {SkinRegion::kSkin, SkinRegion::kEyeWhite, SkinRegion::kIris, SkinRegion::kBrow,
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

namespace {

/// A 2D outline as segments (x, y of the rest pose: the face seen from the front).
using Segments = std::vector<std::array<Eigen::Vector2d, 2>>;

/// Length of the segments over the perimeter of their end points' convex hull: 1 for a convex outline,
/// about 1.3-1.4 for a staircase along a grid's edges.
double length_over_hull(const Segments& s) {
  std::vector<cv::Point2f> points;
  double length = 0.0;
  for (const auto& seg : s) {
    length += (seg[1] - seg[0]).norm();
    for (const auto& p : seg) points.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
  }
  std::vector<cv::Point2f> hull;
  cv::convexHull(points, hull);
  return length / cv::arcLength(hull, true);
}

Eigen::Vector2d front(const Vec3& p) {
  return {p.x(), p.y()};
}

/// The outline of the lips as session 11 drew it: the mesh edges between triangles painted lips (two of
/// their three vertices labelled lips, else the first vertex's label) and the others.
Segments labelled_lip_outline(const SkinnedMesh& mesh) {
  const auto lips = [&](int v) {
    return mesh.surface[static_cast<size_t>(v)] == std::uint8_t(SurfaceKind::kLips);
  };
  std::map<std::pair<int, int>, int> painted_sides;  // edge -> painted lips (+1) / other (+2) triangles
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const bool painted = lips(t[1]) == lips(t[2]) ? lips(t[1]) : lips(t[0]);
    for (int k = 0; k < 3; ++k) {
      const auto e = std::minmax(t[k], t[(k + 1) % 3]);
      painted_sides[{e.first, e.second}] |= painted ? 1 : 2;
    }
  }
  Segments out;
  for (const auto& [e, sides] : painted_sides)
    if (sides == 3)
      out.push_back({front(mesh.rest_vertices_m[static_cast<size_t>(e.first)]),
                     front(mesh.rest_vertices_m[static_cast<size_t>(e.second)])});
  return out;
}

/// The outline the shader draws: the 0.5 level of the lip weight, linear across each skin triangle.
Segments drawn_lip_outline(const MannequinMesh& mesh) {
  Segments out;
  for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    std::vector<Eigen::Vector2d> crossing;
    for (int k = 0; k < 3; ++k) {
      const MannequinVertex& a = mesh.vertices[mesh.indices[i + static_cast<size_t>(k)]];
      const MannequinVertex& b = mesh.vertices[mesh.indices[i + static_cast<size_t>((k + 1) % 3)]];
      if (a.region != std::uint8_t(SkinRegion::kSkin) || b.region != std::uint8_t(SkinRegion::kSkin))
        continue;
      const double wa = a.lips / 255.0 - 0.5, wb = b.lips / 255.0 - 0.5;
      if ((wa < 0.0) == (wb < 0.0)) continue;
      const double s = wa / (wa - wb);
      crossing.push_back((1.0 - s) * Eigen::Vector2d(a.position[0], a.position[1]) +
                         s * Eigen::Vector2d(b.position[0], b.position[1]));
    }
    if (crossing.size() == 2) out.push_back({crossing[0], crossing[1]});
  }
  return out;
}

}  // namespace

TEST_CASE("the lips' outline is a smooth curve, not a sawtooth along the mesh's edges", "[stimuli]") {
  // Issue 28 (session 11's close-ups: "lips with a sawtooth outline"): the lips were the triangles with
  // lips-labelled vertices, so their outline ran along mesh edges in steps. Measured as the outline's
  // length over its convex hull's perimeter (seen from the front; the lips' outline is nearly convex).
  const auto bodies = dressed_bodies(4, 23);
  for (const Mpfb2Sample& s : bodies) {
    const Segments drawn = drawn_lip_outline(skinned_body_mesh(s.body.mesh));
    const Segments labelled = labelled_lip_outline(s.body.mesh);
    REQUIRE(drawn.size() >= 12);
    const double smooth = length_over_hull(drawn), stepped = length_over_hull(labelled);
    INFO("outline length over hull perimeter: drawn " << smooth << " (" << drawn.size()
                                                      << " segments), edges of "
                                                      << "the labelled triangles " << stepped);
    // Measured (session 12, 4 bodies): drawn 1.01-1.54, the labelled triangles' edges 1.55-2.71 (the lips
    // are one or two loops, upper and lower lip, under one hull, so a smooth outline is not exactly 1).
    CHECK(smooth < 1.6);
    CHECK(smooth < 0.7 * stepped);
  }
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

TEST_CASE("levels of detail hold the face to half their error bound", "[stimuli][lod]") {
  // Issue 28: the simplifier's error is one number for the whole body; the face, a small feature, went
  // further from the full mesh than the level's error said (flattened noses, lips beside the mouth in the
  // close-ups drawn at lod_pixels 6). The face and hands now weigh kDetailGain times more in its metric,
  // so a level chosen for its error keeps the face well inside it.
  const auto bodies = dressed_bodies(1, 11);
  const MannequinMesh full = skinned_body_mesh(bodies.front().body.mesh);
  const std::vector<CharacterLod> levels = simplify_character_mesh(full, 5, 2.5);
  REQUIRE(levels.size() >= 4);
  const auto pos = [](const MannequinVertex& v) { return Vec3(v.position[0], v.position[1], v.position[2]); };
  // The face: skin of the head, facing forward.
  const auto is_face = [](const MannequinVertex& v) {
    return v.bones[0] == kHead && v.region == static_cast<std::uint8_t>(SkinRegion::kSkin) &&
           v.normal[2] > 0.5f;
  };
  // The largest distance of the full mesh's face vertices to the level's surface (m).
  const auto face_deviation = [&](const MannequinMesh& m) {
    double worst = 0.0;
    int count = 0;
    for (const MannequinVertex& v : full.vertices) {
      if (!is_face(v)) continue;
      const Vec3 p = pos(v);
      double best = HUGE_VAL;
      for (size_t t = 0; t < m.indices.size(); t += 3) {
        const Vec3 a = pos(m.vertices[m.indices[t]]), b = pos(m.vertices[m.indices[t + 1]]),
                   c = pos(m.vertices[m.indices[t + 2]]);
        if ((a - p).squaredNorm() > 0.09) continue;  // 30 cm: far triangles cannot be the nearest
        best = std::min(best, point_triangle_distance(p, a, b, c));
      }
      worst = std::max(worst, best);
      ++count;
    }
    REQUIRE(count > 100);
    return worst;
  };
  for (size_t l = 1; l < levels.size(); ++l) {
    const double d = face_deviation(levels[l].mesh);
    INFO("level " << l << " (" << levels[l].mesh.indices.size() / 3 << " triangles): face up to "
                  << 1000.0 * d << " mm from the full mesh; level error " << 1000.0 * levels[l].error_m
                  << " mm");
    CHECK(d <= 0.5 * levels[l].error_m);
  }
}

}  // namespace test_clean_scene
