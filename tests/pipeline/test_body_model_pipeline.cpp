// `crowdlab run` with the MPFB2 body model (animation.body_model: mpfb2, the shipped assets by default):
// the crowd files carry the shaped, skinned meshes with their real sex and measured stature, the
// skeletons and capsules come from those meshes (correction and metrics run on them), and the spec can
// name other assets by path or through CROWDLAB_MPFB2.
#include <bit>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>

#include "framework/body/fit_crowd_proxies.hpp"
#include "framework/body/sample_mpfb2_bodies.hpp"
#include "framework/core/appearance.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/mpfb2_asset_dir.hpp"
#include "framework/core/seed.hpp"
#include "framework/io/read_crowd_glb.hpp"
#include "framework/metrics/proxy_coverage.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_body_model_pipeline {

using namespace crowdlab;
using namespace crowdlab::test;
namespace fs = std::filesystem;

namespace {
std::string spec_text(const std::string& body_model, const std::string& animation_extra = "") {
  return "crowdlab: 1\nname: mpfb2\nseed: 3\nscenario:\n  type: stationary\n  area: {width_m: 1.2, depth_m: "
         "1.2}\n"
         "crowd:\n  agent_radius_m: 0.18\nanimation:\n" +
         animation_extra + "  body_model: " + body_model +
         "\nfactors:\n  density: [4.0]\n  viewpoint: [V1]\n  method: [baseline, ours]\nrepetitions: 1\n"
         "duration_s: 0.6\nfps: 10\nresolution: [160, 96]\nprotocol:\n  type: likert\n  scale: {points: 6, "
         "labels: "
         "[\"no\", \"yes\"]}\n  questions:\n    - {id: Q1, text: \"natural\"}\noutputs:\n  video: false\n"
         "  contact_sheet: false\n";
}
}  // namespace

TEST_CASE("run with the default MPFB2 assets: crowd files carry the shaped meshes, real sex and height") {
  ::unsetenv("CROWDLAB_MPFB2");
  const fs::path out = scratch_dir("pipeline_mpfb2");
  const fs::path spec = out / "spec.yaml";
  std::ofstream(spec) << spec_text("mpfb2");
  const CliResult r = run_cli({"-q", "run", spec.string(), "--out", (out / "run").string()});
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  const auto model = Mpfb2Model::load(shipped_mpfb2_dir());
  int crowds = 0;
  for (const auto& dir : fs::directory_iterator(out / "run" / "crowds")) {
    ++crowds;
    for (const char* file : {"baseline.glb", "ours.glb"}) {
      INFO(file);
      const CrowdAnimation crowd = read_crowd_glb((dir.path() / file).string());
      REQUIRE(crowd.characters.size() >= 3);
      int women = 0;
      for (const CharacterAnimation& ch : crowd.characters) {
        REQUIRE(ch.mesh);
        CHECK(ch.mesh->rest_vertices_m.size() > 10000);
        women += ch.shape.params.sex == Sex::kFemale;
        // The stature the mesh stands at is the shape's height (T-pose: up to ~1 % taller), from the soles
        // (the body wears shoes: a sole of 1-3 cm) to the crown of the skin (hair is higher).
        REQUIRE(ch.mesh->surface.size() == ch.mesh->rest_vertices_m.size());  // dressed by default
        double lo = 1e9, hi = -1e9, top = -1e9;
        for (size_t v = 0; v < ch.mesh->rest_vertices_m.size(); ++v) {
          const double y = ch.mesh->rest_vertices_m[v].y();
          lo = std::min(lo, y);
          top = std::max(top, y);
          if (ch.mesh->surface[v] == static_cast<std::uint8_t>(SurfaceKind::kSkin)) hi = std::max(hi, y);
        }
        CHECK(hi - lo == Approx(ch.shape.params.height_m + 0.02).margin(0.03));
        CHECK(ch.shape.params.height_m > 1.35);
        CHECK(ch.shape.params.height_m < 2.1);
        // Capsules were fitted to this mesh: the head capsule's top reaches the skin's crown, and (a concert
        // fits them to the drawn surface, hair within 20 mm) not far above the top of the hair (a round cap
        // wide enough for the hair at the sides rises up to about 4 cm above it).
        const auto rest = joint_positions(ch.shape, Pose::rest(ch.shape));
        const Capsule& head = ch.shape.capsules[kHead];
        const double crown = rest[kHead].y() + std::max(head.a.y(), head.b.y()) + head.radius_m;
        CHECK(crown > hi - 0.03);
        CHECK(crown < top + 0.06);
      }
      const int n = static_cast<int>(crowd.characters.size());
      CHECK(std::abs(women - n / 2) <= 1);  // half women (female_fraction 0.5)
      // The recorded sex and height are those of the body the mesh was built from: sampling again with
      // the condition's seed gives the same bodies, stature measured on their shaped meshes.
      const auto wardrobe =
          Mpfb2Wardrobe::load(default_makehuman_dir(), static_cast<int>(model->base().vertices.size()));
      const std::vector<Mpfb2Sample> again =
          sample_mpfb2_bodies(*model, n, derive_seed(crowd.meta.seed, "bodies"), 0.5, kWorldFemaleHeight,
                              kWorldMaleHeight, wardrobe.get());
      for (int i = 0; i < n; ++i) {
        const CharacterAnimation& ch = crowd.characters[static_cast<size_t>(i)];
        const Mpfb2Sample& s = again[static_cast<size_t>(i)];
        CHECK(ch.shape.params.sex == s.body.shape.params.sex);
        CHECK(ch.shape.params.height_m == Approx(measure_mpfb2_height(*model, s.params)).margin(1e-9));
        CHECK(skin_tone_of(ch.palette) == s.skin_tone);
        REQUIRE(ch.mesh->rest_vertices_m.size() == s.body.mesh.rest_vertices_m.size());
        for (size_t v = 0; v < ch.mesh->rest_vertices_m.size(); v += 101)
          CHECK((ch.mesh->rest_vertices_m[v] - s.body.mesh.rest_vertices_m[v]).norm() < 1e-5);
      }
    }
    CHECK(fs::exists(dir.path() / "ours.metrics.json"));
  }
  CHECK(crowds == 1);
  // (Rendering the MPFB2 meshes is tested in tests/stimuli; no video here keeps this test short.)
}

