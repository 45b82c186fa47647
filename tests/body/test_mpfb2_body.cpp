// MPFB2 body model on the assets shipped in framework/body/assets/mpfb2.
#include <zlib.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <numbers>
#include <utility>

#include "framework/body/mpfb2_body.hpp"
#include "framework/body/mpfb2_model.hpp"
#include "framework/body/sample_mpfb2_bodies.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/mpfb2_asset_dir.hpp"
#include "framework/core/seed.hpp"
#include "framework/metrics/overlap_volume.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_mpfb2_body {

using namespace crowdlab;

namespace {

std::shared_ptr<const Mpfb2Model> model_or_skip() {
  static const std::shared_ptr<const Mpfb2Model> model = Mpfb2Model::load(shipped_mpfb2_dir());
  return model;
}

double body_height_from_mesh(const Mpfb2Model& model, const Mpfb2ShapeParams& p) {
  const std::vector<Vec3> v = shaped_vertices_dm(model, p);
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (int i : model.body_vertices()) {
    lo = std::min(lo, v[static_cast<size_t>(i)].y());
    hi = std::max(hi, v[static_cast<size_t>(i)].y());
  }
  return 0.1 * (hi - lo);
}

}  // namespace

TEST_CASE("MPFB2 assets load, the base mesh body is a plausible adult height") {
  const auto model = model_or_skip();
  if (!model) return;
  CHECK(model->body_vertices().size() > 10000);
  CHECK(model->body_vertices().size() < model->base().vertices.size());  // helpers dropped
  CHECK(model->bones().size() == 52);
  // Base mesh, no targets, decimetres -> metres.
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (int i : model->body_vertices()) {
    lo = std::min(lo, model->base().vertices[static_cast<size_t>(i)].y());
    hi = std::max(hi, model->base().vertices[static_cast<size_t>(i)].y());
  }
  const double base_height = 0.1 * (hi - lo);
  INFO("base mesh body height " << base_height << " m");
  CHECK(base_height > 1.60);
  CHECK(base_height < 1.80);
}

TEST_CASE("macro target weights interpolate as macro.json says") {
  const auto model = model_or_skip();
  if (!model) return;
  Mpfb2ShapeParams p;
  p.gender = 0.3;
  p.age = 0.75;
  p.muscle = 0.75;
  p.weight = 0.5;
  p.height = 0.25;
  std::map<std::string, double> w;
  for (const auto& [name, weight] : macro_target_weights(*model, p)) w[name] = weight;
  // universal: female 0.7 / male 0.3 x young 0.5 / old 0.5 x avg 0.5 / max 0.5 muscle x avg weight.
  CHECK(w["universal-female-young-averagemuscle-averageweight"] == Approx(0.7 * 0.5 * 0.5));
  CHECK(w["universal-male-old-maxmuscle-averageweight"] == Approx(0.3 * 0.5 * 0.5));
  double universal = 0.0;
  for (const auto& [name, weight] : w)
    if (name.rfind("universal-", 0) == 0) universal += weight;
  CHECK(universal == Approx(1.0));
  // height 0.25: minheight at weight 0.5, no maxheight.
  CHECK(w["height/female-young-averagemuscle-averageweight-minheight"] == Approx(0.7 * 0.5 * 0.5 * 0.5));
  CHECK(w.count("height/female-young-averagemuscle-averageweight-maxheight") == 0);
  // proportions 0.5: none.
  for (const auto& [name, weight] : w) CHECK(name.rfind("proportions/", 0) != 0);
  p.age = 0.3;  // children's targets are not shipped
  CHECK_THROWS_AS(macro_target_weights(*model, p), InputError);
}

