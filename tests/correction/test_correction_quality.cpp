// Quality of the collision correction on small stationary crowds (issue 5 targets).
#include <catch2/catch.hpp>

#include "framework/correction/correct_crowd.hpp"
#include "framework/correction/swaying_crowd_fixture.hpp"
#include "tests/correction/correction_measures.hpp"
#include "tests/support/test_paths.hpp"

using namespace crowdlab;

TEST_CASE("probe: dense stationary crowd numbers", "[correction][probe]") {
  SwayingCrowdOptions o;
  o.characters = 16;
  o.density_per_m2 = 6.66;
  o.frames = 60;
  const CrowdAnimation in = make_swaying_crowd_fixture(o);
  CorrectionReport rep;
  const CrowdAnimation out = correct_crowd(in, CorrectorParams{}, nullptr, &rep);
  double vin = 0, vout = 0;
  std::vector<double> depths;
  for (int f = 30; f < 60; f += 5) {
    vin += test::overlap_volume(test::frame_capsules(in, f));
    vout += test::overlap_volume(test::frame_capsules(out, f));
    auto d = test::inter_body_depths(test::frame_capsules(out, f));
    depths.insert(depths.end(), d.begin(), d.end());
  }
  WARN("overlap in " << vin << " out " << vout << " p99 depth " << test::percentile(depths, 0.99)
                     << " mean dev " << test::mean_rotation_deviation_deg(in, out) << " skate "
                     << test::foot_skate_m(in, out) << " contacts " << rep.contacts_mean << " cg "
                     << rep.cg_iterations_mean << " rejected " << rep.rejected_steps << " unconv "
                     << rep.unconverged_steps);
}
