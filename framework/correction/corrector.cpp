#include "framework/correction/corrector.hpp"

#include "framework/core/blend_poses.hpp"
#include "framework/correction/corrector_step.hpp"

namespace crowdlab {

Corrector::Corrector(std::vector<BodyShape> shapes, CorrectorParams params, Environment env, double fps)
    : model_(make_corrector_model(std::move(shapes), params, env, fps)),
      state_(make_corrector_state(model_)) {}

std::vector<Pose> Corrector::step(const std::vector<Pose>& targets) {
  if (model_.substeps == 1 || !state_.initialized) return corrector_step(model_, state_, targets);
  // Substeps (CorrectorParams::max_step_s): the targets move on a straight path from the last frame's,
  // and the frame's statistics say whether any substep was rejected or left CG unconverged.
  const std::vector<Pose> from = state_.target;
  if (targets.size() != from.size()) return corrector_step(model_, state_, targets);  // throws its error
  std::vector<Pose> between(targets.size());
  bool rejected = false, converged = true;
  for (int k = 1; k < model_.substeps; ++k) {
    const double w = static_cast<double>(k) / model_.substeps;
    for (size_t c = 0; c < targets.size(); ++c) between[c] = blend_poses(from[c], targets[c], w);
    corrector_step(model_, state_, between);
    rejected = rejected || state_.stats.rejected;
    converged = converged && state_.stats.converged;
  }
  std::vector<Pose> out = corrector_step(model_, state_, targets);
  state_.stats.rejected = state_.stats.rejected || rejected;
  state_.stats.converged = state_.stats.converged && converged;
  return out;
}

}  // namespace crowdlab