TEST_CASE("an MPFB2 body: T-pose skeleton on the shaped mesh, LBS rest identity, capsule volume") {
  const auto model = model_or_skip();
  if (!model) return;
  Mpfb2ShapeParams p;
  p.gender = 1.0;
  const Mpfb2Body body = make_mpfb2_body(*model, p);
  INFO("height " << body.height_m);
  CHECK(body.height_m > 1.65);
  CHECK(body.height_m < 1.85);
  CHECK(body.height_m == Approx(body_height_from_mesh(*model, p)).margin(1e-12));
  const auto& j = body.mesh.rest_joints_m;
  // T-pose: arm joints level with the shoulder, left (+X) and right (-X); legs straight down.
  for (int side : {0, 1}) {
    const double x = side == 0 ? 1 : -1;
    const int sh = side == 0 ? kLeftShoulder : kRightShoulder;
    for (int k : {side == 0 ? kLeftElbow : kRightElbow, side == 0 ? kLeftWrist : kRightWrist,
                  side == 0 ? kLeftHand : kRightHand}) {
      CHECK(j[static_cast<size_t>(k)].y() == Approx(j[static_cast<size_t>(sh)].y()).margin(1e-9));
      CHECK(x * (j[static_cast<size_t>(k)].x() - j[static_cast<size_t>(sh)].x()) > 0.1);
    }
    const int hip = side == 0 ? kLeftHip : kRightHip, ankle = side == 0 ? kLeftAnkle : kRightAnkle;
    CHECK(j[static_cast<size_t>(ankle)].x() == Approx(j[static_cast<size_t>(hip)].x()).margin(1e-9));
    CHECK(x * j[static_cast<size_t>(hip)].x() > 0.05);
  }
  CHECK(j[kHead].y() > j[kNeck].y());
  CHECK(j[kPelvis].y() / body.height_m == Approx(0.56).margin(0.05));  // pelvis near 0.53-0.6 of stature
  // Feet on the ground, pelvis above the origin.
  double min_y = HUGE_VAL;
  for (const Vec3& v : body.mesh.rest_vertices_m) min_y = std::min(min_y, v.y());
  CHECK(min_y == Approx(0.0).margin(1e-12));
  CHECK(j[kPelvis].x() == Approx(0.0).margin(1e-12));
  // FK of the rest pose reproduces the rest joints, and LBS the rest vertices.
  const BoneTransforms bones = forward_kinematics(body.shape, Pose::rest(body.shape));
  for (int k = 0; k < kJointCount; ++k)
    CHECK((bones[static_cast<size_t>(k)].translation - j[static_cast<size_t>(k)]).norm() < 1e-9);
  const std::vector<Vec3> skinned = skin_vertices(body.mesh, bones);
  double worst = 0.0;
  for (size_t i = 0; i < skinned.size(); ++i)
    worst = std::max(worst, (skinned[i] - body.mesh.rest_vertices_m[i]).norm());
  CHECK(worst < 1e-9);
  for (const auto& w : body.mesh.weights) CHECK(w[0] + w[1] + w[2] + w[3] == Approx(1.0));
  // Turning the root turns every vertex rigidly.
  Pose turned = Pose::rest(body.shape);
  turned.local_rotations[kPelvis] = Quat(Eigen::AngleAxisd(0.7, Vec3::UnitY()));
  const std::vector<Vec3> rotated = skin_vertices(body.mesh, forward_kinematics(body.shape, turned));
  const Vec3 pivot = j[kPelvis];
  for (size_t i = 0; i < rotated.size(); i += 97)
    CHECK((rotated[i] - (turned.local_rotations[kPelvis] * (body.mesh.rest_vertices_m[i] - pivot) + pivot))
              .norm() < 1e-9);
  // Capsules together approximate the mesh volume (union measured with the overlap integrator:
  // vol(A ∩ A) = vol(A)).
  const WorldCapsules caps = world_capsules(body.shape, Pose::rest(body.shape));
  const std::vector<Capsule> list(caps.begin(), caps.end());
  const double union_l = 1000.0 * overlap_volume(list, list).volume_m3;
  const double mesh_l = 1000.0 * mesh_volume(body.mesh.rest_vertices_m, body.mesh.triangles);
  INFO("capsule union " << union_l << " L, mesh " << mesh_l << " L");
  CHECK(mesh_l > 50.0);
  CHECK(mesh_l < 90.0);
  CHECK(std::abs(union_l - mesh_l) < 0.15 * mesh_l);
  CHECK(body.shape.rest_contact_pairs.size() >= 23);  // at least every parent-child pair touches
}

TEST_CASE("height grows with the height macro and men are taller than women at equal settings") {
  const auto model = model_or_skip();
  if (!model) return;
  for (double gender : {0.0, 1.0}) {
    Mpfb2ShapeParams p;
    p.gender = gender;
    double previous = 0.0;
    for (double h = 0.0; h <= 1.0; h += 0.125) {
      p.height = h;
      const double height = measure_mpfb2_height(*model, p);
      CHECK(height > previous);
      previous = height;
    }
  }
  Mpfb2ShapeParams f, m;
  f.gender = 0.0;
  m.gender = 1.0;
  CHECK(measure_mpfb2_height(*model, m) > measure_mpfb2_height(*model, f) + 0.05);
}

