// ObserverModel::judge_by_volume: observers who answer the collision question from the clip's volume even
// when it has a distance factor (how `reproduce hoyet2016` recovers V_crit from known thresholds).
#include <catch2/catch.hpp>

#include "framework/core/error.hpp"
#include "study_ui/simulated_observer.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_judge_by_volume {

using namespace crowdlab;
using namespace crowdlab::study;

TEST_CASE("simulated observers: judge_by_volume switches the collision answer to V_i", "[study]") {
  ObserverModel model;
  const Observer o = draw_observer(model, 11);
  StimulusEntry s;
  s.factors = {{"shoulder", "1"}, {"distance", "0.20"}};  // far below D_crit: a collision by distance
  s.v_i_m = 0.0;                                          // but no interpenetration at all
  CHECK(collision_probability(o, s) > 0.95);
  CHECK(collision_probability(o, s, true) < 0.05);
  // At the observer's own V_crit the answer is a coin flip, whatever the distance.
  s.v_i_m = o.v_crit_m.at("1");
  CHECK(collision_probability(o, s, true) == Approx(0.5).margin(1e-9));
  // Without a volume, the distance still decides.
  s.v_i_m = -1.0;
  CHECK(collision_probability(o, s, true) > 0.95);
  model.set("judge_by_volume=1");
  CHECK(model.judge_by_volume);
  model.set("judge_by_volume=0");
  CHECK_FALSE(model.judge_by_volume);
  CHECK_THROWS_AS(model.set("judge_by_volume=0.5"), InputError);
}

}  // namespace test_judge_by_volume