TEST_CASE("a concert of MPFB2 bodies is corrected with capsules fitted to its rendered meshes, unless told") {
  // animation.collision_proxies: auto fits the capsules of a stationary MPFB2 crowd to the rendered mesh
  // (issue 27): its crowd files' capsules hold the drawn surface (within 5 mm, hair 20 mm, soles free),
  // where the volume-fitted capsules leave most of it outside. `volume` keeps the body's own capsules.
  ::unsetenv("CROWDLAB_MPFB2");
  const fs::path out = scratch_dir("pipeline_mpfb2_proxies");
  auto coverage = [&](const std::string& extra, const std::string& name) {
    const fs::path spec = out / (name + ".yaml");
    std::ofstream(spec) << spec_text("mpfb2", extra);
    const CliResult r = run_cli({"-q", "run", spec.string(), "--out", (out / name).string()});
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    std::vector<double> within;
    for (const auto& dir : fs::directory_iterator(out / name / "crowds"))
      for (const char* file : {"baseline.glb", "ours.glb"})
        within.push_back(measure_proxy_coverage(read_crowd_glb((dir.path() / file).string())).within_share);
    REQUIRE(within.size() == 2);
    CHECK(within[0] == Approx(within[1]).margin(0.02));  // one set of capsules for both methods
    return within[0];
  };
  const double fitted = coverage("", "auto");
  const double volume = coverage("  collision_proxies: volume\n", "volume");
  CHECK(fitted > 0.97);  // every surface within 5 mm but the hair (20 mm) and the soles (free)
  CHECK(volume < 0.6);   // the volume-fitted capsules: about 40 % within 5 mm
  CHECK(coverage("  collision_proxies: fitted\n", "fitted") == Approx(fitted).epsilon(1e-12));
  // fitted_upper (session 26): the chest, neck, head, collars and arms fitted, the pelvis, lower spine and
  // legs as `volume` has them.
  const double upper = coverage("  collision_proxies: fitted_upper\n", "fitted_upper");
  CHECK(upper > volume + 0.2);
  CHECK(upper < fitted);
  auto first_crowd = [&](const std::string& name) {
    for (const auto& dir : fs::directory_iterator(out / name / "crowds"))
      return read_crowd_glb((dir.path() / "baseline.glb").string());
    FAIL("no crowd in " << name);
    return CrowdAnimation{};
  };
  // The upper body is spine3 and the 12 bones it carries; the pelvis, spine1-2 and legs are not in it.
  CHECK(std::popcount(kUpperBodyProxies) == 13);
  for (int j : {kPelvis, kSpine1, kSpine2, kLeftHip, kRightKnee, kLeftAnkle, kRightFoot})
    CHECK((kUpperBodyProxies >> j & 1u) == 0);
  const CrowdAnimation v = first_crowd("volume"), u = first_crowd("fitted_upper");
  REQUIRE(v.characters.size() == u.characters.size());
  for (size_t c = 0; c < v.characters.size(); ++c)
    for (int j = 0; j < kJointCount; ++j) {
      const Capsule& a = v.characters[c].shape.capsules[static_cast<size_t>(j)];
      const Capsule& b = u.characters[c].shape.capsules[static_cast<size_t>(j)];
      const bool same = a.radius_m == b.radius_m && a.a == b.a && a.b == b.b;
      const bool upper_bone = (kUpperBodyProxies >> j & 1u) != 0;
      INFO("character " << c << ", joint " << j);
      if (!upper_bone) CHECK(same);
      if (j == kLeftShoulder || j == kHead) CHECK_FALSE(same);
    }
}

TEST_CASE("mpfb2 without a path takes CROWDLAB_MPFB2, else the shipped assets, a bad folder is named") {
  const fs::path out = scratch_dir("pipeline_mpfb2_env");
  const fs::path spec = out / "spec.yaml";
  std::ofstream(spec) << spec_text("mpfb2");
  ::unsetenv("CROWDLAB_MPFB2");
  CliResult r = run_cli({"validate", spec.string()});
  INFO(r.out << r.err);
  CHECK(r.exit_code == 0);  // the shipped assets
  ::setenv("CROWDLAB_MPFB2", (out / "missing").c_str(), 1);
  r = run_cli({"validate", spec.string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("CROWDLAB_MPFB2") && Catch::Contains((out / "missing").string()));
  fs::create_directories(out / "empty");  // a folder without the assets: the run names the first file
  ::setenv("CROWDLAB_MPFB2", (out / "empty").c_str(), 1);
  r = run_cli({"-q", "run", spec.string(), "--out", (out / "run").string()});
  ::unsetenv("CROWDLAB_MPFB2");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("base.obj"));
}

}  // namespace test_body_model_pipeline