TEST_CASE("sampled bodies reach their target heights, by sex, measured on the shaped meshes") {
  const auto model = model_or_skip();
  if (!model) return;
  const int n = test::kSanitized ? 2 : 4;
  const std::vector<Mpfb2Sample> a = sample_mpfb2_bodies(*model, n, 42);
  const std::vector<Mpfb2Sample> b = sample_mpfb2_bodies(*model, n, 42);  // built in parallel again
  for (int i = 0; i < n; ++i) {
    CHECK(a[static_cast<size_t>(i)].body.params.height == b[static_cast<size_t>(i)].body.params.height);
    CHECK(a[static_cast<size_t>(i)].body.mesh.rest_vertices_m ==
          b[static_cast<size_t>(i)].body.mesh.rest_vertices_m);
  }
  std::array<double, 2> sum{};
  std::array<int, 2> count{};
  const std::vector<Sex> sexes = sample_sexes(n, 0.5, 42);  // the procedural bodies' assignment
  for (int i = 0; i < n; ++i) {
    const Mpfb2Sample& s = a[static_cast<size_t>(i)];
    const bool female = sexes[static_cast<size_t>(i)] == Sex::kFemale;
    CHECK(s.body.shape.params.sex == (female ? Sex::kFemale : Sex::kMale));
    const double measured = body_height_from_mesh(*model, s.body.params);
    INFO("body " << i << " target " << s.target_height_m << " measured " << measured);
    REQUIRE(s.target_reached);
    CHECK(measured == Approx(s.target_height_m).margin(0.001));
    sum[female ? 0 : 1] += measured;
    ++count[female ? 0 : 1];
  }
  // Sample means within 4 standard errors of the distributions' means.
  REQUIRE(count[0] == n / 2);
  CHECK(std::abs(sum[0] / count[0] - kWorldFemaleHeight.mean_m) <
        4 * kWorldFemaleHeight.sd_m / std::sqrt(count[0]));
  CHECK(std::abs(sum[1] / count[1] - kWorldMaleHeight.mean_m) <
        4 * kWorldMaleHeight.sd_m / std::sqrt(count[1]));
}

TEST_CASE("bad MPFB2 input gives clear errors") {
  CHECK_THROWS_AS(Mpfb2Model::load("/nonexistent/mpfb2"), InputError);
  const auto dir = test::scratch_dir("mpfb2-bad");
  const auto bad = dir / "bad.target.gz";
  {
    gzFile f = gzopen(bad.string().c_str(), "wb");
    gzputs(f, "5 0.1 0.2 0.3\n7 0.1 0.2\n");
    gzclose(f);
  }
  try {
    read_target_gz(bad, 100);
    FAIL("expected InputError");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("bad.target.gz:2") != std::string::npos);
  }
  {
    std::ofstream out(dir / "bad.obj");
    out << "v 0 0 0\nv 1 0 0\nf 1 2 9\n";
  }
  CHECK_THROWS_AS(read_obj(dir / "bad.obj"), InputError);
}

TEST_CASE("the height solver reproduces a Gaussian height distribution by sex on the shaped meshes") {
  const auto model = model_or_skip();
  if (!model) return;
  const int per_sex = test::kSanitized ? 3 : 15;
  for (const bool female : {true, false}) {
    const HeightDistribution d = female ? kWorldFemaleHeight : kWorldMaleHeight;
    Rng rng(derive_seed(9, female ? "f" : "m"));
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < per_sex; ++i) {
      const double target = d.mean_m + d.sd_m * standard_normal(rng);
      Mpfb2ShapeParams p;
      p.gender = female ? 0.0 : 1.0;
      bool reached = false;
      p.height = solve_height_param(*model, p, target, reached);
      REQUIRE(reached);
      const double measured = body_height_from_mesh(*model, p);
      CHECK(measured == Approx(target).margin(0.001));
      sum += measured;
      sum2 += measured * measured;
    }
    const double mean = sum / per_sex, sd = std::sqrt(std::max(0.0, sum2 / per_sex - mean * mean));
    INFO((female ? "women" : "men") << ": mean " << mean << " sd " << sd);
    CHECK(std::abs(mean - d.mean_m) < 4 * d.sd_m / std::sqrt(per_sex));
    if (!test::kSanitized) CHECK(sd == Approx(d.sd_m).epsilon(0.6));
  }
}

