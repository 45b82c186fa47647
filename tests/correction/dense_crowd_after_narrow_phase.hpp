#pragma once
// A dense swaying crowd's corrector (12 characters at 6.66 /m^2, swaying_crowd_fixture.hpp) stepped
// through 7 frames, then through the 8th frame's stages up to and including the narrow phase: the state
// the contact scope and the contact blocks start from. Shared by the tests of the stages after it.
#include <vector>

#include "framework/correction/corrector_step.hpp"
#include "framework/correction/swaying_crowd_fixture.hpp"

namespace crowdlab::test {

struct CorrectorAtNarrowPhase {
  CorrectorModel model;
  CorrectorState state;
};

inline CorrectorAtNarrowPhase dense_crowd_after_narrow_phase() {
  SwayingCrowdOptions o;
  o.characters = 12;
  o.density_per_m2 = 6.66;
  o.frames = 8;
  const CrowdAnimation crowd = make_swaying_crowd_fixture(o);
  std::vector<BodyShape> shapes;
  for (const auto& ch : crowd.characters) shapes.push_back(ch.shape);
  CorrectorAtNarrowPhase in{make_corrector_model(shapes, {}, {}, 30), {}};
  in.state = make_corrector_state(in.model);
  std::vector<Pose> targets(crowd.characters.size());
  auto frame = [&](int f) {
    for (size_t c = 0; c < targets.size(); ++c)
      targets[c] = crowd.characters[c].frames[static_cast<size_t>(f)];
    return targets;
  };
  for (int f = 0; f + 1 < o.frames; ++f) corrector_step(in.model, in.state, frame(f));
  stage_targets(in.model, in.state, frame(o.frames - 1));
  stage_assemble(in.model, in.state);
  stage_predict(in.model, in.state);
  stage_broad_phase(in.model, in.state);
  stage_narrow_phase(in.model, in.state);
  return in;
}

}  // namespace crowdlab::test
