// Dressed MPFB2 bodies (body/mpfb2_outfit.hpp, body/mhclo_proxy.hpp) on the shipped assets: MakeHuman's proxy
// fitting, eyes, hair, garments and shoes following the shaped body, and relaxed hands.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>

#include "framework/body/mhclo_proxy.hpp"
#include "framework/body/mpfb2_body.hpp"
#include "framework/body/mpfb2_model.hpp"
#include "framework/body/mpfb2_outfit.hpp"
#include "framework/body/sample_mpfb2_bodies.hpp"
#include "framework/body/tuck_under_garments.hpp"
#include "framework/core/error.hpp"
#include "framework/core/mpfb2_asset_dir.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_mpfb2_outfit {

using namespace crowdlab;

namespace {

std::shared_ptr<const Mpfb2Model> model() {
  static const std::shared_ptr<const Mpfb2Model> m = Mpfb2Model::load(shipped_mpfb2_dir());
  return m;
}

std::shared_ptr<const Mpfb2Wardrobe> wardrobe() {
  static const std::shared_ptr<const Mpfb2Wardrobe> w =
      Mpfb2Wardrobe::load(default_makehuman_dir(), static_cast<int>(model()->base().vertices.size()));
  return w;
}

std::filesystem::path write(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

std::map<SurfaceKind, int> label_counts(const SkinnedMesh& mesh) {
  std::map<SurfaceKind, int> count;
  for (const std::uint8_t s : mesh.surface) ++count[static_cast<SurfaceKind>(s)];
  return count;
}

/// Calls visit(outfit, body) for every shipped outfit of both sexes, worn with the first pair of shoes on
/// the default body of its sex.
template <typename Visit>
void for_every_outfit(Visit visit) {
  const auto w = wardrobe();
  for (const bool female : {true, false}) {
    Mpfb2ShapeParams p;
    p.gender = female ? 0.0 : 1.0;
    for (const auto& o : female ? w->outfit_female : w->outfit_male) {
      Mpfb2Outfit outfit;
      outfit.outfit = o.get();
      outfit.shoes = w->shoes.front().get();
      visit(*o, make_mpfb2_body(*model(), p, &outfit));
    }
  }
}

}  // namespace

TEST_CASE(
    "mhclo: each asset vertex is the weighted sum of three base vertices plus a per-axis scaled offset") {
  const auto dir = std::filesystem::temp_directory_path() / "crowdlab_mhclo_test";
  std::filesystem::create_directories(dir);
  write(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const auto path = write(dir / "tri.mhclo",
                          "# comment\nname tri\nobj_file tri.obj\nx_scale 0 1 2.0\ny_scale 0 2 1.0\n"
                          "z_scale 0 3 4.0\nverts 0\n0 1 2 0.5 0.25 0.25 1.0 1.0 1.0\n3\n"
                          "1 2 3 1 0 0 0 0 0\ndelete_verts\n2 5 - 7\n");
  const MhcloProxy p = read_mhclo(path, 8);
  REQUIRE(p.refs.size() == 3);
  CHECK(p.deleted_base_vertices == std::vector<int>{2, 5, 6, 7});
  std::vector<Vec3> base(8, Vec3::Zero());
  base[0] = Vec3(0, 0, 0);
  base[1] = Vec3(4, 0, 0);  // x scale |4 - 0| / 2 = 2
  base[2] = Vec3(0, 3, 0);  // y scale 3
  base[3] = Vec3(0, 0, 8);  // z scale 2
  const std::vector<Vec3> fit = fit_mhclo_proxy(p, base);
  CHECK((fit[0] - Vec3(0.5 * 0 + 0.25 * 4 + 2.0, 0.25 * 3 + 3.0, 2.0)).norm() < 1e-12);
  CHECK((fit[1] - base[3]).norm() < 1e-12);  // a one-number line is that base vertex
  CHECK((fit[2] - base[1]).norm() < 1e-12);
  // Bad input names the file and line.
  const auto bad = write(dir / "bad.mhclo", "obj_file tri.obj\nverts 0\n0 1 2 0.5\n");
  CHECK_THROWS_WITH(read_mhclo(bad, 8), Catch::Contains("bad.mhclo:3"));
  const auto out_of_range = write(dir / "range.mhclo", "obj_file tri.obj\nverts 0\n0\n1\n99\n");
  CHECK_THROWS_WITH(read_mhclo(out_of_range, 8), Catch::Contains("out of range"));
  const auto count = write(dir / "count.mhclo", "obj_file tri.obj\nverts 0\n0\n1\n");
  CHECK_THROWS_WITH(read_mhclo(count, 8), Catch::Contains("has 3"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("the shipped wardrobe holds outfits and hair for both sexes, shoes and eyebrows") {
  const auto w = wardrobe();
  CHECK(w->outfit_female.size() >= 2);
  CHECK(w->outfit_male.size() >= 2);
  CHECK(w->hair_female.size() >= 2);
  CHECK(w->hair_male.size() >= 2);
  CHECK(!w->shoes.empty());
  CHECK(!w->eyebrows.empty());
}

TEST_CASE(
    "a dressed body has eyes, brows, hair, a top, a bottom and shoes over a skin that stays closed where "
    "seen") {
  const auto m = model();
  Mpfb2ShapeParams p;
  p.gender = 0.0;
  const Mpfb2Outfit outfit = sample_mpfb2_outfit(*wardrobe(), Sex::kFemale, 7);
  const Mpfb2Body bare = make_mpfb2_body(*m, p);
  const Mpfb2Body dressed = make_mpfb2_body(*m, p, &outfit);
  REQUIRE_NOTHROW(validate_skinned_mesh(dressed.mesh, "test"));
  CHECK(bare.mesh.surface.empty());  // a bare body keeps the renderer's positional clothing
  REQUIRE(dressed.mesh.surface.size() == dressed.mesh.rest_vertices_m.size());
  auto count = label_counts(dressed.mesh);
  for (SurfaceKind k : {SurfaceKind::kSkin, SurfaceKind::kLips, SurfaceKind::kEyeWhite, SurfaceKind::kIris,
                        SurfaceKind::kBrow, SurfaceKind::kHair, SurfaceKind::kUpperGarment,
                        SurfaceKind::kLowerGarment, SurfaceKind::kShoes}) {
    INFO("surface " << static_cast<int>(k));
    CHECK(count[k] > 0);
  }
  // The collision bodies are the skin's alone: the same capsules dressed or not.
  for (size_t j = 0; j < kJointCount; ++j)
    CHECK(dressed.shape.capsules[j].radius_m == Approx(bare.shape.capsules[j].radius_m));
  // Garments lie on the body: every top vertex within 8 cm of the bare skin, most within 3 cm.
  const std::vector<Vec3>& skin = bare.mesh.rest_vertices_m;
  const double lift = dressed.shape.joint_offsets_m[kPelvis].y() - bare.shape.joint_offsets_m[kPelvis].y();
  CHECK(lift >= 0.0);  // standing on the soles
  CHECK(lift < 0.05);
  int near = 0, total = 0;
  double worst = 0.0;
  for (size_t v = 0; v < dressed.mesh.surface.size(); v += 7) {
    if (dressed.mesh.surface[v] != static_cast<std::uint8_t>(SurfaceKind::kUpperGarment)) continue;
    const Vec3 q = dressed.mesh.rest_vertices_m[v] - Vec3(0, lift, 0);
    double best = HUGE_VAL;
    for (const Vec3& s : skin) best = std::min(best, (s - q).squaredNorm());
    best = std::sqrt(best);
    worst = std::max(worst, best);
    near += best < 0.03;
    ++total;
  }
  INFO("top vertices checked " << total << ", worst " << worst << " m");
  CHECK(total > 50);
  CHECK(worst < 0.08);
  CHECK(near > 0.9 * total);
  // The eyes sit in the head, in front: iris vertices ahead of the head joint and above the mouth.
  const Vec3 head = dressed.mesh.rest_joints_m[kHead];
  for (size_t v = 0; v < dressed.mesh.surface.size(); ++v)
    if (dressed.mesh.surface[v] == static_cast<std::uint8_t>(SurfaceKind::kIris)) {
      CHECK(dressed.mesh.rest_vertices_m[v].z() > head.z() + 0.05);
      CHECK(std::abs(dressed.mesh.rest_vertices_m[v].y() - head.y()) < 0.12);
    }
}

TEST_CASE("outfits are drawn per body from their own stream: the shapes are the same dressed or not") {
  const auto m = model();
  const auto plain = sample_mpfb2_bodies(*m, 6, 42);
  const auto dressed =
      sample_mpfb2_bodies(*m, 6, 42, 0.5, kWorldFemaleHeight, kWorldMaleHeight, wardrobe().get());
  std::set<size_t> sizes;
  for (size_t i = 0; i < plain.size(); ++i) {
    CHECK(plain[i].params.height == dressed[i].params.height);
    CHECK(plain[i].body.height_m == dressed[i].body.height_m);
    CHECK(!dressed[i].body.mesh.surface.empty());
    sizes.insert(dressed[i].body.mesh.rest_vertices_m.size());
  }
  CHECK(sizes.size() > 1);  // not everyone wears the same
  const auto again =
      sample_mpfb2_bodies(*m, 6, 42, 0.5, kWorldFemaleHeight, kWorldMaleHeight, wardrobe().get());
  for (size_t i = 0; i < again.size(); ++i)
    CHECK(again[i].body.mesh.rest_vertices_m == dressed[i].body.mesh.rest_vertices_m);
}

TEST_CASE("hands rest slightly flexed: the fingertips hang below the knuckles in the T-pose") {
  const auto m = model();
  const Mpfb2Body b = make_mpfb2_body(*m, Mpfb2ShapeParams{});
  for (const int side : {0, 1}) {
    const int hand = side == 0 ? kLeftHand : kRightHand;
    const Vec3 knuckle = b.mesh.rest_joints_m[static_cast<size_t>(hand)];
    const double sign = side == 0 ? 1.0 : -1.0;
    double tip_y = 0.0;
    int n = 0;
    for (size_t v = 0; v < b.mesh.rest_vertices_m.size(); ++v) {
      const Vec3& p = b.mesh.rest_vertices_m[v];
      // The outer finger segments: 5-9 cm beyond the knuckles along the arm, within the hand's width.
      const double along = sign * (p.x() - knuckle.x());
      if (along > 0.05 && along < 0.09 && std::abs(p.z() - knuckle.z()) < 0.06 &&
          std::abs(p.y() - knuckle.y()) < 0.08) {
        tip_y += p.y();
        ++n;
      }
    }
    REQUIRE(n > 20);
    tip_y /= n;
    INFO("side " << side << ": finger ends " << (knuckle.y() - tip_y) * 100 << " cm below the knuckles");
    CHECK(knuckle.y() - tip_y > 0.012);
  }
}

TEST_CASE("skin, trousers and shoes stay behind the garments that cover them, for every outfit") {
  // Issue 28: thigh skin through shorts, a waistband through a shirt's hem, a shoe through a trouser leg,
  // where the garment lay a few millimetres over what it covers (less than the renderer's levels of detail
  // deviate).
  struct Layer {
    const char* name;
    SurfaceKind inner;
    std::vector<SurfaceKind> outer;
    double reach_m = kTuckReachM, shallow_m = 0.002;
  };
  const std::vector<Layer> layers = {
      {"skin",
       SurfaceKind::kSkin,
       {SurfaceKind::kUpperGarment, SurfaceKind::kLowerGarment, SurfaceKind::kShoes}},
      {"trousers", SurfaceKind::kLowerGarment, {SurfaceKind::kUpperGarment}},
      {"shoes", SurfaceKind::kShoes, {SurfaceKind::kLowerGarment}},
      // A thigh swings inside a skirt: it stays 2.5 cm behind.
      {"skin under a lower garment", SurfaceKind::kSkin, {SurfaceKind::kLowerGarment}, kSkirtReachM, 0.025}};
  for_every_outfit([&](const auto& o, const Mpfb2Body& b) {
    for (const Layer& layer : layers) {
      std::vector<Vec3> normal;
      int covered = 0, outside = 0, shallow = 0;
      for (const double d : cover_depths(b.mesh, layer.inner, layer.outer, normal, layer.reach_m)) {
        if (std::isnan(d)) continue;
        ++covered;
        outside += d < 0.0;
        shallow += d < layer.shallow_m;
      }
      INFO(o.name << ", " << layer.name << ": " << covered << " covered vertices, " << outside
                  << " through the garment, " << shallow << " within " << layer.shallow_m * 1000 << " mm");
      if (layer.outer.size() == 3) CHECK(covered > 50);  // the rule finds the skin under the hems
      CHECK(outside == 0);
      CHECK(shallow <= covered / 100);
    }
  });
}

namespace {

/// The body vertex nearest to a rig placement on the unshaped base mesh (decimetres).
int vertex_at(const Mpfb2Model& m, const JointPlacement& p) {
  Vec3 c = Vec3::Zero();
  for (int v : p.vertices) c += m.base().vertices[static_cast<size_t>(v)];
  c = p.vertices.empty() ? Vec3(10.0 * blender_to_y_up(p.default_position_blender))
                         : Vec3(c / static_cast<double>(p.vertices.size()));
  int best = m.body_vertices().front();
  for (int v : m.body_vertices())
    if ((m.base().vertices[static_cast<size_t>(v)] - c).norm() <
        (m.base().vertices[static_cast<size_t>(best)] - c).norm())
      best = v;
  return best;
}

}  // namespace

TEST_CASE("the thumb rests flexed toward the palm, its tip near the index finger's knuckle") {
  // Issue 28: MakeHuman's base mesh holds its thumb nearly straight beside the palm (bent 27 degrees
  // between its first segment and its outer two, tip 7 cm from the index knuckle); a resting thumb is
  // flexed at each joint, its tip near the side of the index finger.
  const auto m = model();
  std::vector<int> local(m->base().vertices.size(), -1);
  for (size_t i = 0; i < m->body_vertices().size(); ++i)
    local[static_cast<size_t>(m->body_vertices()[i])] = static_cast<int>(i);
  const Mpfb2Body b = make_mpfb2_body(*m, Mpfb2ShapeParams{});
  for (const char* side : {"Left", "Right"}) {
    const auto at = [&](const std::string& bone, bool tail) {
      const RigBone& r = m->bones().at("mixamorig:" + std::string(side) + bone);
      const int v = local[static_cast<size_t>(vertex_at(*m, tail ? r.tail : r.head))];
      REQUIRE(v >= 0);
      return b.mesh.rest_vertices_m[static_cast<size_t>(v)];
    };
    const Vec3 first = at("HandThumb2", false) - at("HandThumb1", false);
    const Vec3 outer = at("HandThumb3", true) - at("HandThumb2", false);
    const double bend_deg = std::acos(first.normalized().dot(outer.normalized())) * 180.0 / M_PI;
    const double tip_cm = (at("HandThumb3", true) - at("HandIndex1", false)).norm() * 100.0;
    INFO(side << " thumb bent " << bend_deg << " degrees, tip " << tip_cm << " cm from the index knuckle");
    CHECK(bend_deg > 30.0);
    CHECK(bend_deg < 50.0);
    CHECK(tip_cm < 5.5);
    CHECK(tip_cm > 2.0);  // not through the palm
  }
}

TEST_CASE("the fingers rest together and bend most at the knuckles, as a relaxed hand does") {
  // Issue 28: raised hands showed fanned fingers hooked at their middle joints (claws). A relaxed hand's
  // fingers lie close together and flex most at the knuckle (MCP), less at the middle (PIP) joint.
  const auto m = model();
  std::vector<int> local(m->base().vertices.size(), -1);
  for (size_t i = 0; i < m->body_vertices().size(); ++i)
    local[static_cast<size_t>(m->body_vertices()[i])] = static_cast<int>(i);
  const Mpfb2Body b = make_mpfb2_body(*m, Mpfb2ShapeParams{});
  const auto angle_deg = [](const Vec3& a, const Vec3& c) {
    return std::acos(std::clamp(a.normalized().dot(c.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
  };
  for (const char* side : {"Left", "Right"}) {
    const auto at = [&](const std::string& bone) {
      const RigBone& r = m->bones().at("mixamorig:" + std::string(side) + bone);
      const int v = local[static_cast<size_t>(vertex_at(*m, r.head))];
      REQUIRE(v >= 0);
      return b.mesh.rest_vertices_m[static_cast<size_t>(v)];
    };
    const double fan = angle_deg(at("HandIndex2") - at("HandIndex1"), at("HandPinky2") - at("HandPinky1"));
    const Vec3 palm = at("HandMiddle1") - at("Hand");
    const Vec3 proximal = at("HandMiddle2") - at("HandMiddle1"),
               middle = at("HandMiddle3") - at("HandMiddle2");
    const double mcp = angle_deg(palm, proximal), pip = angle_deg(proximal, middle);
    INFO(side << ": index to little finger " << fan << " degrees apart; middle finger MCP " << mcp << ", PIP "
              << pip << " degrees");
    CHECK(fan < 25.0);  // MakeHuman's spread closed by 60 %: 27.4
    CHECK(mcp > pip);
    CHECK(mcp > 15.0);
  }
}

TEST_CASE("relaxed fingers lie side by side: their tips no farther apart than their knuckles") {
  // Issue 28 (session 11's close-ups): a raised hand, seen from the palm or the back, showed its fingers
  // apart; the rest pose closed only 75 % of MakeHuman's spread. Each finger segment is the centroid of
  // the skin its rig bone dominates (weight > 0.5); distances along the knuckle line (index to little
  // finger knuckle), which the fingers' flexion about that line does not change.
  const auto m = model();
  std::vector<int> local(m->base().vertices.size(), -1);
  for (size_t i = 0; i < m->body_vertices().size(); ++i)
    local[static_cast<size_t>(m->body_vertices()[i])] = static_cast<int>(i);
  for (const double gender : {0.0, 1.0}) {
    Mpfb2ShapeParams params;
    params.gender = gender;
    const Mpfb2Body b = make_mpfb2_body(*m, params);
    for (const char* side : {"Left", "Right"}) {
      const auto segment = [&](const std::string& bone) {
        Vec3 sum = Vec3::Zero();
        int n = 0;
        for (const auto& [v, w] : m->weights().at("mixamorig:" + std::string(side) + bone)) {
          const int l = local[static_cast<size_t>(v)];
          if (w <= 0.5 || l < 0) continue;
          sum += b.mesh.rest_vertices_m[static_cast<size_t>(l)];
          ++n;
        }
        REQUIRE(n > 5);
        return Vec3(sum / n);
      };
      const Vec3 axis = (segment("HandPinky1") - segment("HandIndex1")).normalized();
      const std::array<const char*, 4> fingers = {"Index", "Middle", "Ring", "Pinky"};
      for (size_t f = 0; f + 1 < fingers.size(); ++f) {
        const std::string a = std::string("Hand") + fingers[f], c = std::string("Hand") + fingers[f + 1];
        const double knuckles_cm = (segment(c + "1") - segment(a + "1")).dot(axis) * 100.0;
        const double tips_cm = (segment(c + "3") - segment(a + "3")).dot(axis) * 100.0;
        INFO(side << " hand, gender " << gender << ", " << fingers[f] << " and " << fingers[f + 1]
                  << ": proximal segments " << knuckles_cm << " cm apart, distal " << tips_cm << " cm");
        CHECK(tips_cm <= knuckles_cm);
        CHECK(tips_cm > 0.6 * knuckles_cm);  // not crossed or pressed into each other
      }
    }
  }
}

TEST_CASE("skin under a garment's hem lies a few millimetres behind it, for every outfit") {
  // Issue 28 (session 11's close-ups): necklines showed notches of skin where the body bends. The skin
  // straight under a hem was never tucked (its closest garment point is on the rim), so it lay within a
  // millimetre or two of the garment and came through it when posed or simplified.
  for_every_outfit([&](const auto& o, const Mpfb2Body& b) {
    std::vector<Vec3> normal;
    int under = 0, shallow = 0;
    double shallowest_mm = HUGE_VAL;
    for (const double d :
         cover_depths(b.mesh, SurfaceKind::kSkin,
                      {SurfaceKind::kUpperGarment, SurfaceKind::kLowerGarment, SurfaceKind::kShoes}, normal,
                      kTuckReachM, true)) {
      if (std::isnan(d)) continue;
      ++under;
      shallow += d < kHemMarginM - 0.0005;
      shallowest_mm = std::min(shallowest_mm, d * 1000.0);
    }
    INFO(o.name << ": " << under << " skin vertices under a hem, " << shallow << " less than "
                << (kHemMarginM - 0.0005) * 1000 << " mm behind it (shallowest " << shallowest_mm << " mm)");
    CHECK(shallow == 0);
  });
}

}  // namespace test_mpfb2_outfit
