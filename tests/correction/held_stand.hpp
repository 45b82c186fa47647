#pragma once
// Test-only fixture: one body standing still whose feet the corrector holds (two steps of a still input),
// shared by the foot-hold tests of test_correction_solver.cpp and test_feet_above_ground.cpp.
#include <algorithm>
#include <optional>

#include "framework/core/body_shape.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"
#include "framework/correction/corrector.hpp"
#include "framework/correction/corrector_step.hpp"

namespace crowdlab::test {

struct HeldStand {
  BodyShape shape = make_procedural_body({Sex::kMale, 1.75, 1.0});
  CorrectorModel model;
  CorrectorState state;
  Pose stand;  ///< the input: the rest pose, moved vertically when input_sole_m is given
};

/// The lower of the two soles (m) of `pose`.
inline double lower_sole_m(const BodyShape& shape, const Pose& pose) {
  const WorldCapsules caps = world_capsules(shape, pose);
  return std::min(foot_sole_height_m(caps, leg_joints(LegSide::kLeft)),
                  foot_sole_height_m(caps, leg_joints(LegSide::kRight)));
}

/// The body corrected with `params` for two steps of a still input, its feet held from then on; with
/// input_sole_m the input stands with its lower sole at that height.
inline HeldStand stand_with_held_feet(const CorrectorParams& params,
                                      std::optional<double> input_sole_m = std::nullopt) {
  HeldStand h;
  h.model = make_corrector_model({h.shape}, params, {}, 30);
  h.state = make_corrector_state(h.model);
  h.stand = Pose::rest(h.shape);
  if (input_sole_m) h.stand.root_position_m.y() += *input_sole_m - lower_sole_m(h.shape, h.stand);
  corrector_step(h.model, h.state, {h.stand});
  corrector_step(h.model, h.state, {h.stand});  // the feet are held from here on
  return h;
}

}  // namespace crowdlab::test
