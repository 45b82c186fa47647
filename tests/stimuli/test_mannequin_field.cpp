// The mannequin field's narrow band (stimuli/mannequin_field.hpp, issue 31): the mesh and the samples it
// reads are the same bit for bit as evaluating every capsule at every point, and far points keep their sign.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <random>

#include "framework/core/forward_kinematics.hpp"
#include "stimuli/mannequin_field.hpp"
#include "stimuli/mannequin_mesh.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_mannequin_field {

using namespace crowdlab;
using namespace crowdlab::stimuli;

namespace {

bool same_vertex(const MannequinVertex& a, const MannequinVertex& b) {
  return a.position == b.position && a.normal == b.normal && a.bones == b.bones && a.weights == b.weights &&
         a.region == b.region;
}

/// 24 capsules at random: segments up to 40 cm long, radii 2-15 cm, in a 1 m box (overlapping, as a body's).
WorldCapsules random_capsules(std::mt19937& rng) {
  std::uniform_real_distribution<double> pos(-0.5, 0.5), len(-0.2, 0.2), radius(0.02, 0.15);
  WorldCapsules caps;
  for (Capsule& c : caps) {
    c.a = Vec3(pos(rng), pos(rng), pos(rng));
    c.b = c.a + Vec3(len(rng), len(rng), len(rng));
    c.radius_m = radius(rng);
  }
  return caps;
}

}  // namespace

TEST_CASE("mannequin mesh: the narrow band gives the mesh of every capsule at every point, bit for bit",
          "[stimuli]") {
  int meshes = 0;
  for (Sex sex : {Sex::kFemale, Sex::kMale})
    for (double height_m : {1.55, 1.9}) {
      const BodyShape shape = make_procedural_body({sex, height_m, sex == Sex::kFemale ? 0.85 : 1.25});
      for (double voxel_m : {test::kSanitized ? 0.04 : 0.02, 0.035})
        for (double inset_fraction : {0.0, 0.4}) {
          MannequinOptions options;
          options.voxel_m = voxel_m;
          options.inset_m = inset_fraction * voxel_m;
          options.blend_m = inset_fraction > 0 ? 0.05 : 0.03;
          const MannequinMesh fast = build_mannequin_mesh(shape, options, FieldSampling::kNarrowBand);
          const MannequinMesh every = build_mannequin_mesh(shape, options, FieldSampling::kEveryPoint);
          INFO("height " << height_m << " voxel " << voxel_m << " inset " << options.inset_m);
          REQUIRE(fast.vertices.size() == every.vertices.size());
          CHECK(fast.indices == every.indices);
          size_t differ = 0;
          for (size_t v = 0; v < fast.vertices.size(); ++v)
            differ += !same_vertex(fast.vertices[v], every.vertices[v]);
          CHECK(differ == 0);
          ++meshes;
        }
    }
  CHECK(meshes == 16);
}

TEST_CASE("mannequin field: narrow-band samples equal every-point samples near the surface, signs elsewhere",
          "[stimuli]") {
  const BodyShape shape = make_procedural_body({Sex::kMale, 1.8, 1.0});
  const WorldCapsules caps = world_capsules(shape, Pose::rest(shape));
  const MannequinField field(caps, 0.03);
  FieldGrid grid;
  grid.spacing_m = test::kSanitized ? 0.04 : 0.025;
  grid.lo = Vec3(-0.5, -0.1, -0.4);
  grid.nx = static_cast<int>(1.0 / grid.spacing_m);
  grid.ny = static_cast<int>(2.0 / grid.spacing_m);
  grid.nz = static_cast<int>(0.8 / grid.spacing_m);
  // Points within a cell diagonal of the level set can be corners of a crossed cell: their values are read.
  const double band = std::sqrt(3.0) * grid.spacing_m;
  REQUIRE(narrow_band_m(grid.spacing_m) >= band);
  for (double offset_m : {0.0, 0.01}) {
    const std::vector<float> every = sample_field(field, grid, offset_m, FieldSampling::kEveryPoint);
    const std::vector<float> fast = sample_field(field, grid, offset_m, FieldSampling::kNarrowBand);
    REQUIRE(fast.size() == every.size());
    size_t near = 0, bounded = 0, wrong = 0;
    for (size_t i = 0; i < every.size(); ++i) {
      if (static_cast<double>(std::abs(every[i])) <= band) {
        ++near;
        wrong += std::memcmp(&every[i], &fast[i], sizeof(float)) != 0;
      } else {
        wrong += (every[i] < 0.0f) != (fast[i] < 0.0f) || std::abs(fast[i]) < 0.5f * static_cast<float>(band);
        bounded += every[i] != fast[i];
      }
    }
    INFO("offset " << offset_m);
    CHECK(wrong == 0);
    CHECK(near > 1000);
    // The band pays: most points far from the surface store a bound, not an evaluated value.
    CHECK(bounded > every.size() / 2);
  }
}

TEST_CASE("mannequin field: the terms kept for a ball give the full minimum anywhere in it", "[stimuli]") {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), where(-0.7, 0.7);
  size_t checked = 0, wrong = 0, culled = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const WorldCapsules caps = random_capsules(rng);
    const MannequinField field(caps, trial % 2 ? 0.03 : 0.12);
    for (int ball = 0; ball < 20; ++ball) {
      const Vec3 centre(where(rng), where(rng), where(rng));
      const double rho_m = 0.01 + 0.05 * (unit(rng) + 1.0);
      std::array<double, kJointCount> s;
      field.distances(centre, s);
      const MannequinField::BallBounds bounds = field.bounds_in_ball(s, rho_m);
      culled += bounds.terms.term_count < kJointCount;
      for (int k = 0; k < 25; ++k) {
        Vec3 offset(unit(rng), unit(rng), unit(rng));
        if (offset.norm() > 1.0) offset /= offset.norm();
        const Vec3 p = centre + rho_m * offset;
        const double full = field.value(p);
        wrong += full != field.value(p, bounds.terms) || full < bounds.lower || full > bounds.upper;
        ++checked;
      }
    }
  }
  CHECK(checked == 40 * 20 * 25);
  CHECK(wrong == 0);
  CHECK(culled > 400);  // the bounds leave terms out in most balls
}

}  // namespace test_mannequin_field
