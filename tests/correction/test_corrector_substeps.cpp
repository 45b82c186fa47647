// Substeps (CorrectorParams::max_step_s, issue 27, session 26): a clip under 30 fps is corrected in steps
// of at most 1/30 s, its targets interpolated between frames, so that the corrector tuned at 30 fps
// behaves at 15 fps as it does at 30.
#include <catch2/catch.hpp>

#include "framework/core/error.hpp"
#include "framework/core/joint_flips.hpp"
#include "framework/correction/correct_crowd.hpp"
#include "framework/correction/corrector.hpp"
#include "framework/correction/swaying_crowd_fixture.hpp"
#include "framework/metrics/correction_quality.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_corrector_substeps {

using namespace crowdlab;

TEST_CASE("corrector substeps: frames longer than 1/30 s are split into equal steps", "[correction]") {
  CHECK(substeps_per_frame(30.0, 1.0 / 30.0) == 1);
  CHECK(substeps_per_frame(60.0, 1.0 / 30.0) == 1);
  CHECK(substeps_per_frame(29.97, 1.0 / 30.0) == 1);  // within 1 % of the step
  CHECK(substeps_per_frame(25.0, 1.0 / 30.0) == 2);
  CHECK(substeps_per_frame(15.0, 1.0 / 30.0) == 2);
  CHECK(substeps_per_frame(10.0, 1.0 / 30.0) == 3);
  CHECK(substeps_per_frame(15.0, 1.0 / 15.0) == 1);

  const CrowdAnimation crowd = make_swaying_crowd_fixture({.characters = 2, .frames = 2, .fps = 15.0});
  std::vector<BodyShape> shapes = {crowd.characters[0].shape, crowd.characters[1].shape};
  const Corrector corrector(shapes, CorrectorParams{}, crowd.environment, 15.0);
  CHECK(corrector.model().substeps == 2);
  CHECK(corrector.model().h == Approx(1.0 / 30.0));
  CorrectorParams bad;
  bad.max_step_s = 0.0;
  CHECK_THROWS_AS(Corrector(shapes, bad, crowd.environment, 15.0), InputError);
}

TEST_CASE("corrector substeps: a dense crowd at 15 fps is corrected as well as at 30 fps", "[correction]") {
  // The same swaying motion sampled at 15 and at 30 fps, 6.66 /m^2, 2 s. Stepped once per frame, the
  // 15 fps clip's contacts are resolved one linearised step of 1/15 s at a time.
  SwayingCrowdOptions o{.characters = 16, .density_per_m2 = 6.66, .frames = 60, .fps = 30.0, .seed = 7};
  const CrowdAnimation at30 = make_swaying_crowd_fixture(o);
  o.frames = 30;
  o.fps = 15.0;
  const CrowdAnimation at15 = make_swaying_crowd_fixture(o);
  auto quality = [](const CrowdAnimation& in, const CorrectorParams& p) {
    return measure_correction_quality(in, correct_crowd(in, p), 0, 1, false);
  };
  const CorrectionQuality q30 = quality(at30, {});
  const CorrectionQuality q15 = quality(at15, {});
  CorrectorParams one_step;
  one_step.max_step_s = 1.0 / 15.0;
  const CorrectionQuality q15_one = quality(at15, one_step);
  INFO("p99 depth (mm) 30 fps " << 1e3 * q30.depth_p99_m << ", 15 fps " << 1e3 * q15.depth_p99_m
                                << ", 15 fps one step per frame " << 1e3 * q15_one.depth_p99_m);
  INFO("flips 30 fps " << q30.flips.count << ", 15 fps " << q15.flips.count << ", one step "
                       << q15_one.flips.count);
  CHECK(q15.depth_p99_m <= 1.5 * q30.depth_p99_m + 0.001);
  CHECK(q15.depth_p99_m < q15_one.depth_p99_m);
  CHECK(q15.flips.count <= q30.flips.count);
}

}  // namespace test_corrector_substeps