TEST_CASE("each MPFB2 capsule carries the volume of its body part, for sampled shapes") {
  // Property (mpfb2_body.hpp, "Capsules"): a bone ending at the surface has a capsule whose whole
  // volume is its part's; a joint-to-joint bone has a cylinder pi r^2 L equal to its part's, so its
  // capsule exceeds the part by exactly the two caps' sphere 4/3 pi r^3. The part volumes are measured
  // again from the finished body (the capsule axis line, the rest mesh and its weights). Tolerance 1e-9
  // relative: the radius is bisected to 0.5 m / 2^60, and re-deriving the axis from the stored capsule
  // moves the volume by rounding only (~1e-14 relative); a part given to the wrong bone, a radius from
  // the wrong formula or a mesh changed after fitting would be off by percents.
  const auto model = model_or_skip();
  if (!model) return;
  for (const auto& [gender, height] : {std::pair{0.0, 0.2}, std::pair{1.0, 0.8}, std::pair{0.5, 0.5}}) {
    Mpfb2ShapeParams p;
    p.gender = gender;
    p.height = height;
    const Mpfb2Body body = make_mpfb2_body(*model, p);
    std::array<Vec3, kJointCount> point{}, dir{};
    for (size_t j = 0; j < kJointCount; ++j) {
      const Capsule& c = body.shape.capsules[j];
      point[j] = body.mesh.rest_joints_m[j] + c.a;
      dir[j] = (c.b - c.a).normalized();
    }
    const std::array<double, kJointCount> part = body_part_volumes_m3(body.mesh, point, dir);
    for (int j = 0; j < kJointCount; ++j) {
      const Capsule& c = body.shape.capsules[static_cast<size_t>(j)];
      const double v = part[static_cast<size_t>(j)];
      const double sphere = 4.0 / 3.0 * std::numbers::pi * std::pow(c.radius_m, 3);
      INFO("gender " << gender << " height " << height << " joint " << joint_name(j) << ": part " << v
                     << " m^3, capsule " << c.volume_m3() << " m^3, r " << c.radius_m);
      REQUIRE(v > 0.0);
      if (mpfb2_bone_ends_at_surface(j)) {
        CHECK(c.volume_m3() == Approx(v).epsilon(1e-9));
      } else {
        CHECK(std::numbers::pi * c.radius_m * c.radius_m * c.length_m() == Approx(v).epsilon(1e-9));
        CHECK(c.volume_m3() - v == Approx(sphere).epsilon(1e-6));
      }
    }
  }
}

TEST_CASE("a gzip target that inflates past its vertex count's bound is refused while inflating") {
  // Issue 32: a 2.2 MB .target.gz inflating to gigabytes took 4.4 GB and 71 s in `run`. Small versions:
  // comments past the byte bound, and more entries than vertices.
  const auto dir = test::scratch_dir("mpfb2-gzip-bomb");
  const auto comments = dir / "comments.target.gz";
  {
    gzFile f = gzopen(comments.string().c_str(), "wb9");
    const std::string line = "#" + std::string(126, 'x') + "\n";
    for (int i = 0; i < 20000; ++i) gzputs(f, line.c_str());  // 2.5 MB of text, a few kB compressed
    gzclose(f);
  }
  CHECK(std::filesystem::file_size(comments) < 100000);
  CHECK_THROWS_WITH(read_target_gz(comments, 100), Catch::Contains("comments.target.gz:") &&
                                                       Catch::Contains("inflates past 1061376 bytes") &&
                                                       Catch::Contains("100 vertices"));
  const auto entries = dir / "entries.target.gz";
  {
    gzFile f = gzopen(entries.string().c_str(), "wb");
    for (int i = 0; i < 300; ++i) gzputs(f, (std::to_string(i % 100) + " 0.1 0.2 0.3\n").c_str());
    gzclose(f);
  }
  CHECK_THROWS_WITH(read_target_gz(entries, 100), Catch::Contains("entries.target.gz:102"));
}

}  // namespace test_mpfb2_body
